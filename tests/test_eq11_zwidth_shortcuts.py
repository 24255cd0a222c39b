"""The Z-width's shortcuts change no number (issue 43): where a damper is above the largest B with which eq. 11
proves any K (dfa.analysis.limits.kmax.damper_forbids), the criterion's K is the 0 its halving down to 1e-300 N/m
finds; and a column's describing-function limit, whose search grid takes the column's criterion and linear bound
instead of computing them again, is the one dfa.analysis.limits.kmax.describing_limit finds alone."""

import pytest

import dfa.analysis.limits.kmax as kmax
import dfa.analysis.limits.zwidth as zmod
from dfa.analysis.limits.kmax import damper_forbids, describing_limit, max_proven_damping, wall_k_criterion
from dfa.analysis.limits.require import damper_guidance
from dfa.model.catalogue import get_device
from dfa.model.elements import Delay, OneSided
from dfa.model.wall import Wall

#: Dampers as multiples of the largest B with which the criterion proves some K: both sides of it, and close.
FACTORS = (0.5, 0.999999, 1.000001, 1.01, 2.0)


def _walls(dev):
    """Walls whose criterion the halving decides: spring, delay, filter, one-sided (its impact speed grows with K)."""
    return (
        Wall(1.0),
        Wall.of(1.0, delay=1),
        Wall.of(1.0, filter_cutoff=0.05 / dev.period),
        Wall(1.0, (OneSided(0.0), Delay(1))),
    )


@pytest.mark.parametrize("name", ["Delta", "Impulse Engine", "Phantom 1.0"])
@pytest.mark.parametrize("v", [0.02, 0.2])
def test_eq11_damper_forbids_gives_the_halvings_k_criterion(name, v, monkeypatch):
    """wall_k_criterion with the shortcut equals it without (exactly), and the shortcut fires above the bound."""
    dev = get_device(name).device
    fired = 0
    for base in _walls(dev):
        top = max_proven_damping(dev, base, v)
        for f in FACTORS:
            wall = base.with_damping(top * f)
            fast = wall_k_criterion(dev, wall, v)
            with monkeypatch.context() as m:
                m.setattr(kmax, "damper_forbids", lambda *a: False)
                slow = wall_k_criterion(dev, wall, v)
            assert fast == slow, (name, v, base, f)
            fired += damper_forbids(dev, wall, v)
            assert damper_forbids(dev, wall, v) == (f > 1.0)
    assert fired == 3 * len(_walls(dev))


def test_eq11_max_proven_damping_is_damper_guidance_bound():
    """One formula: the guidance's largest B is max_proven_damping's, to the bit."""
    dev = get_device("Delta").device
    for wall in (Wall.of(1.0, damping=2.0), Wall.of(1.0, damping=7.0, filter_cutoff=300.0)):
        assert damper_guidance(dev, wall, 0.1).max_virtual_damping == max_proven_damping(dev, wall, 0.1)


@pytest.mark.parametrize("b", [0.0, 2.0, 6.0])
def test_eq11_zwidth_column_df_limit_equals_describing_limit_alone(b):
    """The column's k_df (criterion and linear bound passed in) is describing_limit's computed from scratch."""
    dev = get_device("Delta").device
    wall = Wall.of(1.0, delay=1).with_damping(b)
    ks, _ = zmod._grids(dev, Wall.of(1.0, delay=1), 4, None, (0.0, 8.0), 0.1)
    col = zmod._column(dev, wall, 0.1, ks, "half-delay")
    alone = describing_limit(dev, wall, 0.1, "half-delay", None, zmod.DF_GRID)
    assert col[zmod.ZWIDTH_METHODS.index("df")] == alone
