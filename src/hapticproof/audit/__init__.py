"""Auditing printed equations: the LaTeX reader, the registry of papers, paper files and
declarative claims, comparisons of printed and derived results, mutation testing, the runner."""
