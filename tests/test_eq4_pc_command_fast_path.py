"""The controller kernel's held-force path (:func:`dfa.core.wall_kernel._pc_command`) against the general one
(:func:`dfa.core.wall_kernel._controlled`, Hannaford and Ryu's controller, eq. 4's loop): the same force, command and
mode, bit for bit, on every combination of ledgers around the limit, readings' differences (whole numbers with the
encoder, as r_h − r_{h−1} is) and commands, signed zeros, infinities and NaN included."""

import itertools
import math
import struct

import pytest

from dfa.core.wall_kernel import HELD, _controlled, _pc_command


def _bits(values):
    """The values as bit patterns (±0 differ; NaN equals NaN of the same payload)."""
    return tuple(struct.pack("<d", float(v)) if isinstance(v, float) else v for v in values)


LIMITS = [0.38, 3.633, 1.0, 0.0, math.inf]
VHS = [-2.0, -1.0, -0.0, 0.0, 1.0, 2.0, 3.0, math.nan, math.inf, -math.inf]  # with the encoder: whole numbers
WS = [-0.5, -1.5, 0.5, 2.5, -3.25, 0.0, -0.0, math.inf, -math.inf, math.nan]


@pytest.mark.parametrize("limit", LIMITS)
@pytest.mark.parametrize("onesided", [False, True])
@pytest.mark.parametrize("quantize", [True, False])
def test_eq4_pc_command_fast_path_is_controlled_bit_for_bit(limit, onesided, quantize):
    ledgers = [-1e9, -2 * limit, -limit, -math.nextafter(limit, 0.0), -0.5 * limit, -0.0, 0.0, 1.0, -math.inf,
               math.nan]  # fmt: skip
    ctl = (0.0, 0.0, False, 0.0, 0.0, onesided, 0.0, 0.0, True, 0, limit, math.inf, math.inf)
    vhs = VHS if quantize else [*VHS, 0.5, -0.25, 1e-300]
    for ledger, vh, w in itertools.product(ledgers, vhs, WS):
        c = w if not onesided else min(w, 0.0)  # the command the caller passes: w through a one-sided wall's clip
        got = _pc_command(ledger, vh, w, c, True, ctl, quantize)
        want = _controlled(ledger, vh, w, c, True, ctl)
        assert _bits(got) == _bits(want), (ledger, vh, w, limit, onesided, quantize)


def test_eq4_pc_command_fast_path_held_chatter_values():
    # a chatter's readings: v_h = ±1 at a ledger far below the limit gives ∓limit and HELD; v_h = 0 gives +0, mode 0
    ctl = (0.0, 0.0, False, 0.0, 0.0, False, 0.0, 0.0, True, 0, 0.38, math.inf, math.inf)
    assert _pc_command(-5.0, 1.0, -0.5, -0.5, True, ctl, True) == ((-0.5 - 0.38) + 0.5, -0.5 - 0.38, HELD)
    assert _pc_command(-5.0, -1.0, -0.5, -0.5, True, ctl, True) == ((-0.5 + 0.38) + 0.5, -0.5 + 0.38, HELD)
    f, c, mode = _pc_command(-5.0, 0.0, -0.5, -0.5, True, ctl, True)
    assert (math.copysign(1.0, f), f, c, mode) == (1.0, 0.0, -0.5, 0)
