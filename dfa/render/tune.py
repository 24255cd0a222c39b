"""A tuning in words: the table of the best walls, the plain one first, and the wall chosen (``dfa tune``).

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.wall import Wall
>>> dev = get_device("impulse").device
>>> wall_label(Wall.of(1.0, damping=2.0, filter_cutoff=50.0), dev, dev.units)
'B 2 N·s/m, filter 50 Hz'
>>> wall_label(Wall(1.0), dev, dev.units)
'spring'
"""

from __future__ import annotations

from ..formatting import number, text_table
from ..model.device import Device
from ..model.elements import Damper, Delay, PassivityController, VelocityFilter
from ..model.wall import Wall
from ..results.status import RecommendRule, TunedStatus, TuneStatus
from ..results.tune import TunedWall, TuneResult, within_cap
from .answer import recommendation_text, wrap

__all__ = [
    "best_text",
    "export_command",
    "wall_label",
    "wall_flags",
    "tune_rows",
    "tune_screen",
    "command_lines",
    "TUNE_HEADER",
]

#: The columns of the tuning's table.
TUNE_HEADER = ["", "wall", "K", "rule", "at K", "rests to K", "force error", "PC acts"]

_RULES = {
    RecommendRule.PROVEN: "proven",
    RecommendRule.SIMULATED: "sim. / margin",
    RecommendRule.SIMULATED_RANGE: "range / margin",
    RecommendRule.NONE: "none",
}


def wall_label(wall: Wall, device: Device, units: dict[str, str], period: float | None = None) -> str:
    """The tuned elements of a wall in a few words (the others are the tuning's, the same in every row); the sample
    period when it is not ``period``."""
    parts = []
    if device.period != period and period is not None:
        parts.append(f"T {number(device.period * 1e3, 4)} ms")
    d = wall.element(Delay)
    if d is not None:
        parts.append(f"delay {d.delay}")
    b = wall.element(Damper)
    if b is not None:
        parts.append(f"B {number(b.damping, 4)} {units['damping']}")
    f = wall.element(VelocityFilter)
    if f is not None:
        parts.append(f"filter {number(f.filter_cutoff, 4)} Hz")
    pc = wall.element(PassivityController)
    if pc is not None:
        limit = "no limit" if pc.force_limit is None else f"{number(pc.force_limit, 4)} {units['force']}"
        parts.append(f"PC {limit}")
    return ", ".join(parts) if parts else "spring"


def wall_flags(tuned: TunedWall, device: Device) -> list[str]:
    """A tuned wall's varied elements as command-line flags (each element's own flag; ``repr``: the exact doubles),
    with ``--period`` where it runs at another period than ``device``'s.

    Examples
    --------
    >>> from dfa.model.catalogue import get_device
    >>> dev = get_device("impulse").device
    >>> wall_flags(TunedWall(dev, Wall.of(1.0, damping=2.0, delay=1), 100.0), dev)
    ['--delay', '1', '--virtual-damping', '2.0']
    """
    w, out = tuned.wall, []
    if tuned.device.period != device.period:
        out += ["--period", repr(tuned.device.period)]
    for kind, attr in ((Delay, "delay"), (Damper, "damping"), (VelocityFilter, "filter_cutoff")):
        e = w.element(kind)
        if e is not None:
            out += [kind.parameter.flag, repr(getattr(e, attr))]
    pc = w.element(PassivityController)
    if pc is not None:
        switch, window, limit = (row.flag for row in PassivityController.flag_rows())
        out.append(switch)
        out += [] if pc.window is None else [window, repr(pc.window)]
        out += [] if pc.force_limit is None else [limit, repr(pc.force_limit)]
    return out


def _pct(x: float | None) -> str:
    """A fraction in per cent: whole per cents from 10 %, two digits below (``2.04`` → ``'204 %'``)."""
    if x is None:
        return "–"
    return f"{100 * x:.0f} %" if x >= 0.1 else f"{number(100 * x, 2)} %"


def _at_k(w: TunedWall) -> str:
    rec = w.recommendation
    if rec is None or rec.k_recommended is None:
        return "–"
    return "may buzz" if rec.above_rest else "rests"


def _over_cap(error: float | None, r: TuneResult) -> str:
    """`` > cap`` after a known force error beyond the tuning's cap (one rule: :func:`within_cap`), else ``''``."""
    return " > cap" if error is not None and not within_cap(error, r.max_force_error) else ""


def _row(i: int, w: TunedWall, r: TuneResult) -> list[str]:
    u = r.device.units
    label = wall_label(w.wall, w.device, u, r.device.period) + (" (plain)" if i == 0 else "")
    rec = w.recommendation
    if rec is None:
        err = _pct(w.screen_force_error) + _over_cap(w.screen_force_error, r)
        return [str(i + 1), label, f"~{number(w.screen, 5)}", "screened only", "–", "–", err, "–"]
    k = "none" if rec.k_recommended is None else number(rec.k_recommended, 5)
    ctl, err = _pct(w.controller_share), _pct(w.force_error) + _over_cap(w.force_error, r)
    kept = rec.controller is not None and not rec.controller.kept
    rule = _RULES.get(rec.status, rec.status.value) + (" (without PC)" if kept else "")
    rest = "–" if rec.k_rest is None else number(rec.k_rest, 5)
    return [str(i + 1), label, k, rule, _at_k(w), rest, err, ctl]


def tune_rows(r: TuneResult, *, screened: bool = False) -> list[list[str]]:
    """The table's rows: the simulated walls (plain first), and with ``screened`` the walls only screened."""
    return [_row(i, w, r) for i, w in enumerate(r.walls) if screened or w.status is TunedStatus.SIMULATED]


def best_text(r: TuneResult) -> str:
    """The best wall and its recommendation in one paragraph (unwrapped: the report's; the screen wraps it)."""
    best = r.best
    if best is None or best.recommendation is None:
        return f"no wall to recommend: {r.status.message}."
    rec = best.recommendation
    label = wall_label(best.wall, best.device, r.device.units, r.device.period)
    plain = r.walls[0].k_recommended
    gain = ""
    if r.status is TuneStatus.TUNED and plain is not None and best.k_recommended is not None:
        gain = f" ({number(best.k_recommended / plain, 3)}× the plain wall's)"
    elif r.status is TuneStatus.PLAIN_BEST:
        gain = (
            " (no other wall allowed "
            + ("rests at" if r.require_rest and r.rests(best) else "gets")
            + (" a higher recommended K within the force-error cap)")
        )
    buzz = ""
    if r.require_rest and not r.rests(best):
        buzz = " No wall within the force-error cap comes to rest at its recommended K: this one may buzz."
    return f"best: {label}{gain}; {recommendation_text(rec)}.{buzz}"


def choice_text(r: TuneResult) -> str:
    """How the best wall is chosen, in a few words."""
    cap = "" if r.max_force_error is None else f" with a force error of at most {_pct(r.max_force_error)}"
    rest = " that comes to rest at its K (where one does)" if r.require_rest else ""
    return f"the best wall is the stiffest{rest}{cap}"


def export_command(r: TuneResult, device_flags: str) -> str | None:
    """``dfa export`` of the best wall: the device's flags, the speed and margin, the wall's flags (None: no best).

    ``dfa export --velocity`` searches the same wall at the same speed by the same rule: the same K.
    """
    best = r.best
    if best is None:
        return None
    margin = [] if r.margin == 2.0 else ["--margin", repr(r.margin)]
    words = ["dfa", "export", device_flags, "--velocity", repr(r.velocity), *margin, *wall_flags(best, r.device)]
    return " ".join([*words, "--format", "c", "--out", "wall.h"])


def _walls(n: int) -> str:
    return f"{n} wall{'s' if n != 1 else ''}"


def tune_screen(r: TuneResult, export: str | None = None, *, screened: bool = False) -> list[str]:
    """One screen: what was tried, the table, the best wall and its recommendation, and how to export it.

    Parameters
    ----------
    r : TuneResult
    export : str, optional
        The command that exports the best wall (the command line knows its flags).
    screened : bool, optional
        List the walls only screened too (default False: the simulated ones).

    Returns
    -------
    list of str
        Lines under :data:`dfa.render.answer.WIDTH` characters but the table's (a row a line).
    """
    u = r.device.units
    n_sim = len(r.simulated)
    head = (
        f"{r.device.name}, impact speed {number(r.velocity, 4)} {u['velocity']}: {_walls(len(r.walls))} tried, "
        f"{n_sim} simulated in full; K in {u['stiffness']}; rule: proven, or the simulated limit over the margin; "
        "rests to K: the simulated rest limit; force error: RMS over the first contact at the wall's own K, % of the "
        f"ideal spring's peak force; {choice_text(r)}"
    )
    lines = [wrap(head), text_table(tune_rows(r, screened=screened), TUNE_HEADER)]
    lines.append(wrap(best_text(r)))
    if export is not None and r.best is not None:
        lines += ["export the best wall:", *command_lines(export)]
    return lines


def command_lines(command: str, width: int = 96) -> list[str]:
    r"""A shell command on lines under ``width`` characters, continued with a backslash (copy-paste runs it whole);
    a flag stays on the line of its value.

    Examples
    --------
    >>> print("\n".join(command_lines("dfa export --device impulse --velocity 0.05", width=34)))
      dfa export --device impulse \
        --velocity 0.05
    """
    words = command.split(" ")
    groups: list[str] = []
    for w in words:
        if groups and groups[-1].startswith("--") and " " not in groups[-1] and not w.startswith("--"):
            groups[-1] += " " + w
        else:
            groups.append(w)
    out, line = [], "  "
    for g in groups:
        if line.strip() and len(line) + 1 + len(g) + 2 > width:
            out.append(line + " \\")
            line = "    " + g
        else:
            line = f"{line} {g}" if line.strip() else line + g
    return [*out, line]
