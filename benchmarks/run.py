"""Benchmarks of dfa, reported as ratios against baselines measured in the same run.

Run with ``make bench`` (writes ``reports/benchmarks.md``) or
``python benchmarks/run.py --out FILE [--quick]``. Timings are wall-clock
best-of-N on this machine; only the ratios are meaningful across machines.
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import sys
import time
from datetime import datetime, timezone

import numba
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "tests"))  # the slow reference integrators live with the tests

from plain_kernel import plain_kernel  # noqa: E402
from reference import simulate_control, simulate_ivp, zwidth_point_one_by_one  # noqa: E402

import dfa  # noqa: E402
from dfa.analysis.maps import stability_map  # noqa: E402
from dfa.analysis.simulation import _tail_length, divergence_bound, simulate  # noqa: E402
from dfa.core import batch, kernel  # noqa: E402

# a persistent oscillation, the earlier benchmarks' case; its state (ξ, ξ') repeats bit for bit after
# 3032 samples, so the kernel skips its periods from there (dfa.core.kernel.advance_free)
OSC = dict(mu=2.0, beta=0.4, sigma=0.1, xi_dot0=2.0)
# an oscillation whose state (ξ, ξ') does not repeat bit for bit in 4·10⁶ samples: every sample is integrated
STEADY = dict(mu=20.0, beta=0.47, sigma=0.02, xi_dot0=3.0)
# a point of the Fig. 4 map below (4 × 40 × 40) that chatters across ξ = 0 with a stop in every sample, its
# ξ drifting by an ulp a period so that its state never repeats bit for bit: the map's costliest kind of run
CHATTER = dict(
    mu=100.0, beta=float(np.linspace(0.0, 1.0, 40)[14]), sigma=float(np.linspace(0.0, 2.0, 40)[9]), xi_dot0=1.0
)


def best_of(fn, repeat: int) -> float:
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def bench_simulator(quick: bool) -> list[dict]:
    n_fast = 2_000_000 if quick else 20_000_000
    simulate(**STEADY, samples=1000, record=False)  # compile / load the cache
    r = simulate(**STEADY, samples=n_fast, record=False)
    assert r.outcome == "oscillating" and r.samples_run == n_fast
    t_fast = best_of(lambda: simulate(**STEADY, samples=n_fast, record=False), 3) / n_fast
    n_ivp = 100 if quick else 300
    t_ivp = (
        best_of(lambda: simulate_ivp(STEADY["mu"], STEADY["beta"], STEADY["sigma"], 0.0, STEADY["xi_dot0"], n_ivp), 1)
        / n_ivp
    )
    n_ct = 1000 if quick else 5000
    t_ct = (
        best_of(
            lambda: simulate_control(STEADY["mu"], STEADY["beta"], STEADY["sigma"], 0.0, STEADY["xi_dot0"], n_ct), 1
        )
        / n_ct
    )
    return [
        dict(name="exact kernel (numba), no recording", per_sample_ns=t_fast * 1e9, ratio=1.0, goal="baseline"),
        dict(
            name="scipy solve_ivp (DOP853, events)",
            per_sample_ns=t_ivp * 1e9,
            ratio=t_ivp / t_fast,
            goal=">= 1e4x slower than the kernel",
        ),
        dict(
            name="python-control input_output_response",
            per_sample_ns=t_ct * 1e9,
            ratio=t_ct / t_fast,
            goal=">= 1e3x slower than the kernel",
        ),
    ]


@numba.njit(cache=True)
def _chain_floor(x, v, n, p1, e1, q1, q2):  # pragma: no cover - compiled
    """The per-sample dependency chain alone: read ⌊ξ⌋, force, exact update; no stick-slip, no bookkeeping."""
    for _ in range(n):
        f = -(math.floor(x) + 0.5)
        x, v = x + v * p1 + f * q2, v * e1 + f * q1
    return x + v


def _kernel_at(commit: str):
    """dfa/_kernel.py (today dfa/core/kernel.py) as of a git commit, imported as a module, or None.

    Its relative imports are made absolute, except ``._exprel`` (φ₁, φ₂, λ: compiled into the kernel), which is
    that commit's own copy when it has one: the row then measures the kernel as it was, not with today's series.
    """
    src = _source_at(commit, "dfa/_kernel.py")
    if src is None:
        return None
    exprel = _source_at(commit, "dfa/_exprel.py")
    if exprel is not None:
        _import_source(f"exprel_{commit}", exprel.replace("from .", "from dfa."))
        src = src.replace("from ._exprel import", f"from exprel_{commit} import")
    src = src.replace("from .criterion import spring_energy_core", "from dfa.core.energy import spring_energy_core")
    return _import_source(f"kernel_{commit}", src.replace("from .", "from dfa."))


def _source_at(commit: str, path: str) -> str | None:
    """The text of ``path`` at ``commit`` (None when git or the file is missing)."""
    import subprocess

    try:
        return subprocess.run(
            ["git", "-C", HERE, "show", f"{commit}:{path}"], capture_output=True, text=True, check=True
        ).stdout
    except (OSError, subprocess.CalledProcessError):
        return None


def _import_source(name: str, src: str):
    """``src`` imported as the module ``name`` (a temporary file; registered in sys.modules)."""
    import importlib.util
    import tempfile

    path = os.path.join(tempfile.mkdtemp(), f"{name}.py")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(src)
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


# the kernel before the inlined-steps refactor, and before issue 16's hot path (advance_free, period skip)
BEFORE = {"dfa kernel before refactor (afb84de)": "afb84de", "dfa kernel before issue 16 (41efa15)": "41efa15"}


def cpu_best(fn, repeat: int) -> float:
    """Best thread CPU time of ``fn`` (the kernels run in this thread): robust to other processes' load."""
    best = float("inf")
    for _ in range(repeat):
        t = time.thread_time()
        fn()
        best = min(best, time.thread_time() - t)
    return best


def _kernel_case(case: dict, n: int, repeat: int) -> dict:
    """ns per sample of the run: dfa's kernel, the kernels before, the plain kernel, the chain floor."""
    mu, beta, sigma, v0 = case["mu"], case["beta"], case["sigma"], case["xi_dot0"]
    e, e2 = np.empty(0), np.empty((0, 4))

    def ours(mod=kernel):
        st = np.empty(mod.NSTATS)
        if mod is kernel:
            kernel.simulate_kernel((mu, beta, sigma), (0.0, v0), (n, 8192, 1e6, True), 0, e, e, e2, st)
        else:  # a kernel before issue 42 takes its arguments one by one
            mod.simulate_kernel(mu, beta, sigma, 0.0, v0, n, 0, True, 1e6, 8192, e, e, e2, st)

    k = kernel.sample_constants(mu, beta)
    fns = {
        "dfa kernel": ours,
        "plain kernel": lambda: plain_kernel(mu, beta, sigma, 0.0, v0, n, 0, True, 1e6),
        "chain floor": lambda: _chain_floor(0.0, v0, n, k[2], k[1], k[4], k[5]),
    }
    for name, commit in BEFORE.items():
        mod = _kernel_at(commit)
        if mod is not None:
            fns[name] = lambda mod=mod: ours(mod)
    for f in fns.values():  # compile / load the caches
        f()
    times = {name: [] for name in fns}
    for _ in range(repeat):  # interleaved, so that load changes hit every method alike
        for name, f in fns.items():
            times[name].append(1e9 * cpu_best(f, 1) / n)
    return {name: (min(t), max(t)) for name, t in times.items()}


def _per_run(kernel):
    """``kernel`` (per-run lengths, bounds and tails) called with the arguments one by one, as the serial kernel
    before issue 42 and ``benchmarks/lanes_kernel.py`` take them (one of each for all)."""

    def run(mus, betas, sigmas, x0s, v0s, n, delay, quantize, bound, tail_len, stats, done, rest):
        k = mus.size
        runs = (np.full(k, n), np.full(k, tail_len), np.full(k, bound), quantize)
        kernel((mus, betas, sigmas), (x0s, v0s), runs, delay, stats, done, rest)

    return run


def _serial(mus, betas, sigmas, x0s, v0s, n, delay, quantize, bound, tail_len, stats, done, rest):
    """dfa.core.kernel.serial_kernel called with the arguments one by one (as :func:`_per_run`)."""
    kernel.serial_kernel((mus, betas, sigmas), (x0s, v0s), (n, tail_len, bound, quantize), delay, stats, done, rest)


def bench_kernel(quick: bool) -> dict:
    """ns per sample (best, worst of the repeats): dfa's kernel vs the kernels before, the plain kernel,
    the chain floor, on a never-repeating oscillation and on the paper's repeating one; batched runs."""
    n = 1_000_000 if quick else 4_000_000
    repeat = 3 if quick else 7
    out = {"steady": _kernel_case(STEADY, n, repeat), "repeating": _kernel_case(OSC, n, repeat)}
    out["chatter"] = _kernel_case(CHATTER, n // 4, repeat)
    # lists of runs in one compiled call: 64 points of the Fig. 4 map (μ = 100, ξ'0 = 2), per sample run
    import lanes_kernel

    rng = np.random.default_rng(1)
    runs, nb = 64, 50_000
    pts = [np.full(runs, 100.0), rng.uniform(0, 1, runs), rng.uniform(0, 2, runs), np.zeros(runs), np.full(runs, 2.0)]
    tail = (nb, 0, True, 1e6, 8192)
    rows = {}
    for name, fn in (
        ("one run at a time (dfa.core.kernel.serial_kernel)", _serial),
        ("two runs in flight (dfa.core.batch.batch_kernel, used by maps and searches)", _per_run(batch.batch_kernel)),
        ("4 lanes in registers, no period skip (benchmarks/lanes_kernel.py, an experiment)", lanes_kernel.lanes_kernel),
    ):
        st, dn, rs = np.empty((runs, kernel.NSTATS)), np.empty(runs, np.int64), np.empty(runs, np.int64)
        fn(*pts, *tail, st, dn, rs)
        rows[name] = (
            1e9
            * min(cpu_best(lambda fn=fn, st=st, dn=dn, rs=rs: fn(*pts, *tail, st, dn, rs), 1) for _ in range(repeat))
            / dn.sum()
        )
    out["batch"] = rows
    return out


def bench_map_speed(quick: bool) -> dict:
    """`dfa map` at 4 × 40 × 40 points: threads and processes against a single-core loop of simulate(),
    and the map's points through the kernel before issue 16 (one core, one call per chunk as run_points)."""
    speeds, g, n = [1.0, 2.0, 5.0, 10.0], (20 if quick else 40), 50_000
    stability_map(100.0, speeds, grid=2, samples=10, n_jobs=1, progress=False)
    bb, ss = np.meshgrid(np.linspace(0.0, 1.0, g), np.linspace(0.0, 2.0, g))
    pb, ps = np.tile(bb.ravel(), len(speeds)), np.tile(ss.ravel(), len(speeds))
    v0 = np.repeat(np.asarray(speeds), bb.size)
    pts = (np.full(pb.size, 100.0), pb, ps, np.zeros(pb.size), v0)
    bound = divergence_bound(0.0, max(speeds), 100.0)
    outs = (np.empty((pb.size, kernel.NSTATS)), np.empty(pb.size, np.int64), np.empty(pb.size, np.int64))

    def loop():
        for v in speeds:
            for b, s in zip(bb.ravel(), ss.ravel(), strict=True):
                simulate(100.0, float(b), float(s), v, n, record=False)

    runs = {
        "single-core loop of simulate()": loop,
        "stability_map, 1 job": lambda: stability_map(100.0, speeds, grid=g, samples=n, n_jobs=1, progress=False),
        "stability_map, 2 jobs, threads": lambda: stability_map(
            100.0, speeds, grid=g, samples=n, n_jobs=2, progress=False
        ),
        "stability_map, 2 jobs, processes": lambda: stability_map(
            100.0, speeds, grid=g, samples=n, n_jobs=2, progress=False, backend="processes"
        ),
    }
    tail = (n, 0, True, bound, _tail_length(n, 100.0))
    runs["map points, one run at a time (serial_kernel), 1 core"] = lambda: _serial(*pts, *tail, *outs)
    runs["map points, two runs in flight (dfa.core.batch.batch_kernel), 1 core"] = lambda: _per_run(batch.batch_kernel)(
        *pts, *tail, *outs
    )
    runs["map points, plain kernel (benchmarks/plain_kernel.py), 1 core"] = lambda: [
        plain_kernel(100.0, b, s, 0.0, v, n, 0, True, bound) for b, s, v in zip(pb, ps, v0, strict=True)
    ]
    old = _kernel_at("41efa15")
    if old is not None:

        def before():
            k = pb.size
            st, dn, rs = np.empty((k, old.NSTATS)), np.empty(k, np.int64), np.empty(k, np.int64)
            old.serial_kernel(*pts, n, 0, True, bound, _tail_length(n, 100.0), st, dn, rs)

        before()
        runs["map points, kernel before issue 16 (41efa15), 1 core"] = before
    plain_kernel(100.0, 0.5, 0.5, 0.0, 1.0, 10, 0, True, bound)
    seconds = {name: best_of(f, 1) for name, f in runs.items()}
    _serial(*pts, *tail, *outs)
    k = kernel.sample_constants(100.0, 0.5)
    floor_ns = 1e9 * cpu_best(lambda: _chain_floor(0.0, 2.0, 1_000_000, k[2], k[1], k[4], k[5]), 3) / 1e6
    return dict(grid=g, seconds=seconds, samples_run=int(outs[1].sum()), chain_floor_ns=floor_ns)


def bench_fig4(quick: bool) -> dict:
    grid = 30 if quick else 100
    stability_map(100.0, [1.0], grid=2, samples=10, progress=False, n_jobs=1)
    t = time.perf_counter()
    m = stability_map(100.0, [1.0, 2.0, 5.0, 10.0], grid=grid, samples=50_000, progress=False, n_jobs=-1)
    elapsed = time.perf_counter() - t
    return dict(grid=grid, seconds=elapsed, counts=m.counts(), cores=os.cpu_count())


DF_CASES = [(5.0, 0.4), (5.0, 0.45), (20.0, 0.47), (20.0, 0.49), (100.0, 0.495), (100.0, 0.498), (2.0, 0.3)]


def bench_solver(quick: bool) -> list[dict]:
    """Our limit-cycle solver vs python-control's describing_function_response, same loop and DF object (σ = 0)."""
    import warnings

    import control

    from dfa.analysis import cycles as _cycles
    from dfa.analysis.cycles import limit_cycles
    from dfa.analysis.describing import quantizer_df
    from dfa.analysis.loop import loop_response, loop_system
    from dfa.analysis.nonlinearities import QuantizerNonlinearity

    rows = []
    amps = np.linspace(0.05, 10.0, 400)
    for mu, beta in DF_CASES:
        p = dfa.Params(mu, beta, 0.0)
        t_ours = best_of(lambda p=p: limit_cycles(p, model="pade", pade_order=6), 5)

        def cold(p=p):
            # the loop model's caches (Padé coefficients, phase on the scan grid) emptied before the solve
            _cycles.pade_denominator.cache_clear()
            _cycles.grid_lead.cache_clear()
            limit_cycles(p, model="pade", pade_order=6)

        t_cold = best_of(cold, 5)
        ours = limit_cycles(p, model="pade", pade_order=6).cycles
        H = loop_system(p, model="pade", pade_order=6)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t0 = time.perf_counter()
            resp = control.describing_function_response(H, QuantizerNonlinearity(), amps)
            t_pc = time.perf_counter() - t0
        pc = sorted(resp.intersections)
        # one-to-one nearest matching within 1 % in amplitude (python-control's roots are grid-limited)
        used: set[int] = set()
        errs, pc_resid = [], []
        for c in ours:
            cand = [(abs(a - c.amplitude) / c.amplitude, k) for k, (a, _w) in enumerate(pc) if k not in used]
            if cand and min(cand)[0] < 1e-2:
                e, k = min(cand)
                used.add(k)
                errs.append(e)
                a, w = pc[k]
                pc_resid.append(abs(1.0 + quantizer_df(a) * complex(loop_response(p, w, model="pade", pade_order=6))))
        found = len(used)
        in_range = sum(c.amplitude <= amps[-1] for c in ours)
        rows.append(
            dict(
                mu=mu,
                beta=beta,
                t_ours=t_ours,
                t_cold=t_cold,
                t_pc=t_pc,
                n_ours=len(ours),
                n_pc=len(pc),
                found=found,
                in_range=in_range,
                pc_err=max(errs, default=0.0),
                pc_resid=max(pc_resid, default=0.0),
                our_resid=max((c.residual for c in ours), default=0.0),
            )
        )
    return rows


def bench_contours(quick: bool) -> dict:
    """Fig. 7 maps (vectorised) against the point solver run on a random sample of the same grid points."""
    from dfa.analysis.contours import contour_maps
    from dfa.analysis.cycles import limit_cycles

    grid, mu = 200, 5.0
    contour_maps(mu, grid=5)
    t0 = time.perf_counter()
    maps = contour_maps(mu, grid=grid)
    t_maps = time.perf_counter() - t0
    rng = np.random.default_rng(0)
    n = 40 if quick else 200
    ij = rng.integers(0, grid, size=(n, 2))
    t0 = time.perf_counter()
    for i, j in ij:
        limit_cycles(dfa.Params(mu, float(maps.beta[j]), float(maps.sigma[i])), max_amplitude=maps.max_amplitude)
    per_point = (time.perf_counter() - t0) / n
    return dict(grid=grid, mu=mu, seconds=t_maps, per_point=per_point, sampled=n)


SIGMA_CASES = [(5.0, 0.1, 0.3), (5.0, 0.4, 0.05), (20.0, 0.47, 0.02), (100.0, 0.495, 0.01)]


def bench_solver_friction(solver_rows: list[dict]) -> list[dict]:
    """σ > 0 (amplitude-dependent loop, beyond python-control's tool): time per solve for each loop model.

    The ratio is against python-control's σ = 0 solve at the same (μ, β) measured above, only as a scale.
    """
    from dfa.analysis import cycles as _cycles
    from dfa.analysis.cycles import limit_cycles

    pc = {(r["mu"], r["beta"]): r["t_pc"] for r in solver_rows}
    pc_median = float(np.median([r["t_pc"] for r in solver_rows]))
    rows = []
    for mu, beta, sigma in SIGMA_CASES:
        p = dfa.Params(mu, beta, sigma)
        row = dict(mu=mu, beta=beta, sigma=sigma, t_pc=pc.get((mu, beta), pc_median))
        for model in ("half-delay", "pade", "zoh"):

            def cold(p=p, model=model):
                _cycles.zoh_phase_beta_grid.cache_clear()
                _cycles.grid_lead.cache_clear()
                return limit_cycles(p, model=model)

            row[f"n_{model}"] = len(cold().cycles)
            row[f"cold_{model}"] = best_of(cold, 3)
            row[f"t_{model}"] = best_of(lambda p=p, model=model: limit_cycles(p, model=model), 3)
        rows.append(row)
    return rows


def _kernel_table(rows: dict, plain: float) -> list[str]:
    lines = ["| method | ns per sample (best) | worst of the repeats | × plain kernel |", "|---|---:|---:|---:|"]
    for name, (lo, hi) in rows.items():
        lines.append(f"| {name} | {lo:.3g} | {hi:.3g} | {lo / plain:.2f} |")
    return lines


def render_kernel(kern: dict, mapspeed: dict) -> list[str]:
    steady, rep, chat = kern["steady"], kern["repeating"], kern["chatter"]
    plain, ours = steady["plain kernel"][0], steady["dfa kernel"][0]
    lines = [
        "",
        "## Simulator kernel (issue 16): time per sample, measured side by side in one run",
        "",
        "No recording; thread CPU time, best and worst of the interleaved repeats. The plain kernel",
        "(`benchmarks/plain_kernel.py`) is the straightforward exact kernel of the same model; the chain floor is",
        "the read → force → update dependency chain alone (no stick-slip), the physical limit of one trajectory",
        "on this machine. Goal: dfa ≤ 0.5 × plain.",
        "",
        "A persistent oscillation whose state never repeats (μ = 20, β = 0.47, σ = 0.02, ξ'0 = 3): every sample",
        "is integrated.",
        "",
        *_kernel_table(steady, plain),
        "",
        "The earlier benchmarks' oscillation (μ = 2, β = 0.4, σ = 0.1, ξ'0 = 2): its state repeats bit for bit",
        "after 3032 samples and dfa skips the periods from there (same results bit for bit); ns per sample of the run.",
        "",
        *_kernel_table(rep, rep["plain kernel"][0]),
        "",
        f"Chatter across ξ = 0 with a stop in every sample (μ = 100, β = {CHATTER['beta']:.4f}, σ ="
        f" {CHATTER['sigma']:.4f}, ξ'0 = 1, a point of the map below): its ξ drifts by an ulp a period, so its",
        "state never repeats and every sample is integrated; the map's costliest kind of run.",
        "",
        *_kernel_table(chat, chat["plain kernel"][0]),
    ]
    verdict = "met" if ours <= 0.5 * plain else "NOT met"
    before = steady.get("dfa kernel before issue 16 (41efa15)", (np.nan,))[0]
    lines += [
        "",
        f"dfa kernel / plain kernel = {ours / plain:.2f} where every sample is integrated (goal ≤ 0.5: **{verdict}**;"
        f" the kernel before issue 16: {before / plain:.2f} on the same run). The chain floor is"
        f" {steady['chain floor'][0] / ours:.2f} × dfa's sample: the rest is the stick-slip logic and the"
        " run's bookkeeping, off the chain but not free.",
    ]
    lines += [
        "",
        "64 runs of a Fig. 4 map (μ = 100, ξ'0 = 2, random β, σ, 5·10⁴ samples) in one call, per sample run:",
        "",
    ]
    lines += ["| kernel | ns per sample |", "|---|---:|"]
    lines += [f"| {name} | {t:.3g} |" for name, t in kern["batch"].items()]
    sec = mapspeed["seconds"]
    loop = sec["single-core loop of simulate()"]
    g = mapspeed["grid"]
    lines += [
        "",
        f"## `dfa map` speed: 4 × {g} × {g} points, μ = 100, 5·10⁴ samples (issue 16: 2 jobs ≤ 0.25 × single-core loop)",
        "",
        "The single-core loop calls today's simulate() (one run at a time, which skips repeated periods too); the",
        "map deals its points out to chunks in turn and runs each chunk through dfa.core.batch.batch_kernel (one",
        "compiled call, two runs in flight). The rows below run the same points in one call: one at a time, two",
        "in flight (the map's kernel), the plain kernel (no tail statistics, no period skip), the kernel before",
        "issue 16.",
        "",
        "| run | seconds | × single-core loop |",
        "|---|---:|---:|",
    ]
    for name, t in sec.items():
        lines.append(f"| {name} | {t:.2f} | {t / loop:.2f} |")
    phys = mapspeed["samples_run"] * mapspeed["chain_floor_ns"] * 1e-9
    best = min(sec["stability_map, 2 jobs, threads"], sec["stability_map, 1 job"])
    verdict = "met" if best <= 0.25 * loop else "NOT met"
    lines += [
        f"| physical limit: the {mapspeed['samples_run']:,} samples run × the chain floor "
        f"({mapspeed['chain_floor_ns']:.3g} ns), 1 core | {phys:.2f} | {phys / loop:.2f} |",
        "",
        f"Best map / single-core loop = {best / loop:.2f} (goal ≤ 0.25: **{verdict}**). The physical limit counts every"
        " sample of every run; skipped periods are not integrated, so the map can run below it.",
    ]
    return lines


def bench_find_root(quick: bool) -> str:
    """Eq. 43 on the 200 × 200 small-cycle map: scipy's elementwise find_root vs the former 80-step bisection.

    Self-contained: returns its own Markdown section (the bisection is the code contours.py used before).
    """
    import math

    from dfa.analysis.cycles import small_cycle_closed_forms

    mu, grid = 5.0, 200
    bb, ss = np.meshgrid(np.linspace(0.0, 1.0, grid), np.linspace(0.0, 2.0, grid))

    def bisection():
        lo, hi = np.full(bb.shape, 1e-12), np.full(bb.shape, math.pi)
        for _ in range(80):
            mid = 0.5 * (lo + hi)
            f = 0.5 * np.sin(mid / 2) - bb * np.cos(mid / 2) / (2 * mu * mid) - ss
            lo, hi = np.where(f < 0, mid, lo), np.where(f < 0, hi, mid)
        return np.where(ss >= 0.5, np.nan, 0.5 * (lo + hi))

    repeat = 3 if quick else 7
    t_bis = best_of(bisection, repeat)
    t_fr = best_of(lambda: small_cycle_closed_forms(mu, bb, ss), repeat)
    w_bis, cf = bisection(), small_cycle_closed_forms(mu, bb, ss)
    both = np.isfinite(w_bis) & np.isfinite(cf.frequency)
    diff = float(np.max(np.abs(w_bis[both] - cf.frequency[both])))
    flagged = int(np.count_nonzero(np.isfinite(w_bis) & ~np.isfinite(cf.frequency)))
    return "\n".join(
        [
            "",
            "## Vectorised root finding: eq. 43 on the small-cycle map",
            "",
            f"μ = {mu:g}, {grid} × {grid} (β, σ) grid, best of {repeat}: `scipy.optimize.elementwise.find_root` "
            f"{1e3 * t_fr:.3g} ms, hand-written 80-step bisection {1e3 * t_bis:.3g} ms: **{t_bis / t_fr:.1f}× faster**; "
            f"same ω to {diff:.1e} rad/sample. {flagged} point(s) the bisection returned as ω ≈ 1e-12 "
            "(β = σ = 0, no cycle) are flagged DEGENERATE (NaN) instead.",
            "",
        ]
    )


def render(
    sim: list[dict],
    fig4: dict,
    quick: bool,
    solver: list[dict] | None = None,
    friction: list[dict] | None = None,
    contours: dict | None = None,
    kernel: dict | None = None,
    mapspeed: dict | None = None,
) -> str:
    lines = [
        "# Benchmarks",
        "",
        f"Generated by `make bench` (`benchmarks/run.py{' --quick' if quick else ''}`) on "
        f"{datetime.now(timezone.utc):%Y-%m-%d %H:%M} UTC, {platform.processor() or platform.machine()}, "
        f"{os.cpu_count()} cores, Python {platform.python_version()}, numpy {np.__version__}, dfa {dfa.__version__}.",
        "Times are wall clock (best of 3 for the kernel, 1 run for the slow references); the ratios are what carries",
        "over to another machine.",
        "",
        "## Simulator: time per sample (paper eq. 4-5, a persistent oscillation μ = 20, β = 0.47, σ = 0.02, ξ'0 = 3)",
        "",
        "| method | ns per sample | × kernel | goal |",
        "|---|---:|---:|---|",
    ]
    for row in sim:
        lines.append(f"| {row['name']} | {row['per_sample_ns']:.4g} | {row['ratio']:.3g} | {row['goal']} |")
    if kernel and mapspeed:
        lines += render_kernel(kernel, mapspeed)
    g = fig4["grid"]
    lines += [
        "",
        "## Paper Fig. 4 map",
        "",
        f"μ = 100, ξ'0 ∈ {{1, 2, 5, 10}}, {g} × {g} (β, σ) grid, 5·10⁴ samples per run, all {fig4['cores']} cores: "
        f"**{fig4['seconds']:.1f} s** (goal for 100 × 100: under 30 s on 2 cores). Runs that come to rest or pass the bound stop early.",
        "",
        "| ξ'0 | rest | chatter | oscillating | unstable | undecided |",
        "|---:|---:|---:|---:|---:|---:|",
    ]
    for v, c in zip([1, 2, 5, 10], fig4["counts"], strict=False):
        lines.append(
            f"| {v} | {c['rest']} | {c['chatter']} | {c['oscillating']} | {c['unstable']} | {c['undecided']} |"
        )
    if solver:
        lines += [
            "",
            "## Limit-cycle solver vs python-control (eq. 36, exact D of eq. 41)",
            "",
            "Same loop (device with the half-sample hold as a 6th-order Padé model, σ = 0 so that python-control's",
            "amplitude-independent linear block applies) and the same `QuantizerNonlinearity` object. python-control:",
            "`describing_function_response` with 400 amplitudes in [0.05, 10] ticks and its default frequency grid.",
            "",
            'dfa searches every amplitude up to 10⁴ ticks. "dfa" is the best of 5 solves (a sweep at a fixed loop model);',
            '"cold" is a solve right after the loop model\'s caches (Padé coefficients, phase on the scan grid) are emptied (best of 5).',
            "",
            "Roots are matched one to one (nearest, within 1 % in amplitude); python-control's error is its worst relative",
            "amplitude error against ours, and residuals are |1 + D(M)L(jω)| at the reported roots.",
            "",
            "| μ | β | dfa (ms) | dfa cold (ms) | python-control (ms) | × faster | × faster, cold | cycles dfa (≤ 10 ticks) | cycles python-control | matched | unmatched python-control | python-control error | residual python-control | residual dfa |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for r in solver:
            lines.append(
                f"| {r['mu']:g} | {r['beta']:g} | {1e3 * r['t_ours']:.3g} | {1e3 * r['t_cold']:.3g} | {1e3 * r['t_pc']:.3g} | "
                f"{r['t_pc'] / r['t_ours']:.0f} | {r['t_pc'] / r['t_cold']:.0f} | "
                f"{r['n_ours']} ({r['in_range']}) | {r['n_pc']} | {r['found']} | {r['n_pc'] - r['found']} | {r['pc_err']:.1e} | "
                f"{r['pc_resid']:.1e} | {r['our_resid']:.1e} |"
            )
        missed = sum(r["in_range"] - r["found"] for r in solver)
        spurious = sum(r["n_pc"] - r["found"] for r in solver)
        beyond = sum(r["n_ours"] - r["in_range"] for r in solver)
        lines += [
            "",
            f"Every root python-control finds is one of ours ({spurious} unmatched); within its amplitude range it misses "
            f"{missed} of ours, and {beyond} of ours lie beyond the range it was given (it has no way to know how far to search).",
        ]
        ratios = [r["t_pc"] / r["t_ours"] for r in solver]
        cold = [r["t_pc"] / r["t_cold"] for r in solver]
        verdict = "met" if min(ratios) >= 1000 else "NOT met"
        lines += [
            "",
            f"Speed-up {min(ratios):.0f}× to {max(ratios):.0f}× per solve ({min(cold):.0f}× to {max(cold):.0f}× cold); "
            f"goal 1000× per solve: **{verdict}**.",
        ]
    if friction:
        lines += [
            "",
            "### With Coulomb friction (σ > 0: the loop depends on the amplitude, which python-control's tool cannot take)",
            "",
            "Time per solve (best of 3; cold = with the phase curve on the scan grid not yet cached, as for the first solve at a μ) for each loop model.",
            "× is python-control's σ = 0 time at the same (μ, β) above divided by ours, only as a scale.",
            "",
            "| μ | β | σ | half-delay (ms) | Padé-4 (ms) | exact ZOH (ms) | ZOH cold (ms) | × half-delay | × ZOH | cycles (half-delay / Padé / ZOH) |",
            "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|",
        ]
        for r in friction:
            lines.append(
                f"| {r['mu']:g} | {r['beta']:g} | {r['sigma']:g} | {1e3 * r['t_half-delay']:.3g} | {1e3 * r['t_pade']:.3g} | "
                f"{1e3 * r['t_zoh']:.3g} | {1e3 * r['cold_zoh']:.3g} | {r['t_pc'] / r['t_half-delay']:.0f} | {r['t_pc'] / r['t_zoh']:.0f} | "
                f"{r['n_half-delay']} / {r['n_pade']} / {r['n_zoh']} |"
            )
    if contours:
        est = contours["per_point"] * contours["grid"] ** 2
        lines += [
            "",
            "## Paper Fig. 7 contour maps",
            "",
            f"μ = {contours['mu']:g}, {contours['grid']} × {contours['grid']} (β, σ) grid, both families, exact D and the closed forms: "
            f"**{contours['seconds']:.2f} s** (goal: a few seconds). The point solver (`limit_cycles`, every cycle of a point) "
            f"takes {1e3 * contours['per_point']:.3g} ms per point on {contours['sampled']} random grid points, i.e. about "
            f"{est:.0f} s for the whole grid: the vectorised maps are {est / contours['seconds']:.0f}× faster.",
        ]
    return "\n".join(lines) + "\n"


def bench_design_answer(quick: bool) -> str:
    """`dfa stiffness --device X --velocity V --json` (K_max four ways, issue 14) per catalogue device.

    Wall time of the command in a fresh process (import included) and in-process, as a ratio to one exact
    simulation of 5·10⁴ samples of a persistent oscillation (OSC); goal: under 10 s on 2 cores.
    """
    import contextlib
    import io
    import subprocess

    from dfa.cli import main as cli_main

    one = best_of(lambda: simulate(**OSC, samples=50_000, record=False), 3)
    rows = []
    for entry in [e for e in dfa.catalogue() if not e.missing][: 2 if quick else None]:
        v = "2" if entry.rotary else "0.2"
        argv = ["stiffness", "--device", entry.name, "--velocity", v, "--json"]
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "dfa.cli", *argv], check=True, capture_output=True)
        fresh = time.perf_counter() - t0
        with contextlib.redirect_stdout(io.StringIO()):
            warm = best_of(lambda argv=argv: cli_main(argv), 1)
        rows.append(
            f"| {entry.name} | {v} | {fresh:.2f} | {warm:.2f} | {warm / one:.0f} | {'met' if fresh < 10 else 'NOT met'} |"
        )
    return (
        "\n".join(
            [
                "",
                "## Design answer: `dfa stiffness --device X --velocity V --json` (K_max four ways)",
                "",
                f"One exact simulation (5·10⁴ samples, persistent oscillation): {1e3 * one:.2f} ms. Fresh process includes",
                "the import and the compiled kernel's load; × is the in-process time over that one simulation.",
                "",
                "| device | V (m/s; rad/s) | fresh process (s) | in process (s) | × one simulation | goal < 10 s |",
                "|---|---:|---:|---:|---:|---|",
                *rows,
            ]
        )
        + "\n"
    )


def bench_startup(quick: bool) -> str:
    """Start-up of `dfa check` (issue 27 §1) against `python -c "import numpy"`, each a fresh process, one run.

    Goal: `dfa check` at most 3 times the time of importing numpy (best of several starts each, side by side).
    """
    import subprocess

    def start(argv: list[str]) -> float:
        t0 = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True)
        return time.perf_counter() - t0

    repeat = 3 if quick else 7
    numpy_t = min(start([sys.executable, "-c", "import numpy"]) for _ in range(repeat))
    check = [sys.executable, "-m", "dfa.cli", "check", "--device", "delta", "--velocity", "0.1"]
    check_t = min(start(check) for _ in range(repeat))
    ratio = check_t / numpy_t
    return (
        "\n".join(
            [
                "",
                '## Start-up: `dfa check --device delta --velocity 0.1` against `python -c "import numpy"`',
                "",
                f"Fresh processes, best of {repeat} starts each, measured side by side in this run (dfa's bytecode compiled first, as pip does on install).",
                "",
                "| command | seconds | × import numpy | goal |",
                "|---|---:|---:|---|",
                f'| python -c "import numpy" | {numpy_t:.3f} | 1 | baseline |',
                f"| dfa check (python -m dfa.cli) | {check_t:.3f} | {ratio:.2f} | <= 3x: {'met' if ratio <= 3 else 'NOT met'} |",
            ]
        )
        + "\n"
    )


# the controller path (issue 15 item 4): a loop that chatters for ever (σ < ½ never rests)
CTL_RUN = dict(mu=2.0, beta=2.0, sigma=0.1, xi_dot0=2.0)


def bench_controller_kernel(quick: bool) -> str:
    """ns per sample of dfa.core.wall_kernel (damper, filter, delay, amplifier lag) beside the spring kernel, same loop.

    Then the period skip (issue 16): ns per sample of the run with skipping, and the samples integrated.
    """
    from dfa.core import wall_kernel
    from dfa.model.elements import Delay, PassivityController
    from dfa.model.wall import WallParams as CP

    n = 200_000 if quick else 2_000_000
    mu, beta, sigma, v0 = (CTL_RUN[k] for k in ("mu", "beta", "sigma", "xi_dot0"))
    e, e2 = np.empty(0), np.empty((0, 4))

    def spring():  # delay 1: the spring kernel skips exactly repeated periods only at d = 0
        st = np.empty(kernel.NSTATS)
        return kernel.simulate_kernel((mu, beta, sigma), (0.0, v0), (n, 8192, 1e6, True), 1, e, e, e2, st)[0]

    def ctl(c, skip=False):  # (samples run, samples integrated); skip=False integrates every sample
        st = np.empty(kernel.NSTATS)
        table = c.kernel_table()
        out = wall_kernel.run_wall_kernel((mu, beta, sigma), (0.0, v0), (n, 8192, 1e6, True), table, e, e, st, skip)
        return out[0], out[2]

    def per_sample(f):
        f()  # compile / load the cache
        return min(best_of(f, 1) for _ in range(3)) / f()[0]

    full = CP.of(damping=0.5, cutoff=0.1, delay=1, lag=0.2)
    rows = []
    base = per_sample(lambda: (spring(), 0))
    rows.append(f"| spring kernel (dfa.core.kernel), delay 1 | {n} | {1e9 * base:.3g} | 1.00 |")
    for name, c in [
        ("controller kernel, pure spring", CP.of()),
        ("damper β_B = 0.5", CP.of(damping=0.5)),
        ("damper + filter ν_c = 0.1 + delay 1", CP.of(damping=0.5, cutoff=0.1, delay=1)),
        ("amplifier lag α = 0.2", CP.of(lag=0.2)),
        ("damper + filter + delay 1 + lag α = 0.2", full),
        ("passivity controller (issue 30), unbounded observer, force limit 3", CP(((PassivityController, (0, 3.0)),))),
        ("passivity controller, window 50 samples, delay 1", CP(((PassivityController, (50, None)), (Delay, 1)))),
    ]:
        t = per_sample(lambda c=c: ctl(c))
        rows.append(f"| {name} | {n} | {1e9 * t:.3g} | {t / base:.2f} |")
    skips = []
    for name, c in [("damper + filter + delay 1 + lag α = 0.2", full), ("pure spring (never repeats here)", CP.of())]:
        t_all = per_sample(lambda c=c: ctl(c))
        t = per_sample(lambda c=c: ctl(c, True))
        skips.append(f"| {name} | {n} | {ctl(c, True)[1]} | {1e9 * t:.3g} | {t / t_all:.3g} |")
    return (
        "\n".join(
            [
                "",
                "## Simulator with a controller (issue 15 item 4): time per sample integrated",
                "",
                f"μ = {mu}, β = {beta}, σ = {sigma} (chatters for ever), ξ'0 = {v0}, no recording. With the amplifier lag",
                "the force varies within each sample: every stop is a bracketed root of the closed form. The spring",
                "kernel runs with delay 1 so that it integrates every sample (at d = 0 it skips exactly repeated",
                "periods); the controller kernel runs with its period skip off (``run_wall_kernel(..., skip=False)``).",
                "",
                "| kernel / controller | samples integrated | ns per sample | × spring kernel |",
                "|---|---:|---:|---:|",
                *rows,
                "",
                "Period skip of the controller kernel (issue 16; what `simulate_wall_kernel` runs unrecorded): once the",
                "loop's whole state repeats bit for bit, whole periods are skipped. ns per sample of the run; × is the",
                "time over the same run integrating every sample (the cycle check's cost when nothing repeats).",
                "",
                "| controller (same run) | samples run | samples integrated | ns per sample of the run | × every sample |",
                "|---|---:|---:|---:|---:|",
                *skips,
            ]
        )
        + "\n"
    )


def bench_wall_pair(quick: bool) -> str:
    """ns per sample of the searches' chatter with a passivity controller held at its limit, one run at a time
    (:func:`dfa.core.wall_kernel.outcome_wall_kernel`) and two in flight (:func:`dfa.core.wall_pair.pair_wall_outcomes`).

    Four runs of the slow search of issue 43 (the Phantom's groups near 5200 N/m, its controller's limit 10 σ), each
    integrated in every sample (none returns); the same samples done and rest samples both ways.
    """
    from dfa.analysis.simulation import GROWTH, SETTLE, STABLE_AMPLITUDE
    from dfa.core import wall_kernel
    from dfa.core.table import stack_tables
    from dfa.core.wall_pair import pair_wall_outcomes
    from dfa.model.elements import PassivityController
    from dfa.model.wall import WallParams as CP

    n = 100_000 if quick else 1_000_000
    cases = [  # (μ, β, σ, ξ0, ξ'0)
        (13.808895307045114, 0.0009589510629892442, 0.3625884616277739, 0.0, 2.4875621890547266),
        (14.391414037758391, 0.0009994037526221105, 0.3778840059665691, 6.275335919322973, 0.0),
        (13.913981388447178, 0.0009662487075310541, 0.36534777001174185, 4.613867744687147, 0.0),
        (14.08512512156689, 0.0009781336889977009, 0.36984159384987686, 0.0, 2.0729684908789383),
    ]
    k, rules = len(cases), (STABLE_AMPLITUDE, GROWTH, SETTLE)
    mu, beta, sigma, x0, v0 = (np.array(c) for c in zip(*cases, strict=True))
    tables = stack_tables([CP(((PassivityController, (0, 10.0 * c[2])),)).kernel_table() for c in cases])
    runs = (np.full(k, n), np.array([_tail_length(n, m) for m in mu]), np.full(k, 1e6), True)
    outs, integrated = {}, []

    def alone():
        st = np.empty((k, kernel.NSTATS))
        res = [wall_kernel.outcome_wall_kernel((mu[i], beta[i], sigma[i]), (x0[i], v0[i]),
                                               (n, runs[1][i], 1e6, True), tables[i], st[i], rules)
               for i in range(k)]  # fmt: skip
        outs["alone"] = [r[:2] for r in res]
        integrated[:] = [r[2] for r in res]

    def paired():
        st, done, rest = np.empty((k, kernel.NSTATS)), np.empty(k, np.int64), np.empty(k, np.int64)
        pair_wall_outcomes((mu, beta, sigma), (x0, v0), runs, tables, rules, st, done, rest)
        outs["paired"] = list(zip(done.tolist(), rest.tolist(), strict=True))

    t_alone = min(cpu_best(alone, 1) for _ in range(3)) / (k * n)
    t_pair = min(cpu_best(paired, 1) for _ in range(3)) / (k * n)
    same = "yes" if outs["alone"] == outs["paired"] else "NO"
    every = "every sample" if integrated == [n] * k else f"{sum(integrated)} of {k * n} samples"
    return (
        "\n".join(
            [
                "",
                "## Two wall runs in flight (issue 43): the passivity controller's chatter",
                "",
                f"Four runs of the slow search (μ ≈ 14, β ≈ 0.001, σ ≈ 0.37, controller limit 10 σ, {n} samples each,",
                f"{every} integrated), CPU time per sample, best of 3. The lanes overlap the two runs' dependency",
                "chains (`dfa.core.wall_pair`); the searches take them for the walls `pairable` accepts.",
                "",
                "| kernel | ns per sample | × one at a time | same done and rest |",
                "|---|---:|---:|---|",
                f"| one run at a time (`outcome_wall_kernel`) | {1e9 * t_alone:.3g} | 1.00 | |",
                f"| two in flight (`pair_wall_outcomes`) | {1e9 * t_pair:.3g} | {t_pair / t_alone:.2f} | {same} |",
            ]
        )
        + "\n"
    )


def bench_controller_design_answer(quick: bool) -> str:
    """`dfa stiffness --device X --velocity V --virtual-damping B --json` (K_max four ways with a controller).

    Wall time in a fresh process and in-process, as a ratio to one exact controller simulation of 5·10⁴
    samples (CTL_RUN with a damper β_B = 0.5), every sample integrated (that run repeats and would skip its
    periods otherwise); goal: under 30 s on 2 cores.
    """
    import contextlib
    import io
    import subprocess

    from dfa.cli import main as cli_main
    from dfa.core import wall_kernel
    from dfa.model.wall import WallParams as CP

    e, st, c = np.empty(0), np.empty(kernel.NSTATS), CP.of(damping=0.5)
    mu, beta, sigma, v0 = (CTL_RUN[k] for k in ("mu", "beta", "sigma", "xi_dot0"))
    run = ((mu, beta, sigma), (0.0, v0), (50_000, 8192, 1e6, True), c.kernel_table(), e, e, st, False)
    wall_kernel.run_wall_kernel(*run)
    one = best_of(lambda: wall_kernel.run_wall_kernel(*run), 3)
    cases = [("Delta", "0.1", ["--virtual-damping", "1"]), ("Delta", "0.1", ["--virtual-damping", "1", "--delay", "1"])]
    if not quick:
        cases += [("Impulse Engine", "0.1", ["--virtual-damping", "0.05", "--amplifier-bandwidth", "200"])]
    rows = []
    for name, v, flags in cases:
        argv = ["stiffness", "--device", name, "--velocity", v, *flags, "--json"]
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "dfa.cli", *argv], check=True, capture_output=True)
        fresh = time.perf_counter() - t0
        with contextlib.redirect_stdout(io.StringIO()):
            warm = best_of(lambda argv=argv: cli_main(argv), 1)
        goal = "met" if fresh < 30 else "NOT met"
        rows.append(f"| {name} | {v} | {' '.join(flags)} | {fresh:.2f} | {warm:.2f} | {warm / one:.0f} | {goal} |")
    return (
        "\n".join(
            [
                "",
                "## Design answer with a controller: `dfa stiffness ... --virtual-damping B --json`",
                "",
                f"One exact controller simulation (5·10⁴ samples, damper β_B = 0.5, every sample integrated):"
                f" {1e3 * one:.2f} ms; × is the in-process time over that one simulation.",
                "",
                "| device | V (m/s) | controller flags | fresh process (s) | in process (s) | × one simulation | goal < 30 s |",
                "|---|---:|---|---:|---:|---:|---|",
                *rows,
            ]
        )
        + "\n"
    )


def _zwidth_previous_path():
    """Context: :func:`dfa.analysis.limits.zwidth.z_width` as at 8313b4b, one ``simulate()`` per run and per-point thread tasks, the
    boundary columns on threads (for a comparison row)."""
    import contextlib

    import dfa.analysis.limits.zwidth as zmod
    from dfa._parallel import run_in_order

    class _Bar:
        def update(self, n):
            pass

    def grid(tasks, jobs, progress, label):
        return np.array(
            run_in_order(zwidth_point_one_by_one, tasks, [1] * len(tasks), jobs, "threads", _Bar()), dtype=np.int8
        )

    @contextlib.contextmanager
    def patched():
        saved = zmod._simulate_grid, zmod.PROCESS_COLUMNS
        zmod._simulate_grid, zmod.PROCESS_COLUMNS = grid, math.inf
        try:
            yield
        finally:
            zmod._simulate_grid, zmod.PROCESS_COLUMNS = saved

    return patched()


def bench_zwidth(quick: bool) -> str:
    """`z_width` of a catalogue device on a 40 × 40 grid (issue 15): wall time on all cores and on one, and the
    previous path (per-run ``simulate()``, columns on threads) on all cores; goal < 60 s."""
    from dfa.analysis.limits.zwidth import z_width

    g = 8 if quick else 40
    rows = []
    for name, v in (("Impulse Engine", 0.1), ("Phantom 1.0", 0.1)):
        dev = dfa.get_device(name).device
        z_width(dev, v, grid=2, speeds=1, n_jobs=1)  # imports and compiled kernels, once
        z_width(dev, v, grid=16, speeds=1, n_jobs=-1)  # and the worker processes of the boundary columns
        times = {}
        for jobs in (-1, 1, "previous") if not quick else (-1,):
            t0 = time.perf_counter()
            if jobs == "previous":
                with _zwidth_previous_path():
                    old = z_width(dev, v, grid=g, n_jobs=-1)
            else:
                z = z_width(dev, v, grid=g, n_jobs=jobs)
            times[jobs] = time.perf_counter() - t0
        if "previous" in times:  # where the previous path decided (it does not extend undecided runs), the same codes
            from dfa.results.codes import UNDECIDED_POINT

            decided = np.asarray(old.outcome) != UNDECIDED_POINT
            if not np.array_equal(np.asarray(old.outcome)[decided], np.asarray(z.outcome)[decided]):
                raise AssertionError(f"{name}: the previous Z-width path gives other grid codes")
        one = f"{times[1]:.1f}" if 1 in times else "-"
        prev = f"{times['previous']:.1f}" if "previous" in times else "-"
        goal = "met" if times[-1] < 60 else "NOT met"
        rows.append(
            f"| {name} | {v} | {g} × {g} | {z.simulations} | {times[-1]:.1f} | {one} | {prev} | {z.status} | {goal} |"
        )
    return (
        "\n".join(
            [
                "",
                "## Z-width (issue 15): `z_width(device, V, grid=40)`",
                "",
                f"{os.cpu_count()} cores. Each grid point: 2 impact speeds × 2 starts, exact simulation, chunks of grid",
                "points in one compiled call each (threads); per B the exact linear bound, Colgate–Schenkel, the",
                "extended criterion and the describing-function scan (GIL-held Python: worker processes from 16 values",
                "of B on several cores, started before the timing: about 2 s of one core each, once per session).",
                "Previous path: one `simulate()` per run, one thread task per point, every column on threads, and",
                "undecided runs not extended (the codes agree wherever it decided).",
                "",
                "| device | V (m/s) | grid | simulations | all cores (s) | one core (s) | previous path, all cores (s) "
                "| status | goal < 60 s |",
                "|---|---:|---|---:|---:|---:|---:|---|---|",
                *rows,
            ]
        )
        + "\n"
    )


#: The everyday commands of issue 43 and their goals (wall seconds on a quiet 2-core machine; None: no goal).
COMMANDS = [
    ("stiffness --device delta --velocity 0.1", 1.5),
    ("stiffness --device delta --velocity 0.1 --quick", 1.0),
    ("zwidth --device delta --velocity 0.1 --grid 40", 5.0),
    ("stiffness --device phantom --velocity 0.1 --passivity-controller --pc-force-limit 0.38", 10.0),
    ("identify {log} --quiet", 2.0),
    (
        "require --device delta --stiffness 20000 --velocity 0.1 --virtual-damping 1 --velocity-filter 200 --delay 1",
        None,
    ),
    ("tune --device impulse --velocity 0.05", 40.0),
]


def _identify_log(folder: str) -> str:
    """A 16,000-sample log of the Delta driven by a chirp (with a force offset and noise), written to ``folder``."""
    import numpy as np

    from dfa.analysis.identify import synthetic_log
    from dfa.model.catalogue import get_device
    from dfa.model.log import write_log

    dev = get_device("delta").device
    t = np.arange(16000) * dev.period
    force = 3.0 * np.sin(2 * np.pi * (1.0 + 39.0 * t / (2 * t[-1])) * t)  # a chirp from 1 to 40 Hz
    log = synthetic_log(dev, force, force_offset=0.05, force_noise=0.01, seed=1, source="delta_chirp_16k")
    return write_log(log, os.path.join(folder, "delta_chirp_16k.csv"))


def _counted(argv: list[str]) -> tuple[int, int]:
    """Runs and samples (run lengths) one command simulates, counted in-process by :mod:`dfa.progress`."""
    import contextlib
    import io

    from dfa import progress
    from dfa.cli.app import main as dfa_main

    runs, samples = progress.runs_counted(), progress.samples_counted()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        dfa_main(argv)
    return progress.runs_counted() - runs, progress.samples_counted() - samples


def _zwidth_simulations(argv: list[str]) -> int:
    """The simulations a `dfa zwidth` command runs (its JSON's ``simulations``)."""
    import contextlib
    import io
    import json

    from dfa.cli.app import main as dfa_main

    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        dfa_main([*argv, "--json", "--quiet"])
    return int(json.loads(out.getvalue())["simulations"])


def bench_commands(quick: bool) -> str:
    """The everyday commands (issue 43): fresh-process wall time against `python -c "import numpy"` timed in the
    same run, and the runs and samples each simulates."""
    import subprocess
    import tempfile

    def start(argv: list[str]) -> float:
        t0 = time.perf_counter()
        subprocess.run(argv, check=True, capture_output=True)
        return time.perf_counter() - t0

    dfa_cmd = [sys.executable, "-m", "dfa.cli"]
    numpy_t = min(start([sys.executable, "-c", "import numpy"]) for _ in range(5))
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        log = _identify_log(folder)
        for command, goal in COMMANDS[:2] if quick else COMMANDS:
            argv = command.format(log=log).split()
            if goal is not None and goal < 5.0:  # quick ones: a warm-up, then the median of 3
                start(dfa_cmd + argv)  # the kernels compiled and cached, the files in the page cache
                t = sorted(start(dfa_cmd + argv) for _ in range(3))[1]
            else:  # the slow ones: one run after one that compiles what the commands before did not (its workers')
                start(dfa_cmd + argv)
                t = start(dfa_cmd + argv)
            runs, samples = _counted(argv)
            if argv[0] == "zwidth":  # its grid runs outside the design searches' run cache: its JSON counts them
                runs, samples = _zwidth_simulations(argv), float("nan")
            met = "–" if goal is None else (f"≤ {goal:g} s: " + ("met" if t <= goal else "NOT met"))
            shown = command.format(log="delta_chirp_16k.csv")
            sampled = "–" if samples != samples else f"{samples:.3g}"  # NaN: not counted
            rows.append(f"| `dfa {shown}` | {t:.2f} | {t / numpy_t:.1f} | {runs} | {sampled} | {met} |")
    return "\n".join([
        "",
        "## Everyday commands (issue 43)",
        "",
        "Each command in a fresh process: the median of 3 runs after one that fills the caches (for those with a",
        "goal of 5 s or more, or none: one run after that one), dfa's bytecode compiled first as pip does; × is the",
        "time over",
        f'`python -c "import numpy"` ({numpy_t:.3f} s, best of 5) timed in the same run. Runs and samples: what the',
        "command simulates through the design searches' run cache, counted in-process (samples are the runs'",
        "lengths: a run that rests or diverges stops earlier; the Z-width's grid: its JSON's count, samples not",
        "counted). The identify log: 16,000 samples of the Delta driven",
        "by a chirp (written by the benchmark with `synthetic_log`).",
        "",
        "| command | seconds | × import numpy | runs | samples | goal |",
        "|---|---:|---:|---:|---:|---|",
        *rows,
    ]) + "\n"  # fmt: skip


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--out", default=os.path.join(HERE, "..", "reports", "benchmarks.md"))
    ap.add_argument("--quick", action="store_true", help="smaller sizes (for a smoke test)")
    ap.add_argument("--only-kernel", action="store_true", help="only the kernel and map-speed sections, printed")
    args = ap.parse_args()
    # dfa's bytecode compiled first, as pip does on install (an environment with PYTHONDONTWRITEBYTECODE set
    # would otherwise compile every module of an editable install again in every command: about 0.15 s)
    import compileall

    compileall.compile_dir(os.path.dirname(dfa.__file__), quiet=1)
    if args.only_kernel:
        print("\n".join(render_kernel(bench_kernel(args.quick), bench_map_speed(args.quick))))
        return 0
    sim = bench_simulator(args.quick)
    kernel = bench_kernel(args.quick)
    mapspeed = bench_map_speed(args.quick)
    fig4 = bench_fig4(args.quick)
    solver = bench_solver(args.quick)
    friction = bench_solver_friction(solver)
    contours = bench_contours(args.quick)
    text = render(sim, fig4, args.quick, solver, friction, contours, kernel, mapspeed)
    text += bench_find_root(args.quick)
    text += bench_startup(args.quick)
    text += bench_commands(args.quick)
    text += bench_design_answer(args.quick)
    text += bench_controller_kernel(args.quick)
    text += bench_wall_pair(args.quick)
    text += bench_controller_design_answer(args.quick)
    text += bench_zwidth(args.quick)
    with open(args.out, "w", encoding="utf-8") as fh:
        fh.write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
