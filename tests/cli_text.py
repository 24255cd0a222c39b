"""Reading the command line's text output in tests: lines wrapped at 100 characters joined back (dfa.cli.output)."""


def unwrap(text: str) -> str:
    """``text`` with each wrapped line whole again: a line that starts with blanks continues the one before."""
    out: list[str] = []
    for line in text.splitlines():
        if out and line[:1] == " " and line.strip():
            out[-1] = f"{out[-1].rstrip()} {line.strip()}"
        else:
            out.append(line)
    return "\n".join(out) + ("\n" if text.endswith("\n") else "")
