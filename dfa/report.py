"""Design report of one device: verdict, stiffness limits, limit cycles, figures, and how far to trust them.

Markdown (figures as PNG files beside it) or one self-contained HTML file
(figures embedded). Every number is computed by the API when the report is
written.
"""

from __future__ import annotations

import base64
import html
import json
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._io import staged_folder
from .catalogue import CatalogueEntry
from .criterion import device_criterion
from .cycles import growth_threshold
from .device import Device
from .errors import DFATypeError, DFAValueError, check_choice, check_delay, check_int, check_positive, check_real
from .errors import _fmt as _fmt_value
from .loop import nyquist_locus_response
from .maps import stability_map
from .simulation import simulate
from .stiffness import stiffness_limits, stiffness_response
from .validation import _first_unstable_speed

__all__ = ["ReportResult", "design_report"]


@dataclass(frozen=True)
class ReportResult:
    """Files written by :func:`design_report` and the numbers they state."""

    paths: tuple
    figures: tuple
    numbers: dict = field(default_factory=dict)
    status: str = "ok"


def _slug(name: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-") or "device"


def _fmt(x, digits: int = 4) -> str:
    if x is None:
        return "–"
    if isinstance(x, float) and math.isinf(x):
        return "∞"
    return f"{x:.{digits}g}"


class _Doc:
    """A tiny document model rendered to Markdown or HTML."""

    def __init__(self) -> None:
        self.blocks: list[tuple] = []

    def h(self, level: int, text: str) -> None:
        self.blocks.append(("h", level, text))

    def p(self, text: str) -> None:
        self.blocks.append(("p", text))

    def table(self, header: list[str], rows: list[list[str]]) -> None:
        self.blocks.append(("table", header, rows))

    def fig(self, path: Path, caption: str) -> None:
        self.blocks.append(("fig", path, caption))

    def markdown(self, base: Path) -> str:
        out = []
        for b in self.blocks:
            if b[0] == "h":
                out.append("#" * b[1] + " " + b[2])
            elif b[0] == "p":
                out.append(b[1])
            elif b[0] == "table":

                def cell(x: str) -> str:
                    return x.replace("|", "\\|")  # a literal | would end the cell

                out.append("| " + " | ".join(cell(h) for h in b[1]) + " |")
                out.append("|" + "|".join("---" for _ in b[1]) + "|")
                out += ["| " + " | ".join(cell(c) for c in r) + " |" for r in b[2]]
            else:
                out.append(f"![{b[2]}]({os.path.relpath(b[1], base)})\n\n*{b[2]}*")
            out.append("")
        return "\n".join(out)

    def html(self, title: str) -> str:
        body = []
        for b in self.blocks:
            if b[0] == "h":
                body.append(f"<h{b[1]}>{html.escape(b[2])}</h{b[1]}>")
            elif b[0] == "p":
                text = html.escape(b[1])
                text = re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", text)
                text = re.sub(r"`(.+?)`", r"<code>\1</code>", text)
                text = re.sub(r"(?<![*\w])\*([^*]+?)\*(?![*\w])", r"<em>\1</em>", text)
                body.append(f"<p>{text}</p>")
            elif b[0] == "table":
                head = "".join(f"<th>{html.escape(h)}</th>" for h in b[1])
                rows = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>" for r in b[2])
                body.append(f"<table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody></table>")
            else:
                data = base64.b64encode(Path(b[1]).read_bytes()).decode("ascii")
                body.append(
                    f'<figure><img alt="{html.escape(b[2])}" src="data:image/png;base64,{data}"/>'
                    f"<figcaption>{html.escape(b[2])}</figcaption></figure>"
                )
        css = (
            "body{font-family:-apple-system,Segoe UI,Helvetica,Arial,sans-serif;max-width:980px;margin:2em auto;padding:0 1em;"
            "color:#222;line-height:1.45}table{border-collapse:collapse;margin:0.8em 0;font-size:0.92em}"
            "th,td{border:1px solid #ccc;padding:0.3em 0.6em;text-align:left}th{background:#f3f3f3}"
            "figure{margin:1.2em 0}img{max-width:100%}figcaption{font-size:0.88em;color:#555}"
            "h1{border-bottom:2px solid #2166ac}code{background:#f3f3f3;padding:0 0.2em}"
        )
        return (
            f'<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>'
            f"<style>{css}</style></head><body>{''.join(body)}</body></html>\n"
        )


def _outcome_sentence(r, dev: Device, k: float, v: float) -> str:
    """The simulated outcome at the design speed in words, with the force step and frequency in physical units."""
    u = dev.units
    head = f"**Simulated impact at {v:g} {u['velocity']}** ({r.samples_run} of {r.samples} samples): "
    if r.outcome == "rest":
        return head + f"the device comes to rest at sample {r.rest_sample} ({_fmt(r.rest_sample * dev.period)} s)."
    if r.outcome == "unstable":
        return head + "the motion diverges (unstable)."
    ph = r.physical(dev, k)
    step = (
        f"the force toggles over {r.force_peak_to_peak:.3g} KΔ peak-to-peak ({_fmt(ph['force_peak_to_peak_si'])} {ph['force_unit']})"
        + (f" at {ph['frequency_hz']:.4g} Hz" if ph["frequency_hz"] else "")
    )
    if r.outcome == "chatter":
        return (
            head
            + f"chatter: the device never comes to rest; {step} with a motion of {r.amplitude:.2g} ticks, a buzz the user feels."
        )
    if r.outcome == "oscillating":
        return (
            head
            + f"a persistent oscillation of {r.amplitude:.3g} ticks ({_fmt(ph['amplitude_si'])} {u['position']}); {step}."
        )
    return head + (
        f"undecided: the motion is still changing at the end of the run (last {r.amplitude:.3g} ticks); "
        f"about {r.suggested_samples} samples would be needed to tell."
    )


def _verdict_text(dev: Device, k: float, v: float, dl: int, crit, lim, v_sim) -> str:
    """The report's verdict paragraph: what the criterion proves, and at which speed and delay."""
    u = dev.units
    ds = f"a computational delay of {dl} sample{'s' if dl != 1 else ''}"
    if crit.passive:
        verdict = "passive (proven: the energy cannot grow)"
    elif lim.velocity_status == "none":
        verdict = f"not passive even at rest (K > 2c/Δ = {lim.k_static:.5g} {u['stiffness']})"
    else:
        verdict = "not proven passive (the criterion gives no guarantee; that is not a proof of instability)"
    text = (
        f"**Verdict.** With K = {k:g} {u['stiffness']}, an impact speed of {v:g} {u['velocity']} and {ds}, the {dev.name} is "
        f"**{verdict}** (region {crit.region}: {crit.status}). "
    )
    if crit.critical_velocity:
        text += f"The criterion guarantees passivity up to {_fmt(crit.critical_velocity)} {u['velocity']}; "
    text += f"{'at' if crit.critical_velocity else 'At'} {v:g} {u['velocity']} with {ds} the largest passive stiffness is {lim.k_max:.5g} {u['stiffness']}. "
    if v_sim:
        text += (
            f"In exact simulation an impact at {_fmt(dev.velocity(v_sim))} {u['velocity']} diverges: the lowest unstable "
            "speed of a 40-point scan, refined by bisection; stability need not be monotone in speed, so "
            "slower impacts between scan points may diverge too."
        )
    else:
        text += "No impact speed of a 40-point scan up to 30 times the reference speed diverged in exact simulation."
    return text


def design_report(
    device: Device | CatalogueEntry,
    stiffness: float | None = None,
    velocity: float | None = None,
    *,
    out_dir: str | os.PathLike = "reports",
    fmt: str = "html",
    progress: bool = True,
    map_grid: int = 41,
    samples: int = 30_000,
    delay: int = 0,
) -> ReportResult:
    """Write the design report of ``device`` at stiffness K, impact speed ẋ0 and computational delay d.

    Parameters
    ----------
    device : Device or CatalogueEntry
        A catalogue entry adds the paper's printed values and notes.
    stiffness : float, optional
        K in N/m (rotary N·m/rad); default the catalogue K.
    velocity : float, optional
        Impact speed in m/s (rotary rad/s); default 0.1 m/s (1 rad/s rotary).
    out_dir : path
        Folder for the report and its ``figures/``.
    fmt : {"html", "md", "both"}
    progress : bool
        Progress bars on the long parts.
    map_grid, samples : int
        Size of the simulated stability map around the operating point.
    delay : int
        Computational delay d in whole samples (default 0): used by the
        criterion, the stiffness limits, the describing function and every
        simulation of the report.
    """
    entry = device if isinstance(device, CatalogueEntry) else None
    dev = entry.device if entry is not None else device
    if not isinstance(dev, Device):
        raise DFAValueError(f"device = {device!r} is invalid: it must be a dfa.Device or a catalogue entry")
    k = stiffness if stiffness is not None else (entry.stiffness if entry is not None else None)
    if k is None:
        raise DFAValueError(
            f"stiffness = None is invalid for {dev.name!r}: the catalogue gives no K; pass the stiffness in {dev.units['stiffness']}"
        )
    k = check_positive("stiffness", k, "give the virtual wall stiffness K")
    v = abs(check_real("velocity", velocity if velocity is not None else (1.0 if dev.rotary else 0.1)))
    fmt = check_choice("fmt", fmt, ("html", "md", "both"))
    dl = check_delay(delay)
    check_int("map_grid", map_grid, minimum=2, fix="use at least 2 points per axis")
    check_int("samples", samples, minimum=1, fix="simulate at least one sample")
    if not isinstance(progress, (bool, np.bool_)):
        raise DFATypeError(
            f"progress = {_fmt_value(progress)} has type {type(progress).__name__}: it must be True or False"
        )
    if not isinstance(out_dir, (str, os.PathLike)):
        raise DFATypeError(
            f"out_dir = {_fmt_value(out_dir)} has type {type(out_dir).__name__}: it must be a folder path"
        )
    out = Path(out_dir)
    if not out.is_dir():
        raise DFAValueError(f"out_dir = {str(out)!r} is invalid: the folder does not exist; create it first")
    # write everything into a staging folder, then move the files in: never a mix of two reports (dfa._io)
    with staged_folder(out) as stage:
        res = _write_report(entry, dev, k, v, dl, fmt, progress, map_grid, samples, out, stage)
    final = lambda pth: out / Path(pth).relative_to(stage)
    return ReportResult(tuple(final(x) for x in res.paths), tuple(final(x) for x in res.figures), res.numbers)


def _write_report(entry, dev, k, v, dl, fmt, progress, map_grid, samples, out: Path, stage: Path) -> ReportResult:
    figdir = stage / "figures"
    figdir.mkdir(exist_ok=True)
    slug = _slug(dev.name)
    u = dev.units

    from tqdm.auto import tqdm

    steps = tqdm(total=7, desc=f"report {dev.name}", disable=not progress, leave=False)
    p = dev.params(k)
    crit = device_criterion(dev, k, v, delay=dl)
    lim = stiffness_limits(dev, v, k, delay=dl)
    steps.update()
    thr = {
        m: growth_threshold(p, dev, model=m, delay=dl) for m in ("half-delay", "zoh")
    }  # search range follows the problem
    steps.update()
    # how far to trust: the true critical speed of this device by simulation
    ref = crit.critical_xi_dot if crit.critical_xi_dot else max(1.0, crit.xi_dot)
    v_sim = _first_unstable_speed(p, 0.2 * ref, 30.0 * ref, samples, preload=False, delay=dl)
    steps.update()

    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    from . import plotting

    figs: list[tuple[Path, str]] = []

    def save(fig, name: str, caption: str) -> None:
        path = figdir / f"{slug}_{name}.png"
        fig.savefig(path, dpi=120)
        plt.close(fig)
        figs.append((path, caption))

    ax = plotting.regions_plot(
        crit,
        xi_dots=[x for x in (1.0, 5.0) if abs(x - crit.xi_dot) > 0.2],
        beta_max=max(1.0, 2 * p.beta),
        sigma_max=max(2.0, 1.5 * p.sigma),
    )
    save(
        ax.figure,
        "regions",
        f"Operating point of the {dev.name} in the (β, σ) plane with its critical line at {v:g} {u['velocity']}"
        + (f", delay {dl} sample{'s' if dl != 1 else ''}" if dl else "")
        + " (eq. 6, 10).",
    )
    ax = plotting.stiffness_plot(stiffness_response(dev, stiffness=k, delay=dl))
    save(ax.figure, "stiffness", "Largest passive stiffness against impact speed (eq. 11) and the published bounds.")
    res = thr["half-delay"].result
    amps = [c.amplitude for c in res.cycles[:3]] if p.sigma > 0 else None
    if p.sigma > 0 and not amps:
        amps = [1.0]
    m_top = max([50.0] + [2.0 * c.amplitude for c in res.cycles])  # the locus must reach every cycle drawn
    ny = nyquist_locus_response(p, amplitudes=amps, locus_amplitude=np.geomspace(0.05, m_top, 1500), delay=dl)
    ax = plotting.nyquist_plot(ny, cycles=res)
    save(
        ax.figure,
        "nyquist",
        "Nyquist plot of the linearised loop (half-sample delay) against −1/D(M), with the predicted limit cycles.",
    )
    steps.update()
    n_traj = int(min(samples, max(2000, 40 * 2 * math.pi * math.sqrt(p.mu))))
    fig, axs = plt.subplots(2, 1, figsize=(7, 5.4), constrained_layout=True)
    sim_v = simulate(p.mu, p.beta, p.sigma, crit.xi_dot, n_traj, delay=dl)
    # outcomes from runs as long as the loop's time scales need (dfa.simulation.default_samples)
    full_v = simulate(p.mu, p.beta, p.sigma, crit.xi_dot, delay=dl, record=False)
    plotting.trajectory_plot(sim_v, ax=axs[0], period=dev.period)
    axs[0].set_title(f"impact at {v:g} {u['velocity']} (ξ'0 = {crit.xi_dot:.3g}): {full_v.outcome}", fontsize=9)
    v_show = v_sim * 1.05 if v_sim is not None else 2.0 * ref
    sim_hi = simulate(p.mu, p.beta, p.sigma, v_show, n_traj, delay=dl)
    full_hi = simulate(p.mu, p.beta, p.sigma, v_show, delay=dl, record=False)
    plotting.trajectory_plot(sim_hi, ax=axs[1], period=dev.period)
    axs[1].set_title(
        f"impact at {dev.velocity(v_show):.3g} {u['velocity']} (ξ'0 = {v_show:.3g}): {full_hi.outcome}", fontsize=9
    )
    save(
        fig,
        "trajectories",
        "Simulated displacement (exact sampled-data integration) at the design speed and just above the simulated critical speed; dashed: ±1 tick.",
    )
    steps.update()
    bw = max(0.25, 2 * p.beta)
    sw = max(1.0, 2 * p.sigma)
    smap = stability_map(
        p.mu,
        [crit.xi_dot, 2 * crit.xi_dot] if crit.xi_dot > 0 else [1.0, 2.0],
        beta_range=(0.0, bw),
        sigma_range=(0.0, sw),
        grid=map_grid,
        samples=samples,
        progress=progress,
        delay=dl,
    )
    axs = plotting.stability_map_plot(smap)
    for a in axs:
        a.plot([p.beta], [p.sigma], "o", color="#f1a340", mec="k", ms=7)
    save(
        axs[0].figure,
        "map",
        f"Simulated stability around the operating point (orange) at the design speed and twice it; μ = {p.mu:.4g}.",
    )
    steps.update()

    # ------------------------------------------------------------ the document
    d = _Doc()
    d.h(1, f"Design report: {dev.name}")
    d.p(_verdict_text(dev, k, v, dl, crit, lim, v_sim))
    d.p(
        "Method: N. Diolaiti, G. Niemeyer, F. Barbagli, J. K. Salisbury, *A Criterion for the Passivity of Haptic Devices*, ICRA 2005; "
        "equation numbers refer to that paper. Generated by `dfa report`."
    )
    d.h(2, "Device")
    rows = [
        ["mass m", f"{dev.mass:g} {u['mass']}"],
        ["viscous damping b", f"{dev.damping:g} {u['damping']}"],
        ["Coulomb friction c", f"{dev.coulomb:g} {u['force']}"],
        ["encoder resolution Δ", f"{dev.resolution:.4g} {u['resolution']}"],
        ["sample period T", f"{dev.period:.4g} s ({1 / dev.period:.4g} Hz)"],
        ["stiffness K", f"{k:g} {u['stiffness']}"],
        ["μ = m/(K T²)", f"{p.mu:.5g}"],
        ["β = b/(K T)", f"{p.beta:.5g}"],
        ["σ = c/(K Δ)", f"{p.sigma:.5g}"],
    ]
    d.table(["quantity", "value"], rows)
    if entry is not None:
        pr = entry.printed_params
        if pr:
            d.p(
                "Paper Table 2 prints "
                + ", ".join(
                    f"{k_} = {entry.printed[i][1]}" for i, k_ in enumerate(("μ", "β", "σ")) if i < len(entry.printed)
                )
                + (
                    "; disagreements with the recomputed values: " + "; ".join(str(x) for x in entry.discrepancies)
                    if entry.discrepancies
                    else "; the recomputed values agree."
                )
                + (f" Note: {entry.notes}" if entry.notes else "")
            )
    d.h(2, "Passivity and stiffness limits")
    d.table(
        ["quantity", "value"],
        [
            ["impact speed ẋ0", f"{v:g} {u['velocity']} = {crit.xi_dot:.4g} ticks/sample"],
            ["region (paper Fig. 3)", f"{crit.region}: {crit.status}"],
            ["computational delay d", f"{dl} sample{'s' if dl != 1 else ''}"],
            [
                "passive (eq. 6)",
                "yes (proven: the energy cannot grow)" if crit.passive else "no guarantee (not a proof of instability)",
            ],
            ["margin (β − ½ − d)|ξ'0| + (σ − ½)", f"{crit.margin:.4g}"],
            [
                "critical speed (eq. 12)",
                "none"
                if crit.critical_xi_dot is None
                else f"{crit.critical_xi_dot:.4g} ticks/sample = {_fmt(crit.critical_velocity)} {u['velocity']}",
            ],
            ["K_max at this speed (eq. 11)", f"{lim.k_max:.5g} {u['stiffness']}"],
            ["2c/Δ (eq. 9, at rest)", f"{lim.k_static:.5g} {u['stiffness']}"],
            ["Colgate–Schenkel 2b/T (eq. 8)", f"{lim.k_colgate:.5g} {u['stiffness']}"],
            ["Abbott–Okamura min(2b/T, 2c/Δ)", f"{lim.k_abbott_okamura:.5g} {u['stiffness']}"],
            [
                "exact linear bound of the sampled spring (all Jury conditions; Gil et al. where binding)",
                f"{lim.k_gil:.5g} {u['stiffness']}",
            ],
            [f"largest passive speed at K = {k:g}", lim.max_passive_velocity_text()],
            ["verdict for this K at this speed", lim.verdict_text()],
        ],
    )
    d.fig(*figs[0])
    d.fig(*figs[1])
    d.h(2, "Predicted limit cycles (describing function, eq. 36–41)")
    crow = []
    for m, g in thr.items():
        for c in g.result.cycles:
            crow.append(
                [
                    m,
                    f"{c.amplitude:.5g}",
                    f"{c.amplitude * dev.resolution:.3g} {u['position']}",
                    f"{c.frequency:.4g}",
                    f"{1 / (c.period * dev.period):.4g} Hz",
                    "stable" if c.stable else "unstable",
                    c.family + (" (period < 8 samples)" if c.few_samples else ""),
                ]
            )
    if crow:
        d.table(["loop model", "M (ticks)", "amplitude", "ω (rad/sample)", "frequency", "stability", "family"], crow)
    for line in _absence_lines(thr):
        d.p(line)
    g = thr["zoh"]
    if g.amplitude is not None:
        d.p(_growth_paragraph(g, u))
    d.fig(*figs[2])
    d.h(2, "How far to trust these predictions")
    rows = [
        [
            "criterion (eq. 12), guaranteed",
            _fmt(crit.critical_xi_dot),
            f"{_fmt(crit.critical_velocity)} {u['velocity']}",
        ],
        *[
            [
                f"describing function, {m}" + (" (growth band)" if t.is_band else ""),
                _fmt(t.xi_dot) + (f" to {_fmt(t.xi_dot_high)}" if t.is_band else ""),
                f"{_fmt(t.velocity)}" + (f" to {_fmt(t.velocity_high)}" if t.is_band else "") + f" {u['velocity']}",
            ]
            for m, t in (("half-delay", thr["half-delay"]), ("exact ZOH", thr["zoh"]))
        ],
        [
            "exact simulation (bisection on ξ'0, from ξ0 = 0)",
            _fmt(v_sim),
            f"{_fmt(dev.velocity(v_sim)) if v_sim else '–'} {u['velocity']}",
        ],
    ]
    d.table(["critical impact speed", "ticks/sample", "physical"], rows)
    msg = []
    if v_sim and crit.critical_xi_dot:
        msg.append(f"The criterion is conservative by a factor {v_sim / crit.critical_xi_dot:.3g} for this device")
    if v_sim and g.xi_dot:
        msg.append(
            f"the describing function's threshold is within {100 * abs(g.xi_dot / v_sim - 1):.2g} % of the simulated one"
        )
    if msg:
        d.p("; ".join(msg) + ".")
    vjson = out / "validation" / "validation.json"
    if vjson.is_file():
        s = json.loads(vjson.read_text())
        d.p(
            f"Across the validation set (`reports/validation/validation.md`): {s['soundness_violations']} of {s['soundness_passive']} points the "
            f"criterion calls passive went unstable in simulation; the criterion rejects {100 * s['conservatism']:.0f} % of the points that "
            f"came to rest; the describing function's growth threshold is within a median {100 * s['speed_df_median_error']:.2g} % "
            f"of the simulated critical speed; stable cycles with periods under 8 samples are poorly predicted (median frequency error "
            f"{100 * s['short_period_frequency_error']:.2g} %)."
        )
    d.p(_outcome_sentence(full_v, dev, k, v))
    d.fig(*figs[3])
    d.fig(*figs[4])
    steps.update()
    paths = []
    if fmt in ("md", "both"):
        pth = stage / f"design_report_{slug}.md"
        pth.write_text(d.markdown(stage), encoding="utf-8")
        paths.append(pth)
    if fmt in ("html", "both"):
        pth = stage / f"design_report_{slug}.html"
        pth.write_text(d.html(f"dfa design report: {dev.name}"), encoding="utf-8")
        paths.append(pth)
    steps.close()
    numbers = dict(
        mu=p.mu,
        beta=p.beta,
        sigma=p.sigma,
        region=crit.region,
        passive=crit.passive,
        k_max=lim.k_max,
        delay=dl,
        critical_xi_dot=crit.critical_xi_dot,
        df_xi_dot=g.xi_dot,
        simulated_xi_dot=v_sim,
        cycles=[c.amplitude for c in thr["half-delay"].result.cycles],
    )
    return ReportResult(tuple(paths), tuple(f for f, _c in figs), numbers)


def _absence_lines(thr: dict) -> list[str]:
    """Sentences for loop models without cycles: never an absence the search did not prove."""
    out = []
    for m, g in thr.items():
        res = g.result
        if res.cycles:
            if not res.complete:
                out.append(
                    f"{m} loop: search incomplete beyond M = {res.max_amplitude:g} ticks ({res.status.removeprefix('incomplete: ')}); "
                    "more cycles may exist."
                )
            continue
        if not res.complete:
            out.append(
                f"{m} loop: no limit cycle found up to M = {res.max_amplitude:g} ticks (search incomplete: "
                f"{res.status.removeprefix('incomplete: ')})."
            )
        elif res.linear_stable is False:
            out.append(
                f"{m} loop: no limit cycle predicted, but the linear loop without encoder and Coulomb friction (exact ZOH model) "
                "is unstable: amplitudes grow without bound."
            )
        else:
            out.append(f"{m} loop: no limit cycle is predicted (search complete).")
    return out


def _growth_paragraph(g, u: dict) -> str:
    """The exact-ZOH growth threshold, or band for a cluster, with its meaning (physical units from ``u``)."""
    if g.is_band:
        return (
            f"**Growth band** (exact ZOH loop): {g.unstable_count} unstable cycles from M = {g.amplitude:.4g} to {g.amplitude_high:.4g} ticks "
            f"({_fmt(g.position)} to {_fmt(g.position_high)} {u['position']}); speeds M·ω = {g.xi_dot:.4g} to {g.xi_dot_high:.4g} ticks/sample "
            f"= {_fmt(g.velocity)} to {_fmt(g.velocity_high)} {u['velocity']}. {g.meaning()}"
        )
    return (
        f"**Growth threshold** (exact ZOH loop): M_u = {g.amplitude:.4g} ticks ({_fmt(g.position)} {u['position']}); "
        f"the matching impact speed is M_u·ω = {g.xi_dot:.4g} ticks/sample = {_fmt(g.velocity)} {u['velocity']}. {g.meaning()}"
    )
