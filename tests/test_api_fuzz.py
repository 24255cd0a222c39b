"""Hypothesis fuzz of the public API (issue 17 §6): every name in ``dfa.__all__``.

For every callable the arguments are drawn, parameter by parameter (from
:func:`inspect.signature`), from a mix of valid values and hostile ones (NaN,
infinities, subnormal and huge floats, huge integers, numpy scalars and
arrays, booleans, None, text, complex numbers). The call must either return or
raise the package's own error (:class:`dfa.DFAError`); a returned result must
not hold NaN or infinity unless its status or outcome says why.

Derandomised under the ``ci`` profile (``make test``); ``make explore``
(``HYPOTHESIS_PROFILE=explore``) draws many more random examples (set
``DFA_API_FUZZ_EXAMPLES`` to fix the number of examples per name).
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import os
import tempfile

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import dfa

#: Deliberately outside what haptic devices have (extreme values test the numerics): the plausibility warning
#: (dfa.plausibility) is expected here, and tested in tests/test_plausibility.py.
pytestmark = [
    pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning"),
    pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning"),  # numeric_df's quad at extreme M
]


EXPLORE = os.environ.get("HYPOTHESIS_PROFILE") == "explore"

# ------------------------------------------------------------------ hostile values
HOSTILE = st.one_of(
    st.floats(),  # NaN, ±inf, subnormals, huge
    st.sampled_from([5e-324, 1e-310, 2.2e-308, 1e308, -1e308, -0.0, 0.0, 1e-300, 1e300]),
    st.integers(),
    st.sampled_from([10**400, -(10**400), 2**63, 2**64, -(2**63) - 1]),
    st.sampled_from(
        [
            np.float32(2.5),
            np.float64("nan"),
            np.float16(1.0),
            np.int64(3),
            np.uint8(7),
            np.int64(-(2**63)),
            np.bool_(True),
            np.complex128(1j),
            np.longdouble("1e400"),
        ]
    ),
    st.sampled_from([np.array([1.0, 2.0]), np.array([[1.0]]), np.array(2.0), np.array([]), np.array(["a"])]),
    st.booleans(),
    st.none(),
    st.text(max_size=4),
    st.complex_numbers(),
    st.sampled_from([[1.0], (1.0, 2.0), {}, object(), b"1"]),
)


def _floats(lo: float, hi: float):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


_DEVICES = [e.device for e in dfa.catalogue() if not e.incomplete]
_TMP = tempfile.mkdtemp(prefix="dfa-api-fuzz-")

#: Valid loops (every public analysis takes one first): the groups alone (μ, β, σ, with the spring, a delay or a
#: damper), a device and the spring at no given K (the searches over K), a device and a wall of known K.
_WALL_PARAMS = st.sampled_from([None, dfa.WallParams.of(delay=1), dfa.WallParams.of(damping=0.3, delay=1)])


def _loop(device, wall=None):
    """Loop(device, wall), or the device's search loop when the groups refuse the wall (a damper too fast for a
    light device): a valid loop either way."""
    try:
        return dfa.Loop(device, wall)
    except dfa.DFAError:
        return dfa.Loop(device)


_LOOPS = st.one_of(
    st.builds(dfa.Loop.dimensionless, _floats(1e-2, 1e5), _floats(0.0, 2.0), _floats(0.0, 2.0), _WALL_PARAMS),
    st.builds(_loop, st.sampled_from(_DEVICES)),
    st.builds(_loop, st.sampled_from(_DEVICES), _floats(10.0, 5e4)),
    st.builds(
        _loop,
        st.sampled_from(_DEVICES),
        st.builds(dfa.Wall.of, _floats(10.0, 5e4), _floats(0.0, 2.0), st.integers(0, 2)),
    ),
)

# ------------------------------------------------------------------ valid values, by parameter name
VALID = {
    "loop": _LOOPS,
    "mu": _floats(1e-2, 1e5),
    "beta": _floats(0.0, 2.0),
    "sigma": _floats(0.0, 2.0),
    "xi_dot": _floats(-10.0, 10.0),
    "xi_dot0": _floats(-10.0, 10.0),
    "xi0": _floats(-5.0, 5.0),
    "sigma0": _floats(0.0, 1.0),
    "delay": st.integers(0, 2),
    "quantized": st.booleans(),
    "quantize": st.booleans(),
    "record": st.booleans(),
    "energy": st.booleans(),
    "preload": st.booleans(),
    "rotary": st.booleans(),
    "progress": st.just(False),
    "stiffness": _floats(10.0, 5e4),
    "velocity": _floats(1e-3, 1.0),
    "position": _floats(-1e-3, 1e-3),
    "device": st.sampled_from(_DEVICES),
    "params": st.builds(dfa.Params, _floats(0.5, 1e3), _floats(0.0, 1.0), _floats(0.0, 1.5)),
    "amplitude": st.one_of(_floats(1e-3, 1e4), st.just(np.array([0.5, 1.5, 20.0]))),
    "omega": st.one_of(_floats(1e-2, 3.0), st.just(np.array([0.1, 1.0, 3.0]))),
    "gain": _floats(0.1, 3.0),
    "max_amplitude": _floats(1.0, 300.0),
    "samples": st.integers(1, 3000),
    "grid": st.integers(2, 4),
    "map_grid": st.integers(2, 3),
    "n_jobs": st.just(1),
    "beta_range": st.tuples(_floats(0.0, 0.5), _floats(0.6, 1.5)),
    "sigma_range": st.tuples(_floats(0.0, 0.5), _floats(0.6, 2.0)),
    "xi_dots": st.lists(_floats(0.0, 5.0), min_size=1, max_size=2),
    "model": st.sampled_from(["half-delay", "pade", "zoh"]),
    "pade_order": st.integers(1, 8),
    "describing": st.sampled_from(["exact", "small", "unity"]),
    "name": st.sampled_from([e.name for e in dfa.catalogue()] + ["delta", "PHANTOM"]),
    "f": st.just(lambda x: np.floor(x) + 0.5),
    "jumps": st.just(tuple(float(k) for k in range(-20, 21))),
    "tol": _floats(1e-13, 1e-6),
    "bound": _floats(10.0, 1e6),
    "stable_amplitude": _floats(0.0, 2.0),
    "growth": _floats(1.01, 3.0),
    "settle": _floats(0.0, 0.1),
    "mass": _floats(1e-3, 10.0),
    "damping": _floats(0.0, 10.0),
    "coulomb": _floats(0.0, 1.0),
    "resolution": _floats(1e-7, 1e-3),
    "period": _floats(1e-4, 1e-2),
    "out_dir": st.just(_TMP),  # the report's folder rule is tested with the CLI (test_hardening.py)
    "path": st.just(os.path.join(_TMP, "missing.npz")),
    "fmt": st.sampled_from(["html", "md", "both"]),
    "amplitudes": st.one_of(st.none(), st.just(np.array([0.5, 2.0, 10.0]))),
    "locus_amplitude": st.one_of(st.none(), st.just(np.array([0.5, 2.0, 10.0]))),
    "omega_grid": st.one_of(st.none(), st.just(np.geomspace(1e-2, 3.0, 50))),
    "quick": st.just(True),
    "tune": st.just(False),  # design_analysis's tuning is dfa.tune, fuzzed on its own (EXPENSIVE)
    "configurations": st.none(),  # a WorstConfiguration is built by worst_stiffness, not drawn
}

#: Names that are not callables: checked to be the documented constants.
CONSTANTS = {"DEFAULT_DEVICE", "REGION_DESCRIPTIONS", "LOOP_MODELS", "HAND_PRESETS"}

#: Result records: built by the package from validated inputs, not by users (their construction-time
#: validation is the result-objects work); the fuzz calls the functions that return them instead.
RESULTS = {
    "CatalogueEntry",
    "Discrepancy",
    "CriterionResult",
    "StiffnessLimits",
    "NyquistLocusResponse",
    "LimitCycle",
    "LimitCycleResult",
    "SimulationResult",
    "StabilityMap",
    "ContourMaps",
    "StiffnessIntervals",
    "StableRegion",
    "ColgateSchenkel",
    "ColgateSchenkelDamping",
    "ZWidth",
    "Identification",
    "DeviceLog",
}

#: Calls that take seconds when every argument is valid: only their refusals are fuzzed
#: (a valid draw is replaced by a call with one argument known to be refused).
EXPENSIVE = {"validate", "design_report", "stiffness_speed_chart", "z_width", "tune"}

#: Examples per name under ``ci`` (the profile's default for the rest); costly names get fewer.
EXAMPLES = {
    "stability_map": 25,
    "contour_maps": 25,
    "limit_cycles": 40,
    "growth_threshold": 40,
    "nyquist_locus_response": 30,
    "loop_system": 30,
    "validate": 40,
    "design_report": 40,
}

#: The package's error types (builtin signatures): checked to derive from DFAError and the builtins.
ERRORS = {
    "DFAError",
    "DFAValueError",
    "DFATypeError",
    "DeviceFileError",
    "ImplausibleInputWarning",
    "HandNotCovered",
    "LogError",
}

NAMES = [n for n in dfa.__all__ if n not in CONSTANTS | RESULTS | ERRORS]


#: Sizes (run lengths, grids, search ranges) of calls whose cost grows with them: a hostile draw that is a
#: valid but large size (the API runs what it is asked) is left out; larger than int64 stays in (refused).
SIZES = {"grid", "map_grid", "samples", "max_amplitude"}
SIZED = {"contour_maps", "stability_map", "design_report", "simulate"}


def _big_valid_size(x) -> bool:
    if isinstance(x, (bool, np.bool_)) or not isinstance(x, (int, float, np.integer, np.floating)):
        return False
    try:
        return 10.0 < float(x) <= 2.0**63
    except OverflowError:
        return False


def _arg(param: str, name: str = ""):
    """A value for ``param``: valid three times in four (when a valid strategy is known), else hostile."""
    hostile = HOSTILE.filter(lambda x: not _big_valid_size(x)) if param in SIZES and name in SIZED else HOSTILE
    valid = VALID.get(param)
    if valid is None:
        return hostile
    return st.integers(0, 3).flatmap(lambda k: hostile if k == 0 else valid)


def _nonfinite(obj, depth: int = 0) -> list:
    """Paths to NaN or infinite numbers inside a returned object (numbers, arrays, tuples, dicts, dataclasses)."""
    if depth > 6:
        return []
    if isinstance(obj, (bool, np.bool_, str, type(None))):
        return []
    if isinstance(obj, (float, np.floating, complex, np.complexfloating)):
        return [] if np.isfinite(obj) else [repr(obj)]
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fc" and not np.isfinite(obj).all():
            return [f"array with {int((~np.isfinite(obj)).sum())} non-finite"]
        return []
    if isinstance(obj, dict):
        return [f"{k}: {p}" for k, v in obj.items() for p in _nonfinite(v, depth + 1)]
    if isinstance(obj, (tuple, list)):
        return [f"[{i}] {p}" for i, v in enumerate(obj) for p in _nonfinite(v, depth + 1)]
    if hasattr(obj, "to_dict"):
        return _nonfinite(obj.to_dict(), depth + 1)
    if dataclasses.is_dataclass(obj):
        return _nonfinite({f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}, depth + 1)
    return []


def _explains_nonfinite(obj) -> bool:
    """True when the result itself says why it holds NaN or infinity (a status or outcome other than ok)."""
    status = getattr(obj, "status", None)
    if isinstance(status, str) and status != "ok":
        return True
    return getattr(obj, "outcome", None) in ("unstable", "undecided")


#: Functions documented to return infinity or NaN for some valid inputs (with the meaning in their docstring).
DOCUMENTED_NONFINITE = {
    "k_colgate",  # inf when the device alone is stable at every stiffness
    "k_abbott_okamura",
    "k_gil",
    "k_max_criterion",
    "max_passive_velocity",
    "gil_beta_critical",
    "numeric_df",
    "quantizer_df_inverse",
}


#: Result fields documented to hold NaN for valid inputs: name -> field -> the documented meaning.
DOCUMENTED_NAN_FIELDS = {"nyquist_locus_response": {"amplitudes": "NaN when σ = 0: the curve does not depend on M"}}


def _check_call(name: str, obj, kwargs: dict) -> None:
    try:
        out = obj(**kwargs)
    except dfa.DFAError as err:
        msg = str(err)
        assert msg and "\n" not in msg and len(msg) < 600, msg
        return
    if name in DOCUMENTED_NONFINITE:
        return
    skip = DOCUMENTED_NAN_FIELDS.get(name, {})
    if skip and dataclasses.is_dataclass(out):
        out_fields = {f.name: getattr(out, f.name) for f in dataclasses.fields(out) if f.name not in skip}
        bad = _nonfinite(out_fields)
    else:
        bad = _nonfinite(out)
    assert not bad or _explains_nonfinite(out), (name, kwargs, bad[:5])


def _strategy_for(name: str, obj):
    sig = inspect.signature(obj)
    fields = {}
    for pname, par in sig.parameters.items():
        if par.kind in (par.VAR_POSITIONAL, par.VAR_KEYWORD):
            continue
        if par.default is not inspect.Parameter.empty and not (pname in SIZES and name in SIZED):
            fields[pname] = st.one_of(st.just(inspect.Parameter.empty), _arg(pname, name))
        elif par.default is not inspect.Parameter.empty:  # a size left out runs the default (contour_maps: 200²)
            fields[pname] = _arg(pname, name)
        else:
            fields[pname] = _arg(pname, name)
    return st.fixed_dictionaries(fields).map(lambda d: {k: v for k, v in d.items() if v is not inspect.Parameter.empty})


class _WouldRun(Exception):
    """Raised in place of the work of an expensive call: its arguments passed validation."""


#: The first piece of work of each expensive call, after its validation (replaced by _WouldRun in the fuzz).
_WORK = {
    "validate": ("dfa.studies.validation", "cycle_checks"),
    "design_report": ("dfa.studies.report", "design_analysis"),
    "stiffness_speed_chart": ("dfa.analysis.limits.speed_chart", "Evidence"),
    "z_width": ("dfa.analysis.limits.zwidth", "_plan"),
    "tune": ("dfa.analysis.limits.tune", "_screened"),
}


@pytest.mark.parametrize("name", NAMES)
def test_api_fuzz_every_public_name(name):
    obj = getattr(dfa, name)
    assert callable(obj)
    n = EXAMPLES.get(name)
    cfg = {} if n is None or EXPLORE else {"max_examples": n}
    if os.environ.get("DFA_API_FUZZ_EXAMPLES"):  # e.g. a time-boxed explore run: examples per name
        cfg = {"max_examples": int(os.environ["DFA_API_FUZZ_EXAMPLES"])}

    @settings(suppress_health_check=list(HealthCheck), **cfg)
    @given(_strategy_for(name, obj))
    def run(kwargs):
        try:
            _check_call(name, obj, kwargs)
        except _WouldRun:
            pass

    if name in EXPENSIVE:
        import importlib

        module, attr = _WORK[name]

        def work(*a, **k):
            raise _WouldRun

        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(importlib.import_module(module), attr, work)
            run()
    else:
        run()


def test_api_fuzz_covers_every_name():
    assert set(NAMES) | CONSTANTS | RESULTS | ERRORS == set(dfa.__all__)
    assert issubclass(dfa.DFAValueError, (dfa.DFAError, ValueError)) and issubclass(dfa.DFATypeError, TypeError)
    assert issubclass(dfa.DeviceFileError, dfa.DFAValueError) and issubclass(dfa.ImplausibleInputWarning, UserWarning)
    assert dfa.DEFAULT_DEVICE in {e.name for e in dfa.catalogue()}
    assert issubclass(dfa.HandNotCovered, dfa.DFAValueError)
    assert all(isinstance(h, dfa.Hand) and h.stiffness >= 0.0 for h in dfa.HAND_PRESETS.values())
    assert dfa.HAND_PRESETS["hapticmaster"].stiffness == 135.0 and dfa.HandSpring(135.0).value == 135.0
    assert set(dfa.LOOP_MODELS) == {"half-delay", "pade", "zoh"}
    assert all(isinstance(v, str) for v in dfa.REGION_DESCRIPTIONS.values())


def test_api_fuzz_finite_check_sees_nan():
    # the checker itself can fail: NaN in a nested result is found, and an "ok" status does not excuse it
    bad = dfa.Params(1.0, 0.1, 0.2)
    assert _nonfinite({"a": (1.0, np.array([np.nan]))}) and not _nonfinite(bad)
    assert not _explains_nonfinite(bad)
    assert math.isnan(float("nan"))
