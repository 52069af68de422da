"""``.. clihelp:: COMMAND [SYSTEM]``: the ``--help`` of a hapticproof command, generated at build time
from the command line's own parser (so the reference cannot drift from the program)."""

from __future__ import annotations

from docutils import nodes
from sphinx.util.docutils import SphinxDirective


class CliHelp(SphinxDirective):
    required_arguments = 0
    optional_arguments = 2

    def run(self) -> list[nodes.Node]:
        from hapticproof.cli import help_text

        text = help_text(*self.arguments)
        block = nodes.literal_block(text, text)
        block["language"] = "text"
        return [block]


def setup(app):
    app.add_directive("clihelp", CliHelp)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
