"""Z-width simulations batched (issue 16): every grid point's code equals the previous per-run path, one
:func:`dfa.simulate` per run (paper eq. 4-5 with the controller), and :func:`dfa.core.batch.batch_wall_kernel` equals
:func:`dfa.core.wall_kernel.simulate_wall_kernel` run by run, bit for bit."""

import itertools
import json

import numpy as np
import pytest
from reference import zwidth_point_one_by_one

import dfa.analysis.limits.zwidth as zmod
from dfa.analysis.limits.zwidth import z_width
from dfa.analysis.simulation import OUTCOMES
from dfa.core.batch import batch_wall_kernel
from dfa.core.kernel import NSEG, NSTATS, OSCILLATING, REST, UNDECIDED, UNSTABLE
from dfa.core.table import stack_tables
from dfa.core.wall_kernel import simulate_wall_kernel
from dfa.model.catalogue import get_device
from dfa.model.wall import Wall, WallParams


def _tasks(name, v, d, fc, fbw, grid, speeds, cap=zmod.ZWIDTH_MAX_SAMPLES):
    dev = get_device(name).device
    wall = Wall.of(1.0, delay=d, filter_cutoff=fc, amplifier_bandwidth=fbw)
    ks, bs = zmod._grids(dev, wall, grid, None, None, v)
    vs = v * np.arange(1, speeds + 1) / speeds
    return zmod._plan(dev, wall, ks, bs, [dev.xi_dot(float(s)) for s in vs], cap)[0]


CASES = {
    "spring+damper": ("Impulse Engine", 0.1, 0, None, None, 6, 2),
    "delay+filter": ("Phantom 1.0", 0.1, 1, 100.0, None, 5, 2),
    "delay+lag": ("Impulse Engine", 0.1, 2, None, 300.0, 4, 1),
}


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    tasks = _tasks(*CASES[request.param])
    ref = np.array([zwidth_point_one_by_one(*t) for t in tasks], dtype=np.int8)
    return request.param, tasks, ref


@pytest.mark.parametrize("jobs", [1, 2])
@pytest.mark.parametrize("per_call", [zmod.POINTS_PER_CALL, 5])
def test_eq4_zwidth_grid_codes_equal_one_simulate_per_run(case, jobs, per_call, monkeypatch):
    """Grid codes of the batched path equal the per-run simulate() path (spring row B = 0 included), any chunking."""
    name, tasks, ref = case
    monkeypatch.setattr(zmod, "POINTS_PER_CALL", per_call)
    got = zmod._simulate_grid(tasks, jobs, False, name)
    assert got.dtype == np.int8
    np.testing.assert_array_equal(got, ref)
    assert len(set(ref.tolist())) >= 2  # the grid mixes outcomes: the comparison can fail
    if name == "spring+damper":
        assert tasks[0][1].is_spring and not tasks[-1][1].is_spring
        assert {zmod.DIVERGES, zmod.REST} <= set(ref.tolist())


def test_eq4_zwidth_spring_points_run_the_spring_kernel_like_simulate():
    """A pure-spring point (B = 0, no filter or lag) is a chunk of its own kind: the spring kernel, as simulate()."""
    tasks = _tasks("Impulse Engine", 0.1, 1, None, None, 3, 1)
    chunks = zmod._chunks(tasks, 100)
    kinds = [{tasks[i][1].is_spring for i in c} for c in chunks]
    assert kinds == [{True}, {False}] and len(chunks[0]) == 3


def test_eq4_zwidth_point_code_from_run_codes_is_the_per_run_rule():
    """Every combination of 3 run outcomes gives the code of the previous per-run rule (early exit included)."""
    names = {REST: "rest", OSCILLATING: "oscillating", UNSTABLE: "unstable", 3: "chatter", UNDECIDED: "undecided"}
    assert [names[i] for i in range(5)] == list(OUTCOMES[:5])
    assert OUTCOMES[5:] == ("left", "saturated", "end_stop")  # an element's outcomes: each only with its element
    combos = np.array(list(itertools.product(range(5), repeat=3)))
    got = zmod._point_codes(combos)
    for row, code in zip(combos, got, strict=True):
        outs = set()
        want = None
        for c in row:
            outs.add(names[int(c)])
            if "unstable" in outs:
                want = zmod.DIVERGES
                break
        if want is None:
            want = zmod.UNDECIDED_POINT if "undecided" in outs else (zmod.REST if outs == {"rest"} else zmod.BOUNDED)
        assert code == want, row
    # held by the force limit or stopped by the travel: the point diverges, whatever the other runs did
    for held in (OUTCOMES.index("saturated"), OUTCOMES.index("end_stop")):
        rows = np.array([[held, r, r] for r in range(5)] + [[r, r, held] for r in range(5)])
        assert (zmod._point_codes(rows) == zmod.DIVERGES).all()


@pytest.mark.parametrize("delay", [0, 2])
def test_eq4_batch_ckernel_equals_simulate_ckernel_run_by_run(delay):
    """Each run of batch_wall_kernel (its own length, bound, tail and controller) is simulate_wall_kernel alone, bit for bit."""
    rng = np.random.default_rng(16 + delay)
    k = 40
    mu = 10 ** rng.uniform(0.3, 2.5, k)
    beta = np.where(rng.random(k) < 0.3, 0.0, rng.uniform(0, 1, k))
    sigma = np.where(rng.random(k) < 0.3, 0.0, rng.uniform(0, 2, k))
    x0 = np.where(rng.random(k) < 0.5, 0.0, rng.uniform(-3, 3, k))
    v0 = rng.uniform(-4, 4, k)
    ns = rng.integers(200, 6000, k).astype(np.int64)
    bounds = rng.uniform(50, 1e4, k) + np.abs(x0)
    tails = np.maximum(2, ns // rng.integers(2, 8, k)).astype(np.int64)
    damping = np.where(rng.random(k) < 0.2, 0.0, rng.uniform(0, 3, k))
    filtered = rng.random(k) < 0.5
    cutoff = rng.uniform(0.02, 0.35, k)  # filter poles e^{−2πν_c} from 0.11 to 0.88
    lag = np.where(rng.random(k) < 0.4, rng.uniform(0.05, 2, k), 0.0)
    walls = [
        WallParams.of(damping=damping[i], delay=delay, cutoff=cutoff[i] if filtered[i] else None, lag=lag[i])
        for i in range(k)
    ]
    tables = stack_tables([w.kernel_table() for w in walls])
    stats, done, rest = np.empty((k, NSTATS)), np.empty(k, dtype=np.int64), np.empty(k, dtype=np.int64)
    batch_wall_kernel((mu, beta, sigma), (x0, v0), (ns, tails, bounds, True), tables, stats, done, rest)
    e = np.empty(0)
    seen = set()
    for i in range(k):
        st = np.empty(NSTATS)
        run = (ns[i], tails[i], bounds[i], True)
        dn, rs = simulate_wall_kernel(
            (mu[i], beta[i], sigma[i]), (x0[i], v0[i]), run, walls[i].kernel_table(), e, e, st
        )
        assert (dn, rs) == (done[i], rest[i])
        np.testing.assert_array_equal(st, stats[i])
        seen.add("rest" if rs >= 0 else ("bound" if st[NSEG + 5] > 0 else "full"))
    assert seen == {"rest", "bound", "full"}


def test_zwidth_boundary_columns_in_worker_processes_equal_one_thread(monkeypatch):
    """From PROCESS_COLUMNS values of B the boundary columns run in worker processes: the same ZWidth as n_jobs=1."""
    dev = get_device("Phantom 1.0").device
    one = z_width(dev, 0.1, wall=Wall.of(1.0, delay=1, filter_cutoff=100.0), grid=3, speeds=1, n_jobs=1).to_dict()
    monkeypatch.setattr(zmod, "PROCESS_COLUMNS", 2)
    calls = []
    real, started = zmod.run_in_order, zmod.started_in_order

    def spy(fn, tasks, sizes, workers, backend, bar):
        calls.append((fn.__name__, backend))
        return real(fn, tasks, sizes, workers, backend, bar)

    def spy_started(fn, tasks, sizes, workers, backend):
        calls.append((fn.__name__, backend))
        return started(fn, tasks, sizes, workers, backend)

    monkeypatch.setattr(zmod, "run_in_order", spy)
    monkeypatch.setattr(zmod, "started_in_order", spy_started)
    zmod.start_workers(3, 2)  # the worker process started ahead (as the command line does) is the one used
    two = z_width(dev, 0.1, grid=3, speeds=1, n_jobs=2, wall=Wall.of(1.0, delay=1, filter_cutoff=100.0)).to_dict()
    # the columns are dispatched to the workers first, then the simulations run on threads beside them
    assert calls == [("_column", "processes"), ("_run_chunk", "threads")]
    assert json.dumps(one, sort_keys=True) == json.dumps(two, sort_keys=True)
