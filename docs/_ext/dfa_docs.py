"""Sphinx extension of the dfa site: plain console commands and console blocks that wrap instead of being cut.

Pygments' own ``console`` lexer highlights the command after ``$`` as Bash: a number in ``--velocity 0.1`` came out
coloured, and only in part (``0`` coloured, ``.1`` not). Here a console block is a prompt, a plain command (with
its ``\\``-continued lines) and the program's output, nothing else; ``dfa.css`` wraps its long lines.
"""

from __future__ import annotations

from typing import Any

from pygments.lexer import RegexLexer, bygroups
from pygments.token import Generic, Text

__all__ = ["ConsoleLexer", "setup"]


class ConsoleLexer(RegexLexer):
    """A shell session: ``$ `` a prompt, the command plain text to its end (and its ``\\`` continuations), every
    other line the program's output."""

    name = "dfa console"
    aliases = ["console"]
    tokens = {
        "root": [  # every pattern consumes at least one character: an empty match would never advance
            (r"^(\$ )(.*\\\n)", bygroups(Generic.Prompt, Text), "continued"),
            (r"^(\$ )(.*\n?)", bygroups(Generic.Prompt, Text)),
            (r".+\n?|\n", Generic.Output),
        ],
        "continued": [
            (r".*\\\n", Text),
            (r".+\n?|\n", Text, "#pop"),
        ],
    }


def setup(app: Any) -> dict[str, Any]:
    """Register the console lexer (for ``console`` blocks) and the site's style sheet ``_static/dfa.css``."""
    app.add_lexer("console", ConsoleLexer)
    app.add_css_file("dfa.css")
    return {"parallel_read_safe": True, "parallel_write_safe": True}
