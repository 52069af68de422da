"""Views of findings and derivations: LaTeX, HTML, readable text, summaries, exports, figures."""
