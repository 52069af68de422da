"""The reader of printed LaTeX: the papers' loose dialect into SymPy, driven by a symbol table.

Layered like a compiler front end: :mod:`~hapticproof.audit.reader.lexer` (tokens and delimiters),
:mod:`~hapticproof.audit.reader.names` (names and the symbol table: the semantics of a name),
:mod:`~hapticproof.audit.reader.statements` (what a display reads as), the grammar
(:mod:`~hapticproof.audit.reader.grammar` with the rules for names and for constructs in
:mod:`~hapticproof.audit.reader.namerules` and :mod:`~hapticproof.audit.reader.constructs`), and
:mod:`~hapticproof.audit.reader.printed`, the entry point (:func:`parse_printed`).
"""
