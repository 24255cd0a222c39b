"""K_max four ways with a wall controller (issue 15 item 5, issue 14 §1): the simulated limit against an
independent bisection over controller simulations written here, the orderings theory requires (criterion <=
simulated no-divergence, rest <= no-divergence, or the counterexample reported), the B = 0 wall equal to the
spring's design answer, the describing-function limit against limit_cycles(wall=), `dfa stiffness` with the
controller flags, and default_samples(wall=)."""

import functools
import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from result_json import written

import dfa
import dfa.analysis.limits.kmax as kmax
from dfa.analysis.cycles import limit_cycles
from dfa.analysis.limits.closed_form import k_gil, k_max_criterion
from dfa.analysis.limits.kmax import design_answer
from dfa.analysis.limits.recommend import recommend_stiffness
from dfa.analysis.limits.runs import simulate_points
from dfa.analysis.linear_wall import controlled_spectral_radius
from dfa.analysis.simulation import default_samples, divergence_bound, preload_position, simulate
from dfa.cli import main
from dfa.errors import DFAValueError
from dfa.model.device import Params
from dfa.model.wall import MIN_LAG, Wall, WallParams
from dfa.render.answer import stiffness_screen
from dfa.render.controller import controller_limit_rows
from dfa.render.limits import BELOW_K, PROOF_NOTE, evidence_text, limit_text
from dfa.results.status import KMaxStatus, LimitStatus

DELTA = dfa.get_device("Delta").device
SMALL = {"speeds": 2, "grid": 6}


def _groups(dev, k, b, d=0, fc=None, fbw=None):
    """(μ, β, σ) and the controller's groups at K, written here: β_B = B/(KT), ν_c = f_c T, α = 1/(2π f_bw T)."""
    t = dev.period
    p = Params(dev.mass / (k * t * t), dev.damping / (k * t), dev.coulomb / (k * dev.resolution))
    lag = 0.0 if fbw is None else 1.0 / (2 * math.pi * fbw * t)
    return p, WallParams.of(damping=b / (k * t), delay=d, cutoff=None if fc is None else fc * t, lag=lag)


def _check_theory(r):
    """The orderings theory requires, or the counterexample the result reports."""
    assert r.counterexamples == (), f"counterexample to the extended criterion: {r.counterexamples}"
    assert r.status in (KMaxStatus.OK, KMaxStatus.CAVEATS)
    if r.k_sim.value is not None:
        if r.k_criterion.value is not None:
            assert r.k_criterion.value <= r.k_sim.value * (1 + 1e-9)
    else:
        assert r.k_sim.status is LimitStatus.ABOVE_RANGE
    if r.k_sim_rest.value is not None and r.k_sim.value is not None:
        assert r.k_sim_rest.value <= r.k_sim.value * (1 + 1e-9)
    d = json.loads(json.dumps(r.to_dict(), allow_nan=False))
    for key in ("k_df", "k_sim", "k_sim_rest"):
        assert d[key]["value"] == r.searches[key].value and d[key]["status"] == r.searches[key].status.value
        if d[key]["value"] is None:
            assert d[key]["null_reasons"]["/value"] == r.searches[key].status.message


# ---------------------------------------------------------------- independent bisection
def _diverges(dev, k, speeds, b, d=0):
    """True if an impact at one of ``speeds`` (from ξ0 = 0 or the preload) diverges at K with damper B."""
    p, c = _groups(dev, k, b, d)
    for v in speeds:
        xd = v * dev.period / dev.resolution
        for x0, v0 in ((0.0, xd), (preload_position(p.mu, xd), 0.0)):
            n = min(default_samples(p.mu, p.beta, p.sigma, v0, x0, wall=c), 10**6)
            bound = divergence_bound(x0, v0, p.mu, 1e6)
            run = simulate(p.mu, p.beta, p.sigma, v0, n, xi0=x0, record=False, bound=bound, wall=c)
            if run.outcome == "unstable":
                return True
    return False


def test_eq11_controller_k_sim_matches_independent_bisection():
    v, b = 0.1, 1.0
    r = design_answer(DELTA, v, wall=Wall.of(14500.0, damping=b), speeds=3, grid=8)
    speeds = [v * i / 3 for i in (1, 2, 3)]
    assert r.evidence.speeds == pytest.approx(speeds, rel=1e-12)
    # the grid written here: 8 geometric points from K_criterion/2 to 8 × the largest bound, and K_criterion;
    # safety is not monotone in K near this limit, so the bisection starts from the same bracket as the search
    kc = r.k_criterion.value
    top = 8 * max(kc, r.k_linear.value, 2 * DELTA.coulomb / DELTA.resolution)
    assert r.evidence.k_range == (kc / 2, pytest.approx(top, rel=1e-12))
    grid = sorted({*np.geomspace(kc / 2, top, 8), kc})
    first = next(i for i, k in enumerate(grid) if _diverges(DELTA, k, speeds, b))
    assert grid[first - 1] >= kc
    lo, hi = grid[first - 1], grid[first]
    while hi - lo > 1e-3 * hi:
        mid = math.sqrt(lo * hi)
        lo, hi = (lo, mid) if _diverges(DELTA, mid, speeds, b) else (mid, hi)
    assert not r.k_sim.non_monotone
    assert r.k_sim.searched_value == pytest.approx(lo, rel=5e-3)
    assert r.k_sim.first_failure == pytest.approx(hi, rel=5e-3)
    assert r.k_sim.value <= r.k_sim.searched_value
    assert (r.k_sim.value < r.k_sim.searched_value) == bool(r.k_sim.failures) == r.k_sim.lowered
    assert all(f.stiffness > r.k_sim.value for f in r.k_sim.failures)  # every failure met lies above the limit
    assert kc < r.k_sim.value  # the extended criterion holds, with margin


# ---------------------------------------------------------------- orderings on the catalogue
def _controllers(dev, k):
    """A damper (β_B = 0.2 at K), the damper behind a filter at 0.05 cycles/sample with a delay, an amplifier lag."""
    t = dev.period
    b = 0.2 * k * t
    return {
        "damper": Wall.of(k, damping=b),
        "filter": Wall.of(k, damping=b, delay=1, filter_cutoff=0.05 / t),
        "lag": Wall.of(k, damping=b, amplifier_bandwidth=1.0 / (2 * math.pi * 0.3 * t)),
    }


@pytest.mark.parametrize("kind", ["damper", "filter", "lag"])
@pytest.mark.parametrize("name", ["Delta", "Impulse Engine"])
def test_eq11_controller_kmax_orderings_catalogue(name, kind):
    e = dfa.get_device(name)
    ctl = _controllers(e.device, e.stiffness)[kind]
    r = design_answer(e.device, 0.1, wall=ctl, **SMALL)
    _check_theory(r)
    assert (r.k_criterion.status is LimitStatus.NOT_COVERED) == (kind == "lag")
    ev = r.evidence
    assert ev.simulations > 0 and len(ev.speeds) == 2 and ev.k_range[0] < ev.k_range[1]


def test_eq11_controller_b0_is_the_spring_design_answer():
    """A wall of B = 0 without filter or lag (any delay, any K of its own) is the spring's design answer, bit for bit:
    the closed forms of eq. 11 and the exact linear bound k_gil, the spring's published bounds, the same searches.
    (Formerly the controller's implementation against the spring's; now one implementation, whose answer must not
    depend on the wall's own K, nor differ from the default spring's.)"""
    for dev, v, d in ((DELTA, 0.1, 0), (dfa.get_device("Impulse Engine").device, 0.2, 1)):
        r = design_answer(dev, v, wall=Wall.of(100.0, delay=d), **SMALL)
        s = design_answer(dev, v, **SMALL) if d == 0 else design_answer(dev, v, wall=Wall.of(1.0, delay=d), **SMALL)
        assert r.wall.params(dev.period).is_spring and r.delay == s.delay == d
        assert r.k_criterion.value == k_max_criterion(dev, v, d) and r.k_linear.value == k_gil(dev, delay=d)
        assert r.k_criterion == s.k_criterion and r.k_linear == s.k_linear
        assert None not in (r.k_static, r.k_colgate, r.k_abbott_okamura)
        assert (r.k_static, r.k_colgate, r.k_abbott_okamura) == (s.k_static, s.k_colgate, s.k_abbott_okamura)
        for key in ("k_df", "k_sim", "k_sim_rest"):
            assert r.searches[key] == s.searches[key], key
        assert (r.evidence, r.counterexamples, r.status) == (s.evidence, s.counterexamples, s.status)


# ---------------------------------------------------------------- describing function
def _growth(dev, k, b, d=0):
    """Smallest M·ω over the unstable cycles (inf: none and a stable linear loop; 0: an unstable linear loop)."""
    p, c = _groups(dev, k, b, d)
    res = limit_cycles(p, model="half-delay", wall=c)
    if res.unstable_cycles:
        return min(cy.amplitude * cy.frequency for cy in res.unstable_cycles)
    return 0.0 if res.linear_stable is False else math.inf


@pytest.mark.parametrize("b, d", [(1.0, 0), (0.5, 1)])
def test_eq36_controller_k_df_against_limit_cycles(b, d):
    v = 0.1
    r = design_answer(DELTA, v, wall=Wall.of(14500.0, damping=b, delay=d), simulate=False)  # k_df as in the full
    s = r.k_df
    assert s.value is not None and s.first_failure is not None
    xd = DELTA.xi_dot(v)
    if not s.non_monotone:
        assert _growth(DELTA, s.value, b, d) >= xd
        assert _growth(DELTA, s.first_failure, b, d) < xd
        assert s.first_failure <= s.value * (1 + 3e-3)


# ---------------------------------------------------------------- dfa stiffness
@pytest.fixture
def small_search(monkeypatch):
    """`dfa stiffness` with the small search (the CLI calls dfa.analysis.limits.kmax.design_answer)."""
    monkeypatch.setattr(kmax, "design_answer", functools.partial(design_answer, **SMALL))


def _values(d):
    """The limits' values of a JSON record of a K_max answer."""
    return [d[key]["value"] for key in ("k_criterion", "k_linear", "k_df", "k_sim", "k_sim_rest")]


def test_cli_stiffness_controller_text_and_json(capsys, small_search):
    argv = ["stiffness", "--device", "delta", "--velocity", "0.1", "--virtual-damping", "1"]
    assert main(argv) == 0
    screen = capsys.readouterr().out
    r = design_answer(DELTA, 0.1, wall=Wall.of(14500.0, damping=1.0), assess=True, source="catalogue", **SMALL)
    # the default: one screen rendered from the same result, every line under 100 characters (issue 26)
    assert screen.splitlines() == stiffness_screen(r, recommend_stiffness(r))
    assert max(len(line) for line in screen.splitlines()) <= 100
    for s in r.searches.values():
        assert s.value is not None and f"{s.value:.5g} N/m" in screen
    assert main([*argv, "--explain"]) == 0
    out = capsys.readouterr().out
    for s in r.searches.values():
        assert f"  {limit_text(s, 'N/m', explain=True, velocity_unit='m/s')}\n" in out  # each limit as rendered
    assert f"{r.evidence.simulations} exact simulations" in out and f"evidence: {evidence_text(r)}." in out
    # a simulated K_max claims the simulated speeds, starts and stiffnesses, not every K below it (red team:
    # divergent bands below K_sim): the closing note always, and with --explain each confirmation's claim
    fresh = PROOF_NOTE.replace("a proof", "a proof (for a wall whose memory is fresh at t = 0)")  # a damper's memory
    assert fresh in " ".join(out.split()) and "only the criterion is a proof" in out
    assert "simulated speeds, starts and stiffnesses" in out
    assert "largest passive speed at K = 14500 N/m (catalogue K)" in out
    a = r.assessment
    assert f"{a.max_passive_velocity:.4g} m/s" in out
    assert f"{a.outcomes['impact']} (from ξ0 = 0), {a.outcomes['preload']} (preload)" in out
    explained = out
    assert explained.count(BELOW_K) == 2  # k_sim and k_sim_rest: each says what its confirmation does not exclude
    for s in r.searches.values():
        assert limit_text(s, "N/m", explain=True, velocity_unit="m/s") in explained
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert _values(d) == written(
        [r.k_criterion.value, r.k_linear.value, r.k_df.value, r.k_sim.value, r.k_sim_rest.value]
    )
    assert d["evidence"]["simulations"] == r.evidence.simulations
    assert d["assessment"]["source"] == "catalogue" and d["stiffness_source"] == "catalogue"
    assert d["wall"]["damping"] == 1.0 and d["wall"]["dimensionless"]["damping"] > 0 and d["status"] == r.status.value


def test_cli_stiffness_controller_lag_json_nulls_explained(capsys, small_search):
    """With an amplifier lag: K_criterion null, not covered (and so no counterexample check: there is no criterion
    to contradict; the former ``counterexample_check`` sentence is the status now), every null explained."""
    from test_cli_json_null_reasons import unexplained_nulls

    argv = ["stiffness", "--device", "delta", "--velocity", "0.1", "--amplifier-bandwidth", "500", "--json"]
    assert main(argv) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["k_criterion"]["value"] is None and d["k_criterion"]["status"] == "not_covered"
    assert d["k_criterion"]["null_reasons"]["/value"] == LimitStatus.NOT_COVERED.message
    assert d["counterexamples"] == [] and d["status"] != "counterexample"
    assert d["assessment"]["max_passive_velocity"] is None and d["assessment"]["velocity_status"] == "not_covered"
    assert "amplifier lag" in d["assessment"]["null_reasons"]["/max_passive_velocity"]
    assert unexplained_nulls(d) == []


# ---------------------------------------------------------------- default run length
def test_default_samples_controller_spring_unchanged_and_lag_longer():
    # the spring's lengths (any delay) are those of the former spring-only default_samples(delay=d), pinned here
    # (formerly compared with controller=None), and a filter on no damper changes nothing
    for mu, beta, sigma, xd, d, n in (
        (100.0, 0.3, 1.5, 2.0, 0, 50000),
        (156250.0, 0.125, 0.9554, 0.637, 0, 462407),
        (800.0, 2.0, 0.6, 3.0, 1, 50000),
    ):
        assert default_samples(mu, beta, sigma, xd, wall=WallParams.of(delay=d)) == n
        assert default_samples(mu, beta, sigma, xd, wall=WallParams.of(delay=d, cutoff=0.1)) == n
        assert d > 0 or default_samples(mu, beta, sigma, xd, wall=None) == n
    # Impulse Engine at 50 kg: the lag's extra delay α = 0.2 makes the net damping more negative: longer
    n = default_samples(156250.0, 0.125, 0.9554, 0.637)
    assert default_samples(156250.0, 0.125, 0.9554, 0.637, wall=WallParams.of(lag=0.2)) > n
    # a damper that pays for the hold: shorter (net damping β + β_B G − ½ > 0)
    assert default_samples(156250.0, 0.125, 0.9554, 0.637, wall=WallParams.of(damping=2.0)) < n
    # a damper whose lag eats all of it: no decay at all, Coulomb alone: as for the spring with σ small
    no_decay = default_samples(1e4, 0.0, 0.0, 5.0, wall=WallParams.of(damping=0.4, lag=0.5))
    assert no_decay == dfa.analysis.simulation.MAX_DEFAULT_SAMPLES


# filter_too_much: the assume() on a decaying loop rejects most draws; in the full suite the health check has
# failed this test intermittently at the base commit too (9 kept, 50 filtered), never the property itself
@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(
    log_mu=st.floats(2.0, 5.0),
    beta=st.floats(0.0, 1.0),
    beta_b=st.floats(0.0, 2.0),
    cutoff=st.one_of(st.none(), st.floats(0.02, 0.45)),
    lag=st.one_of(st.just(0.0), st.floats(MIN_LAG, 1.5)),  # shorter lags are refused (WallParams)
    delay=st.integers(0, 2),
)
def test_default_samples_controller_decaying_linear_run_rests(log_mu, beta, beta_b, cutoff, lag, delay):
    """A run of default length of a loop the exact linear analysis calls decaying ends at rest (no encoder, no
    Coulomb: the linear loop), not undecided: the length covers the decay."""
    mu = 10**log_mu
    c = WallParams.of(damping=beta_b, delay=delay, cutoff=cutoff, lag=lag)
    rho = controlled_spectral_radius(mu, beta, c)
    assume(rho < 1.0 - 1e-7)  # decays (a margin above rounding), slowly or fast
    xd = 10.0
    n = default_samples(mu, beta, 0.0, xd, quantize=False, wall=c)
    if n >= dfa.analysis.simulation.MAX_DEFAULT_SAMPLES:  # no decay predicted: the cap; keep the test's time modest
        assume(-math.log(rho) * n * 3 / 8 > 1.0)
    run = simulate(mu, beta, 0.0, xd, None, quantize=False, record=False, bound=1e12, wall=c)
    assert run.samples == n
    assert run.outcome == "rest", (n, rho, run.outcome)


def test_default_samples_controller_used_by_simulate_and_search():
    c = WallParams.of(damping=0.5, lag=0.3)
    run = simulate(1e4, 0.1, 0.6, 3.0, None, record=False, wall=c)
    assert run.samples == default_samples(1e4, 0.1, 0.6, 3.0, wall=c)
    outs, lengths = simulate_points([(1e4, 0.1, 0.6, 0.0, 3.0)], [c], 10**6)
    assert lengths == [min(run.samples, 10**6)] and outs == [str(run.outcome)]
    assert np.isfinite(dfa.analysis.simulation.net_damping(1e4, 0.1, c))


def test_cli_stiffness_controller_assesses_given_stiffness(capsys, small_search):
    argv = ["stiffness", "--device", "delta", "--velocity", "0.1", "--stiffness", "30000", "--virtual-damping", "1"]
    assert main([*argv, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    r = design_answer(DELTA, 0.1, wall=Wall.of(30000.0, damping=1.0), assess=True, source="given", **SMALL)
    a = written(r.assessment.to_dict())
    assert d["assessment"] == a and d["stiffness_source"] == "--stiffness" and a["source"] == "given"
    assert a["stiffness"] == 30000.0 and a["outcomes"]["impact"] in dfa.analysis.simulation.OUTCOMES
    # the same K's limits: the answer does not depend on the K being assessed (B, f_c, f_bw, d held fixed)
    assert d["k_sim"]["value"] == written(r.k_sim.value) and d["k_criterion"]["value"] == written(r.k_criterion.value)
    r14 = design_answer(DELTA, 0.1, wall=Wall.of(14500.0, damping=1.0), **SMALL)
    assert [getattr(r14, k) for k in r.limits] == [getattr(r, k) for k in r.limits]
    assert main([*argv, "--explain"]) == 0
    out = capsys.readouterr().out
    assert "simulated at K = 30000 N/m, impact at V" in out and "predicted cycles at K = 30000 N/m" in out


#: The criterion's row of `dfa stiffness` and of the report with a damper, filter or delay.
CRITERION_ROW = "criterion K_max at this speed (eq. 11 extended to the wall)"


def test_eq6_extended_cli_explains_a_zero_criterion_k(capsys, small_search):
    """Impulse Engine with B = 0.5 N·s/m: c/Δ = 76 N/m < B/T = 500 N/m, so σ >= σ₀ = ½ + β_B fails at every K
    (eq. 6 extended): the criterion gives no K_max and the text says why (red-team: a bare "0 N/m")."""
    e = dfa.get_device("impulse").device
    assert e.coulomb / e.resolution <= 0.5 / e.period
    assert main(["stiffness", "--device", "impulse", "--velocity", "0.1", "--virtual-damping", "0.5", "--explain"]) == 0
    row = next(line for line in capsys.readouterr().out.splitlines() if line.startswith("criterion K_max"))
    assert row.startswith(CRITERION_ROW)
    assert row.endswith(f"  none: {LimitStatus.NEVER.message}") and "σ >= σ₀ needs c/Δ > (1 − a)B/T" in row


def test_eq6_extended_zero_criterion_k_reason_in_the_api_and_report_rows():
    """The reason for no criterion K is the analysis' (the status of KMaxResult.k_criterion), worded by
    dfa.render.limits for the CLI and the report's K_max rows alike."""
    e = dfa.get_device("impulse").device
    r = design_answer(e, 0.1, wall=Wall.of(80.0, damping=0.5), simulate=False)  # the criterion's row is read
    assert r.k_criterion.value is None and r.k_criterion.status is LimitStatus.NEVER
    assert "σ >= σ₀ needs c/Δ > (1 − a)B/T" in r.k_criterion.status.message
    row = dict(controller_limit_rows(r, e.units))
    assert row[CRITERION_ROW] == f"none: {LimitStatus.NEVER.message}" == limit_text(r.k_criterion, "N/m")


def test_simulate_points_controller_runs_batched_equal_simulate_one_by_one():
    """The K_max search's wall runs go through the batch kernels (chunks on threads): each outcome and length is one
    simulate() of its own point and wall (damper, filter, lag, a pure spring; delays 1 and 0 in one batch: the delay
    is each wall's, formerly one delay per batch and a wall of another delay refused); a batch with a wall per point
    missing is refused."""
    rng = np.random.default_rng(16)
    ctls = [
        WallParams.of(damping=0.5, delay=1),
        WallParams.of(damping=0.2, cutoff=0.1, delay=1),
        WallParams.of(damping=0.1, lag=0.3, delay=1),
        WallParams.of(delay=1),
        WallParams.of(damping=0.5),
        WallParams.of(),
    ]
    pts, cs = [], []
    for i in range(36):
        pts.append((10 ** rng.uniform(0.5, 2.5), rng.uniform(0, 1), rng.uniform(0, 1.5), 0.0, rng.uniform(0.3, 4)))
        cs.append(ctls[i % len(ctls)])
    outs, lengths = simulate_points(pts, cs, 20_000)
    want = []
    for (mu, beta, sigma, x0, v0), c, n in zip(pts, cs, lengths, strict=True):
        assert n == min(default_samples(mu, beta, sigma, v0, x0, wall=c), 20_000)
        bound = divergence_bound(x0, v0, mu)
        run = simulate(mu, beta, sigma, v0, n, xi0=x0, record=False, bound=bound, wall=c)
        want.append(str(run.outcome))
    assert outs == want and len(set(outs)) >= 2
    with pytest.raises(DFAValueError, match=r"walls has 1 entries for 2 points: give one per point"):
        simulate_points(pts[:2], cs[:1], 1000)
