"""dfa: passivity, limit cycles and stiffness limits of sampled, quantized haptic devices.

Implements and extends N. Diolaiti, G. Niemeyer, F. Barbagli and J. K. Salisbury,
"A Criterion for the Passivity of Haptic Devices", Proc. IEEE ICRA 2005.

The numerical core works in the paper's dimensionless parameters (Table 1)
μ = m/(K T²), β = b/(K T), σ = c/(K Δ); physical units appear only in
:class:`Device`, the catalogue, the command line and report labels.

Naming scheme of analyses and results
-------------------------------------
An analysis is a function named for what it computes; it returns a frozen
result named for the same thing:

- noun → the noun in CamelCase: ``stiffness_limits`` → :class:`StiffnessLimits`,
  ``stability_map`` → ``StabilityMap``, ``contour_maps`` → ``ContourMaps``,
  ``growth_threshold`` → ``GrowthThreshold``, ``criterion_soundness`` → ``CriterionSoundness``;
- verb or criterion → the noun + ``Result``: ``simulate`` → ``SimulationResult``,
  ``passivity_criterion`` / ``device_criterion`` → :class:`CriterionResult`,
  ``limit_cycles`` → ``LimitCycleResult``, ``validate`` → ``ValidationResult``;
- a response over frequency or speed, as in python-control: ``*_response`` →
  ``*Response``: ``nyquist_locus_response`` → ``NyquistLocusResponse``,
  ``stiffness_response`` → :class:`StiffnessResponse`.

Every result carries its inputs and a ``status``, a member of an enum of
:mod:`dfa.results.status` whose ``message`` says what it means; numpy arrays in results
are read-only copies; ``to_dict()`` returns strict-JSON data (NaN and infinities
become null, with the reason under ``null_reasons``; :mod:`dfa.jsonable`);
results with a figure have ``.plot(ax=None)`` returning the matplotlib Axes
(matplotlib loads then, never on ``import dfa``); maps and contours have
``to_xarray()`` (optional extra ``pip install 'dfa-haptics[xarray]'``).

Examples
--------
>>> import dfa
>>> dev = dfa.get_device("Delta").device
>>> p = dev.params(stiffness=14500.0)
>>> r = dfa.passivity_criterion(p.beta, p.sigma, xi_dot=dev.xi_dot(0.1))
>>> r.region, r.passive, r.status.value
('e', True, 'passive_below_critical_speed')
>>> r.status.message
'passive up to the critical speed: the energy cannot grow (proven)'
>>> r.to_dict()["status"]
'passive_below_critical_speed'
"""

from typing import TYPE_CHECKING

from .analysis.criterion import (
    REGION_DESCRIPTIONS,
    CriterionResult,
    CriticalLine,
    classify_region,
    device_criterion,
    passivity_criterion,
)
from .errors import DeviceFileError, DFAError, DFATypeError, DFAValueError, ImplausibleInputWarning
from .model.catalogue import (
    DEFAULT_DEVICE,
    CatalogueEntry,
    Discrepancy,
    ResolvedDevice,
    catalogue,
    device_template,
    get_device,
    load_device_file,
    resolve_device,
)
from .model.device import Device, Params
from .model.elements import (
    AmplifierLag,
    Damper,
    Delay,
    ForceLimit,
    HandSpring,
    OneSided,
    PassivityController,
    Push,
    Travel,
    VelocityFilter,
)
from .model.grasp import hold
from .model.hand import HAND_PRESETS, Hand, HandNotCovered, get_hand
from .model.loop import Loop
from .model.wall import Wall, WallParams

if TYPE_CHECKING:  # loaded on first use (_DEFERRED): `dfa check` needs none of them
    from .analysis.check import PassivityCheck, passivity_check
    from .analysis.colgate_schenkel import (
        ColgateSchenkel,
        ColgateSchenkelDamping,
        colgate_schenkel_beta,
        colgate_schenkel_damping,
    )
    from .analysis.limits.closed_form import (
        StiffnessLimits,
        StiffnessResponse,
        gil_beta_critical,
        k_abbott_okamura,
        k_colgate,
        k_gil,
        k_max_criterion,
        max_passive_velocity,
        stiffness_limits,
        stiffness_response,
    )
    from .analysis.linear_wall import StableRegion, StiffnessIntervals, stable_region, stable_stiffness
    from .model.log import DeviceLog, LogError, read_log

    __version__: str  # looked up on first use (__getattr__)

#: The distribution's name on the package index ("dfa" there is an unrelated project); ``import dfa`` and
#: the ``dfa`` command keep their names.
DISTRIBUTION = "dfa-haptics"


def _version() -> str:
    """The installed distribution's version (pyproject.toml is the only place that states it)."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version(DISTRIBUTION)
    except PackageNotFoundError:  # pragma: no cover - running from a source tree that was never installed
        return "0+unknown"


# Modules that need python-control are imported on first use: python-control
# itself imports matplotlib, and `import dfa` must stay free of it.
_LAZY = {
    "quantizer_df": "analysis.describing",
    "quantizer_df_inverse": "analysis.describing",
    "quantizer_df_peak": "analysis.describing",
    "coulomb_df": "analysis.describing",
    "coulomb_equivalent_damping": "analysis.describing",
    "numeric_df": "analysis.describing",
    "QuantizerNonlinearity": "analysis.nonlinearities",
    "CoulombNonlinearity": "analysis.nonlinearities",
    "LOOP_MODELS": "analysis.loop_models",
    "loop_response": "analysis.loop",
    "loop_system": "analysis.loop",
    "NyquistLocusResponse": "analysis.loop",
    "nyquist_locus_response": "analysis.loop",
    "LimitCycle": "analysis.cycles",
    "LimitCycleResult": "analysis.cycles",
    "limit_cycles": "analysis.cycles",
    "growth_threshold": "analysis.cycles",
    "small_cycle_closed_form": "analysis.cycles",
    "large_cycle_closed_form": "analysis.cycles",
    "SimulationResult": "analysis.simulation",
    "simulate": "analysis.simulation",
    "approach_start": "analysis.approach",
    "preload_position": "analysis.simulation",
    "StabilityMap": "analysis.maps",
    "stability_map": "analysis.maps",
    "load_map": "analysis.maps",
    "ContourMaps": "analysis.contours",
    "contour_maps": "analysis.contours",
    "validate": "studies.validation",
    "design_report": "studies.report",
    "DesignAnalysis": "studies.design",
    "design_analysis": "studies.design",
    "design_answer": "analysis.limits.kmax",
    "KMaxResult": "analysis.limits.kmax",
    "stiffness_speed_chart": "analysis.limits.speed_chart",
    "StiffnessSpeedChart": "analysis.limits.speed_chart",
    "z_width": "analysis.limits.zwidth",
    "ZWidth": "analysis.limits.zwidth",
    "identify": "analysis.identify",
    "observe": "analysis.observer",
    "ObserverSummary": "analysis.observer",
    "passivity_gain": "analysis.limits.passivity_gain",
    "PassivityGain": "analysis.limits.passivity_gain",
    "Identification": "analysis.identify",
    "tune": "analysis.limits.tune",
    "TuneResult": "analysis.limits.tune",
    "TunedWall": "analysis.limits.tune",
    "force_error": "analysis.fidelity",
    "export": "render.export",
    "DeployableWall": "results.deploy",
}
#: Names of the API (listed in ``__all__`` below) whose modules load on their first use, like those of
#: :data:`_LAZY`: ``dfa check`` and most commands need none of them, and each costs start-up time.
_DEFERRED = {
    **dict.fromkeys(("PassivityCheck", "passivity_check"), "analysis.check"),
    **dict.fromkeys(("ColgateSchenkel", "ColgateSchenkelDamping", "colgate_schenkel_beta", "colgate_schenkel_damping"),
                    "analysis.colgate_schenkel"),
    **dict.fromkeys(("StiffnessLimits", "StiffnessResponse", "gil_beta_critical", "k_abbott_okamura", "k_colgate",
                     "k_gil", "k_max_criterion", "max_passive_velocity", "stiffness_limits", "stiffness_response"),
                    "analysis.limits.closed_form"),
    **dict.fromkeys(("StableRegion", "StiffnessIntervals", "stable_region", "stable_stiffness"), "analysis.linear_wall"),
    **dict.fromkeys(("DeviceLog", "LogError", "read_log"), "model.log"),
}  # fmt: skip
_SUBMODULES = {
    "core",
    "model",
    "results",
    "analysis",
    "render",
    "studies",
    "cli",
    "errors",
    "checks",
    "formatting",
}


def __getattr__(name: str):
    import importlib

    where = _LAZY.get(name) or _DEFERRED.get(name)
    if where is not None:
        value = getattr(importlib.import_module(f".{where}", __name__), name)
        globals()[name] = value
        return value
    if name == "__version__":  # importlib.metadata costs start-up time: looked up when asked
        globals()[name] = _version()
        return globals()[name]
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'dfa' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


__all__ = [
    "Device",
    "Params",
    "Loop",
    "Hand",
    "HAND_PRESETS",
    "HandNotCovered",
    "get_hand",
    "hold",
    "DeviceLog",
    "LogError",
    "read_log",
    "Wall",
    "WallParams",
    "Damper",
    "VelocityFilter",
    "Delay",
    "AmplifierLag",
    "HandSpring",
    "OneSided",
    "Push",
    "PassivityController",
    "ForceLimit",
    "Travel",
    "approach_start",
    "stable_stiffness",
    "stable_region",
    "StiffnessIntervals",
    "StableRegion",
    "colgate_schenkel_beta",
    "colgate_schenkel_damping",
    "ColgateSchenkel",
    "ColgateSchenkelDamping",
    "CatalogueEntry",
    "Discrepancy",
    "catalogue",
    "get_device",
    "resolve_device",
    "ResolvedDevice",
    "load_device_file",
    "device_template",
    "DEFAULT_DEVICE",
    "CriterionResult",
    "CriticalLine",
    "passivity_criterion",
    "device_criterion",
    "classify_region",
    "REGION_DESCRIPTIONS",
    "PassivityCheck",
    "passivity_check",
    "StiffnessLimits",
    "stiffness_limits",
    "StiffnessResponse",
    "stiffness_response",
    "k_max_criterion",
    "k_colgate",
    "k_abbott_okamura",
    "k_gil",
    "gil_beta_critical",
    "max_passive_velocity",
    *_LAZY,
    "DFAError",
    "DFAValueError",
    "DFATypeError",
    "DeviceFileError",
    "ImplausibleInputWarning",
]
