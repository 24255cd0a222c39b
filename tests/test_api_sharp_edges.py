"""Sharp edges of the API found by the fuzz (issue 41 §3) and their siblings: flags read by their truth value, and
finite inputs whose result leaves a float. Each is now the package's error naming the parameter (DFATypeError for a
flag that is not True or False, DFAValueError naming the value and the rule), never numpy's ValueError, a
ZeroDivisionError or an infinite result.
"""

from __future__ import annotations

import numpy as np
import pytest

import dfa
from dfa.errors import DFATypeError, DFAValueError
from dfa.model.elements import OneSided

#: Values that are not True or False: an empty array raised numpy's "truth value ... is ambiguous", the others
#: were read by their truth value.
NOT_BOOLS = [np.array([]), np.array([True, False]), "no", 1]


@pytest.mark.parametrize("value", NOT_BOOLS, ids=["empty", "two", "text", "one"])
def test_boolean_flags_are_checked(value):
    """approach_start(quantize=...) and its siblings taking a flag (OneSided.engage, contact_excess, contact_speed,
    design_answer(assess=...)) refuse a value that is not True or False, naming the flag."""
    with pytest.raises(DFATypeError, match=r"^quantize = .* it must be True or False"):
        dfa.approach_start(0.2, quantize=value)
    with pytest.raises(DFATypeError, match=r"^quantized = .* it must be True or False"):
        OneSided.engage(0.3, value)
    with pytest.raises(DFATypeError, match=r"^quantized = "):
        OneSided.contact_excess(0.3, 1.0, value)
    with pytest.raises(DFATypeError, match=r"^quantized = "):
        OneSided.contact_speed(0.3, 1.0, 2.0, delay=1, quantized=value)
    dev = dfa.get_device("delta").device
    with pytest.raises(DFATypeError, match=r"^assess = "):
        dfa.design_answer(dev, 0.05, wall=1000.0, assess=value)


def test_approach_start_refuses_a_start_beyond_a_float():
    """approach_start(np.longdouble(1.797e308)) returned the start −inf: refused, naming xi_dot and the overflow."""
    with pytest.raises(DFAValueError, match=r"^xi_dot = 1\.797e\+308 is invalid with samples = 2: .* overflows"):
        dfa.approach_start(np.longdouble(1.797e308))
    start, v, d = dfa.approach_start(1e6, samples=3, phase=0.0)  # large but a float: the formula ξ_e − V D
    assert (start, v, d) == (pytest.approx(-3e6, rel=1e-15), 1e6, 3)


@pytest.mark.filterwarnings("ignore::dfa.ImplausibleInputWarning")  # T = 1e-9 s: no haptic device
def test_stiffness_for_a_group_never_divides_by_zero():
    """Device.stiffness_for_sigma(np.longdouble(1e-320)) raised ZeroDivisionError (σΔ underflows to 0); the same
    for stiffness_for_mu and stiffness_for_beta (one helper): refused as an overflow of K naming the group; a K
    below the smallest normal float is refused too (its groups overflow)."""
    dev = dfa.Device(0.32, 4.0, 0.2, 1e-5, 1e-9)
    cases = [(dev.stiffness_for_sigma, np.longdouble(1e-320), "sigma"), (dev.stiffness_for_sigma, 1e-320, "sigma"),
             (dev.stiffness_for_beta, 1e-320, "beta"), (dev.stiffness_for_mu, 2.3e-308, "mu")]  # fmt: skip
    for method, value, name in cases:
        with pytest.raises(DFAValueError, match=rf"^{name} = .* is invalid for this device: K = .* overflows a float"):
            method(value)
    tiny = dfa.Device(0.32, 4.0, 1e-300, 1e-5, 1e-3)
    with pytest.raises(DFAValueError, match=r"^sigma = 1e\+20 is invalid for this device: K = c/\(σ Δ\) = .* vanishes"):
        tiny.stiffness_for_sigma(1e20)
    assert dev.stiffness_for_sigma(0.5) == pytest.approx(2 * 0.2 / 1e-5, rel=1e-15)  # eq. 9: K = 2c/Δ


def test_closed_form_cycles_refuse_an_amplitude_beyond_a_float():
    """small_cycle_closed_form at σ = 1e-320 (β = 0) and large_cycle_closed_form at σ = 1.797e308 returned M = inf
    with status ok: refused, naming the groups."""
    with pytest.raises(DFAValueError, match=r"sigma = 1e-320 is invalid here: the cycle's amplitude M overflows"):
        dfa.small_cycle_closed_form(1.0, 0.0, 1e-320)
    with pytest.raises(DFAValueError, match=r"sigma = 1\.797e\+308 is invalid here: the cycle's amplitude M overflows"):
        dfa.large_cycle_closed_form(1.0, 0.3, 1.797e308)
    m, w = dfa.small_cycle_closed_form(1.0, 0.0, 1e-3)  # a small σ still has its (large) cycle
    assert w == pytest.approx(2 * np.arcsin(2e-3), rel=1e-12) and m == pytest.approx(
        2 * np.cos(w / 2) / (np.pi * w * w)
    )
