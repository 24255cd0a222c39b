"""Design report of one device: verdict, stiffness limits, limit cycles, figures, and how far to trust them.

:func:`design_report` = :func:`dfa.studies.design.design_analysis` (every number) + :func:`write_design_report`
(figures and documents from that analysis only). Markdown (figures as PNG files in ``figures/`` beside it)
and/or one self-contained HTML file (figures embedded, no PNG written). The files of one report appear
together or not at all (:func:`dfa._io.staged_folder`), with ``design_report_{name}.json`` beside them: the
inputs and numbers stated, used to refuse overwriting the report of another device, stiffness, speed or delay.
A report of a wall beyond the paper's spring (a virtual damper, velocity filter or amplifier lag) is named
``design_report_{name}_controller.*`` (figures ``{name}_controller_*.png``): it never replaces the spring report of
the same device, and a report of another wall in the way is refused like any report of other inputs. A device
held by a hand (:meth:`dfa.Device.holding`) adds ``_held`` to the name (``design_report_{name}_held.*``).
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from .._io import staged_folder
from ..checks import check_bool, check_choice, check_int, format_value
from ..errors import DFATypeError, DFAValueError
from ..jsonable import dumps, explain_nulls, round_floats, to_jsonable
from ..model.catalogue import CatalogueEntry
from ..model.elements import Coverage, OneSided
from ..model.loop import Loop
from ..results.status import ReportStatus
from .design import DesignAnalysis, design_analysis, design_first, design_loop

__all__ = ["ReportResult", "design_report", "report_name", "report_slug", "write_design_report"]


@dataclass(frozen=True)
class ReportResult:
    """Files written by :func:`design_report` and the numbers they state.

    Attributes
    ----------
    paths : tuple of Path
        The documents (``.md``, ``.html``) and the JSON of the numbers, in that order.
    figures : tuple of Path
        PNG files written (only with Markdown; HTML embeds its figures).
    numbers : dict
        Headline numbers (μ, β, σ, region, passive, K_max, speeds in ticks/sample, cycle amplitudes); for a wall
        beyond the spring those of the criterion extended to it and of K_max with it, ``k_linear`` and the
        ``wall`` object of `dfa check --json` (nulls explained in ``null_reasons``).
    status : ReportStatus
        ``OK``.
    analysis : DesignAnalysis or None
        Every number of the report.
    """

    paths: tuple
    figures: tuple
    numbers: dict = field(default_factory=dict)
    status: ReportStatus = ReportStatus.OK
    analysis: DesignAnalysis | None = field(default=None, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "status", ReportStatus.coerce(self.status))

    def to_dict(self) -> dict[str, object]:
        """Paths (as text), headline numbers and the full analysis, strict JSON data."""
        return to_jsonable(
            {
                "paths": [str(p) for p in self.paths],
                "figures": [str(p) for p in self.figures],
                "numbers": self.numbers,
                "status": self.status,
                "status_message": self.status.message,
                "analysis": self.analysis.to_dict() if self.analysis is not None else None,
            }
        )


def report_slug(name: str) -> str:
    """File-name part of a device name: lower case, runs of other characters as ``-``.

    Examples
    --------
    >>> report_slug("Phantom 1.0"), report_slug("  "), report_slug("My pen #2")
    ('phantom-1-0', 'device', 'my-pen-2')
    """
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-") or "device"


def _numbers(a: DesignAnalysis) -> dict[str, Any]:
    """The headline numbers: the spring's closed forms, or for a wall its extended criterion and K_max."""
    p, crit = a.params, a.criterion
    if a.covers(Coverage.CLOSED_FORM) and crit is not None and a.limits is not None:
        return dict(
            mu=p.mu,
            beta=p.beta,
            sigma=p.sigma,
            region=crit.region,
            passive=crit.passive,
            k_max=a.limits.k_max,
            delay=a.delay,
            critical_xi_dot=crit.critical_xi_dot,
            df_xi_dot=a.threshold("zoh").xi_dot,
            simulated_xi_dot=a.simulated_xi_dot,
            cycles=[c.amplitude for c in a.threshold("half-delay").result.cycles],
        )
    return _wall_numbers(a)


def _wall_numbers(a: DesignAnalysis) -> dict[str, Any]:
    """The headline numbers of a wall beyond the spring: the extended criterion's, K_max with the wall, its groups."""
    from ..render.controller import wall_dict

    p, r, lim = a.params, a.criterion, a.design_answer
    out = dict(
        mu=p.mu,
        beta=p.beta,
        sigma=p.sigma,
        region=None if r is None else r.region,
        passive=a.check.passive,
        k_max=None if lim is None else lim.k_criterion.value,
        k_linear=None if lim is None else lim.k_linear.value,
        delay=a.delay,
        critical_xi_dot=None if r is None else r.critical_xi_dot,
        df_xi_dot=None if not a.wall.linear else a.threshold("zoh").xi_dot,
        simulated_xi_dot=a.simulated_xi_dot,
        cycles=[] if not a.wall.linear else [c.amplitude for c in a.threshold("half-delay").result.cycles],
        wall=wall_dict(a.wall, a.device.period, a.device.units, a.device.resolution),
    )
    lag = f"not covered: {a.wall.params(a.device.period, a.device.resolution).not_covered()}"
    why = {
        "region": lag,
        "passive": lag,
        "critical_xi_dot": lag if r is None else "no critical speed: passive at every speed (region a) or at none",
    }
    why["k_max"] = "impact speed 0: no K_max" if lim is None else lim.k_criterion.status.message
    why["k_linear"] = "impact speed 0: no K_max" if lim is None else lim.k_linear.status.message
    why["simulated_xi_dot"] = "no scanned impact speed diverged"
    why["df_xi_dot"] = (
        "not a linear loop: no describing function" if not a.wall.linear else "no unstable cycle predicted"
    )
    return explain_nulls(to_jsonable(out), why)


def _identity(loop: Loop, velocity: float) -> dict[str, Any]:
    """What makes two reports the same report: device, stiffness, speed, delay (and the wall's elements, if any)."""
    device, wall = loop.physical("design_report")
    wp = loop.groups("design_report")[1]
    ident: dict[str, Any] = {
        "device": device.to_dict(),
        "stiffness": wall.stiffness,
        "velocity": velocity,
        "delay": wp.delay,
    }
    if not wp.covers(Coverage.CLOSED_FORM):  # a wall beyond the spring (its report is a separate file)
        ident["controller"] = wall.to_dict()
    return json.loads(dumps(ident, ensure_ascii=False))


def report_name(name: str, beyond_spring: bool = False, held: bool = False, one_sided: bool = False) -> str:
    """File-name part of a report: the device's slug, with ``_held`` for a device held by a hand,
    ``_one_sided`` for a one-sided wall and ``_controller`` for another wall beyond the spring.

    Examples
    --------
    >>> report_name("Delta"), report_name("Delta", True), report_name("Delta", held=True)
    ('delta', 'delta_controller', 'delta_held')
    >>> report_name("Delta", True, one_sided=True)
    'delta_one_sided'
    """
    wall = "_one_sided" if one_sided else ("_controller" if beyond_spring else "")
    return report_slug(name) + ("_held" if held else "") + wall


def _doc_names(slug: str, fmt: str) -> tuple[list[str], str]:
    return [
        f"design_report_{slug}.{ext}" for ext in ("md", "html") if fmt in (ext, "both")
    ], f"design_report_{slug}.json"


def _check_overwrite(out: Path, fmt: str, ident: dict[str, Any]) -> None:
    """Refuse to replace a report of another device, stiffness, speed or delay (the fix: --name, --out, --force)."""
    name = ident["device"]["name"]
    ctl = ident.get("controller")
    one_sided = ctl is not None and "one_sided_surface" in ctl
    docs, meta = _doc_names(report_name(name, ctl is not None, "hand" in ident["device"], one_sided), fmt)
    existing = [n for n in docs + [meta] if (out / n).exists()]
    if not existing:
        return
    other = None
    if (out / meta).is_file():
        try:
            old = round_floats(json.loads((out / meta).read_text(encoding="utf-8")).get("identity"))
        except (OSError, ValueError, AttributeError):
            old = None  # compared at JSON's digits: a file written with more (older dfa) is the same report
        if old != ident:
            other = "a report of other inputs" if not isinstance(old, dict) else _describe(old)
    else:  # a report without its JSON: accept it only when it names the same device
        text = (out / existing[0]).read_text(encoding="utf-8", errors="replace").lower()
        if f"design report: {name}".lower() not in text:
            other = "a report of another device"
    if other is not None:
        raise DFAValueError(
            f"out_dir {str(out)!r} already holds {existing[0]}, {other}: it would be overwritten; "
            "give another --name (name) or --out folder, or --force (force=True) to replace it"
        )


def _describe(identity: dict[str, Any]) -> str:
    dev = identity.get("device") or {}
    ctl = identity.get("controller")
    with_ctl = (
        ""
        if not isinstance(ctl, dict)
        else f", controller B = {ctl.get('damping')}, "
        + (f"filter {ctl.get('filter_cutoff')} Hz, amplifier {ctl.get('amplifier_bandwidth')} Hz")
    )
    hand = dev.get("hand")
    held = (
        ""
        if not isinstance(hand, dict)
        else f" held by {hand.get('name')!r} ({hand.get('mass')} kg, {hand.get('damping')} N·s/m)"
    )
    return (
        f"the report of {dev.get('name', '?')!r}{held} at K = {identity.get('stiffness')}, speed "
        f"{identity.get('velocity')}, delay {identity.get('delay')}{with_ctl}"
    )


def write_design_report(
    analysis: DesignAnalysis, out_dir: str | os.PathLike = "reports", fmt: str = "html", *, force: bool = False
) -> ReportResult:
    """Render ``analysis`` as Markdown and/or HTML into ``out_dir`` (all files at once, or none).

    Parameters
    ----------
    analysis : DesignAnalysis
        From :func:`dfa.studies.design.design_analysis`; only read.
    out_dir : path
        Existing folder for ``design_report_{name}.md|html|json`` and, with Markdown, ``figures/``.
    fmt : {"html", "md", "both"}
        HTML is self-contained (figures embedded, no PNG written); Markdown links PNGs in ``figures/``.
    force : bool
        Replace a report of the same file name made for another device, stiffness, speed or delay.

    Returns
    -------
    ReportResult

    Raises
    ------
    DFAValueError
        A missing folder, an unknown format, or a report of other inputs in the way (without ``force``).
    """
    from .design_document import design_html, design_markdown
    from .design_figures import design_figures

    fmt = check_choice("fmt", fmt, ("html", "md", "both"))
    out = Path(out_dir)
    if not out.is_dir():
        raise DFAValueError(f"out_dir = {str(out)!r} is invalid: the folder does not exist; create it first")
    a = analysis
    one_sided = a.wall.element(OneSided) is not None
    slug = report_name(a.device.name, not a.covers(Coverage.CLOSED_FORM), a.device.hand is not None, one_sided)
    docs, meta = _doc_names(slug, fmt)
    ident = _identity(Loop(a.device, a.wall), a.velocity)
    if not force:
        _check_overwrite(out, fmt, ident)
    figs = design_figures(analysis)
    fig_paths = [Path("figures") / f"{slug}_{f.name}.png" for f in figs] if fmt in ("md", "both") else []
    res = ReportResult(tuple(out / d for d in docs) + (out / meta,), tuple(out / p for p in fig_paths),
                       _numbers(analysis), analysis=analysis)  # fmt: skip
    with staged_folder(out) as stage:  # never a mix of two reports (dfa._io)
        for f, rel in zip(figs, fig_paths, strict=False):
            (stage / rel).parent.mkdir(exist_ok=True)
            (stage / rel).write_bytes(f.png)
        captions = {f.name: f.caption for f in figs}
        if fmt in ("md", "both"):
            src = {f.name: rel.as_posix() for f, rel in zip(figs, fig_paths, strict=False)}
            (stage / docs[0]).write_text(design_markdown(analysis, captions, src.__getitem__), encoding="utf-8")
        if fmt in ("html", "both"):
            page = design_html(analysis, {f.name: (f.caption, f.png) for f in figs})
            (stage / docs[-1]).write_text(page, encoding="utf-8")
        body = {"identity": ident, **res.to_dict()}
        (stage / meta).write_text(dumps(body, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return res


@design_first
def design_report(
    loop: Loop,
    velocity: float | None = None,
    *,
    entry: CatalogueEntry | None = None,
    out_dir: str | os.PathLike = "reports",
    fmt: str = "html",
    progress: bool = True,
    map_grid: int = 81,
    samples: int = 30_000,
    validation: dict[str, Any] | None = None,
    force: bool = False,
    zwidth_grid: int | None = None,
    tune: bool = False,
    configurations: Any = None,
) -> ReportResult:
    """Write the design report of the loop's device with its wall at impact speed ẋ0.

    :func:`dfa.studies.design.design_analysis` followed by :func:`write_design_report`; the loop's groups are
    formed once.

    Parameters
    ----------
    loop : Loop
        The device and the wall (:class:`dfa.Wall`: K in N/m, rotary N·m/rad, and its elements: computational
        delay d in samples, virtual damper, velocity filter, amplifier; or a stiffness K for the paper's spring),
        ``Loop(device, wall)``; ``Loop(device)`` with a catalogue ``entry``: the spring at the catalogue K. A wall
        beyond the spring writes ``design_report_{name}_controller.*``. The former call
        ``design_report(device_or_entry, wall, velocity, ...)`` still works.
    velocity : float, optional
        Impact speed in m/s (rotary rad/s); default 0.1 m/s (1 rad/s rotary).
    entry : CatalogueEntry, optional
        Keyword only: the catalogue entry of the loop's device, adding the paper's printed values and notes.
    out_dir : path
        Existing folder for the report and its ``figures/``.
    fmt : {"html", "md", "both"}
        Self-contained HTML, Markdown with PNG figures, or both.
    progress : bool
        Progress bars on the long parts.
    map_grid, samples : int
        Size of the simulated stability map around the operating point.
    validation : dict, optional
        Summary of a validation run (``dfa.validate(...).summary()``) for the "how far to trust" paragraph.
    force : bool
        Replace a report of the same name made for other inputs.
    zwidth_grid : int or None
        Points per axis of a Z-width section (:func:`dfa.analysis.limits.zwidth.z_width`); None (default): no
        section for the spring, a 16 × 16 one for a wall beyond it; 0: none.
    tune : bool
        Add the "deployable wall" section: :func:`dfa.tune` with its default lists at the report's speed, and the
        ``dfa export`` command that writes the best wall for the firmware (about 40 s; default False).
    configurations : WorstConfiguration or None
        A device file's configurations answered by :func:`dfa.analysis.configurations.worst_stiffness`, the loop's
        device being the limiting one: a row per configuration, the limiting one marked (default None).

    Returns
    -------
    ReportResult
        Paths of the files and figures written, the numbers stated, the analysis and a status.

    Raises
    ------
    DFAValueError
        Bad inputs (see :func:`dfa.studies.design.design_analysis`), a missing folder, or a report of other inputs in the way.

    See Also
    --------
    design_analysis : The numbers of the report, without rendering or files.
    """
    fmt = check_choice("fmt", fmt, ("html", "md", "both"))
    check_int("map_grid", map_grid, minimum=2, fix="use at least 2 points per axis")
    check_int("samples", samples, minimum=1, fix="simulate at least one sample")
    progress = check_bool("progress", progress, "pass True to show a progress bar, False for none")
    force = check_bool("force", force, "pass True to replace a report of other inputs, False to refuse it")
    if not isinstance(out_dir, (str, os.PathLike)):
        raise DFATypeError(
            f"out_dir = {format_value(out_dir)} has type {type(out_dir).__name__}: it must be a folder path"
        )
    if not Path(out_dir).is_dir():
        raise DFAValueError(f"out_dir = {str(out_dir)!r} is invalid: the folder does not exist; create it first")
    loop, v = design_loop(loop, velocity, entry)
    if not force:  # before the analysis: refuse in a second, not after a minute of simulation
        _check_overwrite(Path(out_dir), fmt, _identity(loop, v))
    a = design_analysis(
        loop, v, entry=entry, map_grid=map_grid, samples=samples, validation=validation, progress=progress,
        zwidth_grid=zwidth_grid, tune=check_bool("tune", tune, "pass True for the deployable wall, False for none"),
        configurations=configurations,
    )  # fmt: skip
    return write_design_report(a, out_dir, fmt, force=force)
