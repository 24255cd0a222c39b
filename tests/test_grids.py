"""dfa.grids.geometric_grid: the same doubles on every machine, each the exact point rounded once."""

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from dfa.errors import DFAValueError
from dfa.grids import geometric_grid


def _exact(lo: float, hi: float, n: int, endpoint: bool) -> list[float]:
    """Each point start·(stop/start)^(i/m) in 60-digit mpmath, rounded once to a double (an independent method)."""
    m = n - 1 if endpoint else n
    with mpmath.workdps(60):
        ratio = mpmath.mpf(hi) / mpmath.mpf(lo)
        return [float(mpmath.mpf(lo) * ratio ** (mpmath.mpf(i) / m)) for i in range(n)]


@settings(max_examples=60, deadline=None)
@given(
    lo=st.floats(1e-12, 1e6),
    span=st.floats(1.0001, 1e9),
    n=st.integers(2, 300),
    endpoint=st.booleans(),
)
def test_geometric_grid_is_the_exact_grid_rounded_once(lo, span, n, endpoint):
    """Every point is the correctly rounded exact point (40-digit decimal vs 60-digit mpmath), the ends exact, and
    it agrees with numpy.geomspace to a few ulp (numpy's last bit is the machine's)."""
    hi = lo * span
    got = geometric_grid(lo, hi, n, endpoint=endpoint)
    assert got.tolist()[1:-1] == _exact(lo, hi, n, endpoint)[1:-1]
    assert got[0] == lo and (not endpoint or got[-1] == hi)
    assert np.all(np.diff(got) > 0)
    np.testing.assert_allclose(got, np.geomspace(lo, hi, n, endpoint=endpoint), rtol=1e-14, atol=0)


def test_geometric_grid_speed_chart_point_is_off_the_printed_rounding_boundary():
    """The Delta speed chart's criterion grid (K from 15 to 470,933 N/m, 200 points): its point 136 is
    17755.29118275003…, which 12 digits print as …8275 → 17755.2911828 on every machine; numpy's geomspace gave
    17755.29118274999928 here (printed …827) and a double on the other side of the boundary elsewhere."""
    k = geometric_grid(14.999999999999998, 470933.3333333333, 200)[136]
    assert k == _exact(14.999999999999998, 470933.3333333333, 200, True)[136]
    assert f"{k:.12g}" == "17755.2911828"


@pytest.mark.parametrize(
    "args, match",
    [((0.0, 1.0, 3), "finite ends > 0"), ((1.0, float("inf"), 3), "finite ends > 0"), ((1.0, 2.0, 0), "num = 0")],
)
def test_geometric_grid_refuses_what_has_no_geometric_grid(args, match):
    with pytest.raises(DFAValueError, match=match):
        geometric_grid(*args)


def test_geometric_grid_formed_once_and_each_caller_gets_its_own_copy():
    """The grid is cached by its arguments (issue 43: the searches ask for the same grids again and again); a
    caller that writes into its grid changes no later caller's."""
    first = geometric_grid(3.0, 7.0e3, 50)
    expected = first.copy()
    first[:] = -1.0
    again = geometric_grid(3.0, 7.0e3, 50)
    assert np.array_equal(again, expected) and again is not first
