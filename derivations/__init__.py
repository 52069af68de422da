"""Registered papers: each module holds one paper's printed equations, verbatim, and how to
derive and audit each of them (see :mod:`hapticproof.audit.runner`)."""
