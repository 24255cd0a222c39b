"""A wall to deploy as the firmware takes it (issue 44): a C99 header, a YAML parameter file, JSON.

:func:`c_header` writes a self-contained C99 header: the wall's constants and a reference implementation of the wall
as dfa models it (:mod:`dfa.core.wall_kernel`'s controller: the spring on the encoder's reading, paper eq. 2, the
damper on the backward difference, the velocity filter, a one-sided wall, the passivity observer and controller, the
force limit and the delay line), in the simulator's dimensionless arithmetic in the same order, multiplied by K·Δ at
the end::

    typedef struct {...} dfa_wall_t;
    void dfa_wall_init(dfa_wall_t *w);
    double dfa_wall_force(dfa_wall_t *w, long counts);   /* N (rotary N·m) for the next sample */

(``static inline``: the header may be included in several files). Compiled without floating-point contraction
(``-ffp-contract=off``) its forces are the simulator's (:func:`dfa.core.wall_kernel.applied_forces` times K·Δ),
sample by sample (``tests/test_export_c.py``). :func:`yaml_text` writes the parameters for a ros2_control-style
configuration (no nulls: ROS parameters have none), with the provenance :meth:`DeployableWall.from_dict
<dfa.results.deploy.DeployableWall.from_dict>` reads back; :func:`json_text` the record of
:meth:`~dfa.results.deploy.DeployableWall.to_dict`, every number exact.

Examples
--------
>>> from dfa.model.catalogue import get_device
>>> from dfa.model.loop import Loop
>>> from dfa.model.wall import Wall
>>> loop = Loop(get_device("impulse").device, Wall.of(100.0, damping=0.5))
>>> text = export(loop)
>>> [line for line in text.splitlines() if "DFA_WALL_FORCE_STEP " in line][0].split()[:3]
['#define', 'DFA_WALL_FORCE_STEP', '0.0314']
"""

from __future__ import annotations

import json
import math
import textwrap
from functools import lru_cache
from typing import Any

from ..errors import DFATypeError, DFAValueError
from ..jsonable import to_jsonable
from ..model.elements import ForceLimit, OneSided, PassivityController, VelocityFilter
from ..model.loop import Loop
from ..results.deploy import DeployableWall
from ..results.require import Recommendation
from ..results.status import DeployRule
from ..results.tune import TunedWall, TuneResult
from .hand import device_title

__all__ = ["FORMATS", "c_header", "export", "json_text", "yaml_text", "deployable"]

#: The formats of :func:`export`.
FORMATS = ("c", "yaml", "json")
#: The YAML's top-level key (the node's name in a ros2_control-style configuration).
YAML_NODE = "dfa_wall"
_ASCII = {"·": "*", "²": "^2", "Δ": "Delta", "μ": "mu", "β": "beta", "σ": "sigma", "ξ": "xi", "φ": "phi", "±": "+-",
          "−": "-", "≥": ">=", "≤": "<=", "–": "-", "—": "-", "’": "'"}  # fmt: skip


def _ascii(text: str) -> str:
    """``text`` for a C comment: ASCII (units spelt out, any other character ``?``), no ``*/``."""
    for k, v in _ASCII.items():
        text = text.replace(k, v)
    return text.encode("ascii", "replace").decode("ascii").replace("*/", "* /")


def _literal(x: float) -> str:
    """A double as a C literal that reads back exactly (the shortest round trip, parenthesised when negative)."""
    text = repr(float(x))
    if not math.isfinite(x):
        raise DFAValueError(f"constant = {text} is invalid in C: it must be finite")
    return f"({text})" if text.startswith("-") else text


def deployable(source: object, command: str | None = None) -> DeployableWall:
    """The wall to export of ``source``: a :class:`DeployableWall` (as it is), a :class:`Recommendation` (its K and
    rule), a tuning (:func:`dfa.tune`'s best wall) or one of its walls, or a :class:`Loop` with a stiffness (rule
    ``given``).

    Parameters
    ----------
    source : DeployableWall, Recommendation, TuneResult, TunedWall or Loop
        What to export.
    command : str or None, optional
        The command line that made it, for a Recommendation or a Loop (default None).

    Returns
    -------
    DeployableWall
    """
    if isinstance(source, DeployableWall):
        return source
    if isinstance(source, TuneResult):
        if source.best is None:
            raise DFAValueError(f"source = a tuning with no best wall is invalid: {source.status.message}")
        source = source.best
    if isinstance(source, TunedWall):
        if source.recommendation is None:
            raise DFAValueError(
                "source = a wall only screened is invalid: it has no recommended K; give a simulated one"
            )
        source = source.recommendation
    if isinstance(source, Recommendation):
        return DeployableWall.from_recommendation(source, command)
    if isinstance(source, Loop):
        return DeployableWall.given(source, command)
    raise DFATypeError(
        f"source of type {type(source).__name__} is invalid: give a dfa.DeployableWall, a Recommendation "
        "(dfa.recommend_stiffness), a dfa.tune result or a dfa.Loop(device, wall) with its stiffness"
    )


def export(source: object, format: str = "c", *, command: str | None = None) -> str:
    """The wall to deploy as text: a C99 header, a YAML parameter file or JSON.

    Parameters
    ----------
    source : DeployableWall, Recommendation or Loop
        The wall (:func:`deployable`): a recommendation's K with its rule, or a loop's own K (rule ``given``).
    format : {"c", "yaml", "json"}, optional
        The text (default ``"c"``: :func:`c_header`; :func:`yaml_text`, :func:`json_text`).
    command : str or None, optional
        Keyword only: the command line that made it, stated in the text (default None).

    Returns
    -------
    str
        The header, the YAML or the JSON, ready to write to a file.

    Raises
    ------
    DFAValueError
        For an unknown format, or a recommendation with no K.

    See Also
    --------
    DeployableWall : The wall to deploy, its provenance and its JSON.
    c_header, yaml_text, json_text : Each format.
    """
    if format not in FORMATS:
        raise DFAValueError(f"format = {format!r} is invalid: it must be one of {', '.join(FORMATS)}; give e.g. 'c'")
    dep = deployable(source, command)
    return {"c": c_header, "yaml": yaml_text, "json": json_text}[format](dep)


# ------------------------------------------------------------------ the C header
def _origin(dep: DeployableWall) -> list[str]:
    """Where K comes from, in words: the speed, the rule and its numbers."""
    u = dep.device.units
    k = f"K = {dep.stiffness:.6g} {u['stiffness']}"
    if dep.rule is DeployRule.GIVEN:
        return [f"{k}, given (rule 'given'): no impact speed chose it, and nothing here proves it passive."]
    head = f"{k}, chosen for an impact speed of {dep.velocity:.6g} {u['velocity']} by the rule '{dep.rule.value}': "
    if dep.rule is DeployRule.PROVEN:
        why = f"the largest K the criterion proves passive at this speed (K_criterion = {dep.k_basis:.6g})."
    else:
        limit = (
            "the simulated no-divergence limit" if dep.rule is DeployRule.SIMULATED else "the top of the range searched"
        )
        why = (
            f"no proof at this speed; {limit}, {dep.k_basis:.6g} {u['stiffness']} (no simulated impact up to this "
            f"speed diverged below it), divided by the gain margin {dep.margin:g}. Not a proof."
        )
    return [head + why]


def _elements_text(dep: DeployableWall) -> list[str]:
    """The firmware's elements with their physical values, and what is left out."""
    u, wall = dep.device.units, dep.loop.wall
    assert wall is not None
    parts = [f"spring K = {dep.stiffness:.6g} {u['stiffness']} on the encoder's reading (Delta = "
             f"{dep.device.resolution:.6g} {u['position']}, T = {dep.device.period:.6g} s)"]  # fmt: skip
    if wall.delay:
        parts.append(f"delay {wall.delay} sample{'s' if wall.delay != 1 else ''}")
    if wall.damping:
        parts.append(f"damper B = {wall.damping:.6g} {u['damping']} on the backward difference")
    if wall.filter_cutoff is not None:
        parts.append(f"first-order velocity filter f_c = {wall.filter_cutoff:.6g} Hz")
    if wall.one_sided:
        parts.append(f"one-sided wall, surface s = {wall.surface:g} counts")
    pc = wall.element(PassivityController)
    if pc is not None:
        win = "an unbounded observer" if pc.window is None else f"window {pc.window:g} s"
        lim = "no force limit" if pc.force_limit is None else f"force limit {pc.force_limit:.6g} {u['force']}"
        parts.append(f"passivity observer and controller ({win}, {lim})")
    fl = wall.element(ForceLimit)
    if fl is not None:
        parts.append(f"actuator force limit F_max = {fl.max_force:.6g} {u['force']}")
    lines = ["Firmware: " + "; ".join(parts) + "."]
    if dep.outside:
        left = "; ".join(f"{type(e).__name__} ({_value_text(e, u)}): {why}" for e, why in dep.outside)
        lines.append(f"Not exported (modelled by dfa, not the firmware's: leave them to the hardware): {left}.")
    return lines


def _value_text(e: Any, units: dict[str, str]) -> str:
    """An element's physical value in a few words (:attr:`~dfa.model.elements.Element.parameter`)."""
    par = type(e).parameter
    unit = par.units[1] if units.get("force") == "N·m" else par.units[0]
    return f"{par.name} = {e.value:.6g} {unit}"


def _intro(dep: DeployableWall) -> list[str]:
    """The header's comment: the device, the speed, the rule, the command, the elements, the use."""
    dev, fu = dep.device, dep.device.units["force"]
    rotary = " (rotary: angles in rad, torques in N*m)" if dev.rotary else ""
    paras = [
        [f"Virtual wall for {device_title(dev)}, exported by dfa {dep.dfa_version}{rotary}."],
        [f"Device: m = {dev.mass:.6g} {dev.units['mass']}, b = {dev.damping:.6g} {dev.units['damping']}, "
         f"c = {dev.coulomb:.6g} {dev.units['coulomb']}, Delta = {dev.resolution:.6g} {dev.units['resolution']}, "
         f"T = {dev.period:.6g} s" + ("" if dev.max_force is None else f", F_max = {dev.max_force:.6g} {fu}")
         + ("" if dev.travel is None else f", travel +-{dev.travel:.6g} {dev.units['position']}") + "."],
        _origin(dep),
        [f"Command: {dep.command}" if dep.command else "Made through the API (dfa.export), not the command line."],
        _elements_text(dep),
        ["The reference implementation of the wall as dfa models it (its simulator's controller, "
         "dfa/core/wall_kernel.py), in the same dimensionless arithmetic in the same order: positions in encoder "
         "counts, forces in units of the force of one count, K*Delta, multiplied by K*Delta at the end. Compiled "
         "without floating-point contraction (gcc/clang: -ffp-contract=off) it gives the simulator's forces to the "
         "last bit; with it, to rounding."],
        ["Use: dfa_wall_t w; dfa_wall_init(&w); then once per sample period, after reading the encoder, "
         f"F = dfa_wall_force(&w, counts): the force in {fu} to command for the next sample, positive along +x "
         "(counts increase along +x; position = counts * DFA_WALL_RESOLUTION). The first call's reading starts "
         "the wall (r_{-1} = r_0, every pending command the one at r_0)."],
    ]  # fmt: skip
    out: list[str] = []
    for para in paras:
        for text in para:
            out += textwrap.wrap(_ascii(text), 100, break_long_words=False, break_on_hyphens=False) or [""]
        out.append("")
    return out[:-1]


def _constants(dep: DeployableWall) -> list[tuple[str, str, str]]:
    """The header's #defines: (name, C literal, comment)."""
    dev, u = dep.device, dep.device.units
    p = dep.firmware_params
    rows = [
        ("DFA_WALL_STIFFNESS", _literal(dep.stiffness), f"K, {u['stiffness']}"),
        ("DFA_WALL_RESOLUTION", _literal(dev.resolution), f"Delta, {u['position']} per count"),
        ("DFA_WALL_PERIOD", _literal(dev.period), "T, s: one call of dfa_wall_force per period"),
        ("DFA_WALL_FORCE_STEP", _literal(dep.force_step), f"K*Delta, {u['force']}: the force of one count"),
        ("DFA_WALL_DELAY", str(p.delay), "d, samples from a reading to its force"),
        ("DFA_WALL_DAMPING", _literal(p.damping), "beta_B = B/(K T), dimensionless (0: no damper)"),
    ]
    if p.group(VelocityFilter) is not None:
        rows.append(("DFA_WALL_FILTER_POLE", _literal(p.filter_pole), "a = exp(-2 pi f_c T), the filter's pole"))
    surface = p.group(OneSided)
    if surface is not None:
        rows.append(("DFA_WALL_SURFACE", _literal(surface), "s, counts: the one-sided wall's surface"))
    pc = p.group(PassivityController)
    if pc is not None and surface is not None:
        rows.append(("DFA_WALL_SURFACE_READING", _literal(math.floor(surface + 0.5)), "floor(s + 1/2): the first "
                     "reading inside"))  # fmt: skip
    if pc is not None and pc[0] > 0:
        rows.append(("DFA_WALL_PC_WINDOW", str(pc[0]), "W, samples: the passivity observer's window"))
    if pc is not None and pc[1] is not None:
        rows.append(("DFA_WALL_PC_LIMIT", _literal(pc[1]), "f_max, K*Delta: the most force the controller adds"))
    limit = p.group(ForceLimit)
    if limit is not None:
        rows.append(("DFA_WALL_FORCE_LIMIT", _literal(limit), "phi_max = F_max/(K Delta): the actuator's limit"))
    return [(n, v, _ascii(c)) for n, v, c in rows]


@lru_cache(maxsize=1)
def _template() -> Any:
    import jinja2

    env = jinja2.Environment(
        loader=jinja2.PackageLoader("dfa.render", "templates"),
        autoescape=False,  # C, not HTML
        trim_blocks=True,
        lstrip_blocks=True,
        keep_trailing_newline=True,
        undefined=jinja2.StrictUndefined,
    )
    return env.get_template("wall.h.j2")


def c_header(dep: DeployableWall) -> str:
    """The wall as a self-contained C99 header (module docstring): its constants and its reference implementation.

    Parameters
    ----------
    dep : DeployableWall
        The wall to deploy.

    Returns
    -------
    str
        The header's text (ASCII); compiles warning-free with ``cc -std=c99 -Wall -Wextra -pedantic``.
    """
    p = dep.firmware_params
    pc = p.group(PassivityController)
    return str(
        _template().render(
            intro=_intro(dep),
            constants=_constants(dep),
            filter=p.group(VelocityFilter) is not None,
            one_sided=p.group(OneSided) is not None,
            pc=pc is not None,
            window=pc is not None and pc[0] > 0,
            pc_limit=pc is not None and pc[1] is not None,
            force_limit=p.group(ForceLimit) is not None,
            force_unit=_ascii(dep.device.units["force"]),
        )
    )


# ------------------------------------------------------------------ YAML and JSON
def _no_nulls(data: Any) -> Any:
    """``data`` without None, empty text and ``null_reasons`` (a ROS parameter cannot be null or empty)."""
    if isinstance(data, dict):
        return {k: _no_nulls(v) for k, v in data.items() if v is not None and v != "" and k != "null_reasons"}
    if isinstance(data, (list, tuple)):
        return [_no_nulls(v) for v in data]
    return data


def _parameters(dep: DeployableWall) -> dict[str, Any]:
    """The YAML's numeric parameters: physical (SI; rotary rad, N·m) and the dimensionless ones the C uses."""
    dev, wall = dep.device, dep.loop.wall
    assert wall is not None
    p = dep.firmware_params
    pc, pcg = wall.element(PassivityController), p.group(PassivityController)
    fl = wall.element(ForceLimit)
    physical = {
        "stiffness": dep.stiffness, "resolution": dev.resolution, "period": dev.period, "force_step": dep.force_step,
        "delay": p.delay, "damping": wall.damping, "filter_cutoff": wall.filter_cutoff, "one_sided": wall.one_sided,
        "surface": wall.surface, "pc_window": None if pc is None else pc.window,
        "pc_force_limit": None if pc is None else pc.force_limit, "max_force": None if fl is None else fl.max_force,
    }  # fmt: skip
    dimensionless = {
        "damping": p.damping, "filter_pole": p.filter_pole if p.group(VelocityFilter) is not None else None,
        "surface": p.group(OneSided), "pc_window": None if pcg is None else pcg[0],
        "pc_force_limit": None if pcg is None else pcg[1], "force_limit": p.group(ForceLimit),
    }  # fmt: skip
    return physical | {"passivity_controller": pc is not None, "dimensionless": dimensionless}


def yaml_text(dep: DeployableWall) -> str:
    """The wall as a YAML parameter file for a ros2_control-style configuration.

    ``dfa_wall: ros__parameters:`` holds the physical parameters (SI units; rotary rad, N·m), ``dimensionless``
    the groups the C header uses (β_B, the filter's pole a, s, W, f_max, φ_max), ``units`` the unit of each,
    ``not_exported`` the modelled elements left to the hardware, and ``provenance`` the device, the wall (its
    elements), the impact speed, the rule, the margin, the command and the dfa version, which
    :meth:`DeployableWall.from_dict <dfa.results.deploy.DeployableWall.from_dict>` reads back. No nulls (ROS
    parameters have none): an absent value is left out.

    Parameters
    ----------
    dep : DeployableWall
        The wall to deploy.

    Returns
    -------
    str
        YAML (``yaml.safe_dump``; floats exact).
    """
    import yaml

    u = dep.device.units
    # a ROS parameter holds maps and lists of plain values, no list of maps: the elements by their names
    elements = {}
    for e in dep.wall.elements:
        record = e.to_dict()
        elements[record.pop("element")] = record
    wall = {"stiffness": dep.wall.stiffness, "elements": elements}
    provenance = {
        "device": dep.device.to_dict(), "wall": wall, "velocity": dep.velocity, "rule": dep.rule.value,
        "rule_message": dep.rule.message, "margin": dep.margin, "k_basis": dep.k_basis, "command": dep.command,
        "dfa_version": dep.dfa_version,
    }  # fmt: skip
    units = {"stiffness": u["stiffness"], "resolution": u["position"], "period": "s", "force_step": u["force"],
             "delay": "samples", "damping": u["damping"], "filter_cutoff": "Hz", "surface": "counts",
             "pc_window": "s", "pc_force_limit": u["force"], "max_force": u["force"], "velocity": u["velocity"]}  # fmt: skip
    numbers = _no_nulls(to_jsonable(_parameters(dep)))
    units = {k: v for k, v in units.items() if k in numbers or k == "velocity"}  # the units of the values given
    params = numbers | {"units": units, "not_exported": dep.not_exported or None, "provenance": provenance}
    data = {YAML_NODE: {"ros__parameters": _no_nulls(to_jsonable(params))}}
    return str(yaml.safe_dump(data, sort_keys=False, allow_unicode=True, default_flow_style=False, width=120))


def json_text(dep: DeployableWall) -> str:
    """The wall as JSON: :meth:`DeployableWall.to_dict <dfa.results.deploy.DeployableWall.to_dict>`, every number
    exact (not rounded to :data:`dfa.jsonable.JSON_DIGITS`: the firmware's constants are formed from them), which
    ``dfa export --from FILE.json`` reads back.

    Parameters
    ----------
    dep : DeployableWall
        The wall to deploy.

    Returns
    -------
    str
        One JSON object, indented, with a final newline.
    """
    return json.dumps(dep.to_dict(), indent=2, allow_nan=False, ensure_ascii=False) + "\n"
