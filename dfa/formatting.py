"""Number formatting and tables for everything ``dfa`` prints or writes (one implementation each).

:func:`number` formats a value for people (significant digits, a mark for "none" and for infinity);
:func:`text_table` aligns columns for the terminal; :func:`markdown_table` writes a Markdown (GFM) table.
Pure string functions: no numerics, no I/O.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

__all__ = [
    "WIDTH",
    "fill",
    "markdown_table",
    "number",
    "number_at",
    "percent",
    "round_at",
    "text_table",
    "uncertainty_place",
]

#: Longest line of the default text output, characters: under 100 (the answer fits one screen).
WIDTH = 99


def number(x: float | int | None, digits: int = 4, *, none: str = "–", inf: str = "∞") -> str:
    """``x`` with ``digits`` significant digits (``%g``); ``none`` for None and ``inf`` for ±infinity.

    Parameters
    ----------
    x : float, int or None
        The value (any unit: the caller writes the unit).
    digits : int
        Significant digits (default 4).
    none, inf : str
        Text for a missing value and for infinity (the terminal uses "-" and "inf", documents "–" and "∞").

    Returns
    -------
    str

    Examples
    --------
    >>> number(641.1312, 5), number(None), number(float("inf")), number(None, none="-")
    ('641.13', '–', '∞', '-')
    >>> number(-float("inf"), inf="inf")
    '-inf'
    """
    if x is None:
        return none
    if isinstance(x, float) and math.isinf(x):
        return ("-" if x < 0 else "") + inf
    return f"{x:.{digits}g}"


def percent(x: float | None, digits: int = 2, *, none: str = "–") -> str:
    """A fraction as a percentage with ``digits`` significant digits (``0.0123`` → ``'1.2 %'``).

    Examples
    --------
    >>> percent(0.006552), percent(None), percent(float("nan"))
    ('0.66 %', '–', '–')
    """
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return none
    return f"{100 * x:.{digits}g} %"


def _cell(x: object) -> str:
    return str(x).replace("|", "\\|")  # a literal | would end the cell


def markdown_table(header: Sequence[object], rows: Sequence[Sequence[object]], align: str | None = None) -> str:
    """A Markdown (GFM) table; ``|`` inside cells is escaped.

    Parameters
    ----------
    header : sequence
        Column titles.
    rows : sequence of sequences
        Cells (converted with ``str``), as many per row as there are titles.
    align : str, optional
        One letter per column, ``l`` (left, the default) or ``r`` (right).

    Returns
    -------
    str
        The table, one line per row, no trailing newline.

    Examples
    --------
    >>> print(markdown_table(["a", "b"], [[1, "x|y"]], align="lr"))
    | a | b |
    |---|---:|
    | 1 | x\\|y |
    """
    rule = {"l": "---", "r": "---:"}
    spec = align or "l" * len(header)
    lines = ["| " + " | ".join(_cell(h) for h in header) + " |", "|" + "|".join(rule[a] for a in spec) + "|"]
    lines += ["| " + " | ".join(_cell(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def text_table(rows: Sequence[Sequence[object]], header: Sequence[str] | None = None, width: int | None = None) -> str:
    """Columns aligned with two spaces for the terminal; a dashed rule under the header (none under an empty one).

    With ``width``, a last cell that would make its line longer is wrapped, its continuation lines indented
    to the last column (the other columns are never wrapped).

    Examples
    --------
    >>> print(text_table([["β", 0.5], ["σ", 12]], ["name", "value"]))
    name  value
    ----  -----
    β     0.5
    σ     12
    >>> print(text_table([["far", 2250, "◀ limiting"], ["near", 1125, ""]], ["pose", "μ", ""]))
    pose  μ
    ----  ----
    far   2250  ◀ limiting
    near  1125
    >>> print(text_table([["verdict", "no passivity guarantee at this speed"]], width=30))
    verdict  no passivity
             guarantee at this
             speed
    """
    cells = [[str(c) for c in r] for r in ([header] if header else []) + list(rows)]
    widths = [max(len(r[i]) for r in cells) for i in range(len(cells[0]))]
    lead = sum(widths[:-1]) + 2 * (len(widths) - 1)
    room = None if width is None else max(width - lead, 20)
    if room is not None and widths[-1] > room:
        cells = [[*r[:-1], *_wrapped(r[-1], room)] for r in cells]
        widths[-1] = max(len(line) for r in cells for line in r[-1].split("\n"))
    lines = []
    for r in cells:
        first, *more = r[-1].split("\n")
        lines.append("  ".join(c.ljust(w) for c, w in zip([*r[:-1], first], widths, strict=False)).rstrip())
        lines += [" " * lead + m for m in more]
    if header:
        rule = ["-" if str(h).strip() else " " for h in header]
        lines.insert(1, "  ".join(r * w for r, w in zip(rule, widths, strict=True)).rstrip())
    return "\n".join(lines)


#: Stands for the space before a percent sign while a line is wrapped: "0.5 %" is never split ("%" alone).
_BOUND = "\x00"


def _wrapped(text: str, room: int) -> list[str]:
    """``text`` in lines of at most ``room`` characters, joined by newlines (one cell)."""
    import textwrap

    lines = textwrap.wrap(text.replace(" %", _BOUND + "%"), room, break_on_hyphens=False)
    return ["\n".join(lines).replace(_BOUND, " ") or text]


def fill(text: str, width: int = WIDTH, indent: str = "  ") -> str:
    """Each line of ``text`` wrapped at ``width`` characters, continuation lines indented by ``indent``.

    Examples
    --------
    >>> print(fill("a b c d e f", width=5))
    a b c
      d e
      f
    >>> print(fill("steps of 0.5 %", width=12))  # a percent sign stays with its number
    steps of
      0.5 %
    """
    import textwrap

    out = [textwrap.fill(line.replace(" %", _BOUND + "%"), width, subsequent_indent=indent,
                         break_on_hyphens=False).replace(_BOUND, " ") if len(line) > width
           else line for line in text.split("\n")]  # fmt: skip
    return "\n".join(out)


def uncertainty_place(half_width: float | None) -> int | None:
    """Exponent k of the last meaningful decimal place 10^k of a value known to ± ``half_width``.

    One significant digit of the half-width, two when it starts with 10 to 35 (the Particle Data Group's rule:
    ± 0.0078 gives 10^-3, ± 0.0024 gives 10^-4). A digit below it moves with the last bits of the computation
    (an optimizer's stopping point, another CPU): printing it would be printing noise. None for a half-width that
    is missing, zero or not finite.

    Examples
    --------
    >>> uncertainty_place(0.0078), uncertainty_place(0.0024), uncertainty_place(36.0), uncertainty_place(None)
    (-3, -4, 1, None)
    """
    if half_width is None or not (math.isfinite(half_width) and half_width > 0.0):
        return None
    mantissa, exponent = f"{half_width:.2e}".split("e")
    return int(exponent) - (1 if float(mantissa) < 3.55 else 0)


def round_at(x: float, place: int, mode: str = "nearest") -> float:
    """``x`` rounded at the decimal place 10^``place``: ``"nearest"`` (half to even), ``"down"`` or ``"up"``.

    The result is the float nearest to a short decimal, the same on every machine for the same digits (exact
    decimal arithmetic, no float division). A value with more than 17 significant digits above that place is
    returned unchanged.

    Examples
    --------
    >>> round_at(0.0197704, -4, "down"), round_at(0.0213271, -4, "up"), round_at(-2e-9, -6)
    (0.0197, 0.0214, 0.0)
    """
    from decimal import ROUND_CEILING, ROUND_FLOOR, ROUND_HALF_EVEN, Decimal

    rounding = {"nearest": ROUND_HALF_EVEN, "down": ROUND_FLOOR, "up": ROUND_CEILING}[mode]
    d = Decimal(repr(float(x)))
    if not d.is_finite() or (d != 0 and d.adjusted() - place > 17):
        return float(x)
    return float(d.quantize(Decimal(f"1e{place}"), rounding=rounding)) + 0.0  # + 0.0: no -0


def number_at(x: float, place: int, mode: str = "nearest", *, scientific: bool = False) -> str:
    """``x`` rounded at the decimal place 10^``place`` (:func:`round_at`), its trailing zeros kept.

    ``scientific`` writes it with an exponent (to print the ends of an interval alike).

    Examples
    --------
    >>> number_at(0.0090123, -4), number_at(6.4632e-05, -6), number_at(9.92e-05, -6, "up", scientific=True)
    ('0.0090', '6.5e-05', '1.00e-04')
    >>> number_at(7.17e-08, -7), number_at(-3e-9, -6), number_at(1234.5, 1)
    ('1e-07', '0', '1230')
    """
    from decimal import Decimal

    q = round_at(x, place, mode)
    if q == 0.0:
        return "0"
    digits = max(1, Decimal(repr(q)).adjusted() - place + 1)
    if scientific:
        text = f"{q:.{digits - 1}e}"
    else:
        text = f"{q:.0f}" if place >= 0 else f"{q:#.{digits}g}"
    return text.replace(".e", "e").rstrip(".")
