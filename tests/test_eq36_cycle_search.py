"""Limit-cycle search: no crash near σ = ½, no silent absence, no false threshold (eq. 36, 41, 45; issue 12 item 6, issue 17)."""

import json
import math
import re

import mpmath
import numpy as np
import pytest
from cli_text import unwrap
from hypothesis import example, given, settings
from hypothesis import strategies as st
from result_json import written

import dfa
from dfa.analysis.cycles import (
    LimitCycleSearchWarning,
    SearchStatus,
    envelope_bound,
    growth_threshold,
    large_cycle_frequency,
    limit_cycles,
)
from dfa.analysis.describing import DF_ENVELOPE, quantizer_df, quantizer_df_derivative
from dfa.analysis.loop import loop_response
from dfa.cli import main
from dfa.core import dfcore
from dfa.model.wall import WallParams
from dfa.render.text import growth_meaning, search_text


def residual(p, m, w, model="half-delay", delay=0):
    return abs(1 + quantizer_df(m) * loop_response(p, w, m, model=model, wall=WallParams.of(delay=delay)))


# ------------------------------------------------------------- 1. σ = ½ (K = 2c/Δ, eq. 9)
@settings(max_examples=40)
@given(
    st.sampled_from([0.5, 5.0, 100.0]),
    st.sampled_from([0.0, 0.05, 0.3]),
    st.floats(1e-12, 1e-6),
    st.sampled_from([-1.0, 1.0]),
    st.sampled_from(["half-delay", "pade", "zoh"]),
    st.integers(0, 2),
)
@example(5.0, 0.05, 0.0, 1.0, "pade", 0)  # the reported crash: σ = ½ exactly
@example(5.0, 0.05, 1e-9, -1.0, "half-delay", 1)
@example(5.0, 0.05, 1e-12, 1.0, "pade", 2)
@example(100.0, 0.3, 1e-6, -1.0, "zoh", 2)
def test_eq9_sigma_half_no_exception_and_small_residuals(mu, beta, offset, sign, model, delay):
    p = dfa.Params(mu, beta, 0.5 + sign * offset)
    res = limit_cycles(p, model=model, wall=WallParams.of(delay=delay))
    assert isinstance(res.status, SearchStatus)
    assert res.complete == (res.status is SearchStatus.COMPLETE)
    for c in res.cycles:
        assert residual(p, c.amplitude, c.frequency, model, delay) <= 1e-10


def test_eq9_cli_sigma_half_pade_reported_case(capsys):
    assert main(["limit-cycles", "--mu", "5", "--beta", "0.05", "--sigma", "0.5", "--model", "pade"]) == 0
    out = capsys.readouterr().out
    assert "Traceback" not in out and "unstable" in out


def test_eq41_compiled_brent_reports_no_bracket_instead_of_an_end():
    # D on [3, 4] stays within 0.9..1.05: g = 2 has no root there; the old port returned a bracket end
    assert math.isnan(dfcore._brent(0, 3, 2.0, 0.0, 1.0, 1e-15, 4 * np.finfo(float).eps))
    t = dfcore._brent(0, 3, 1.0, 0.0, 0.5, 1e-15, 4 * np.finfo(float).eps)
    assert abs(dfcore._d_in_t(3, t) - 1.0) < 1e-14


def test_numerical_failure_gives_incomplete_status_and_warning(monkeypatch):
    import dfa.analysis.cycles as cyc

    def broken(self, m):
        raise ValueError("f(a) and f(b) must have different signs")

    monkeypatch.setattr(cyc.PieceOmega, "scalar", broken)
    with pytest.warns(LimitCycleSearchWarning, match="numerical failure"):
        res = limit_cycles(dfa.Params(5.0, 0.1, 0.3))
    assert not res.complete and res.status is SearchStatus.NUMERICAL and res.search.failures >= 1
    assert search_text(res).startswith(f"incomplete: {res.search.failures} root bracket(s)")
    assert res.to_dict()["status"] == "numerical"


# ------------------------------------------------------------- 2. no silent absence
def _delta_10nm():
    entry = dfa.get_device("Delta")
    d = entry.device
    dev = dfa.Device(
        mass=d.mass, damping=d.damping, coulomb=d.coulomb, resolution=1e-8, period=d.period, name="Delta 10 nm"
    )
    return dev, dev.params(entry.stiffness)


def test_eq45_ten_nanometre_encoder_cycle_found_by_default_search():
    dev, p = _delta_10nm()
    res = limit_cycles(p)
    assert res.complete and res.status is SearchStatus.COMPLETE
    (c,) = res.unstable_cycles
    # eq. 44-45 (D ≈ 1 far out): M = (4σ/π)/(sin(ω/2) − βω)
    w = large_cycle_frequency(p.mu)
    m45 = 4 * p.sigma / (math.pi * (math.sin(w / 2) - p.beta * w))
    assert (
        c.amplitude > 1e5 and c.amplitude == pytest.approx(m45, rel=1e-3) and c.frequency == pytest.approx(w, rel=1e-3)
    )
    assert c.residual <= 1e-10
    # the old default range (1e4 ticks) cannot claim absence
    capped = limit_cycles(p, max_amplitude=1e4)
    assert not capped.cycles and not capped.complete and capped.status is SearchStatus.MAX_AMPLITUDE


def test_cli_and_report_never_state_absence_for_an_incomplete_search(capsys):
    assert main(["limit-cycles", "--device", "delta", "--resolution", "1e-8", "--max-amplitude", "1e4"]) == 0
    out = capsys.readouterr().out
    assert "no limit cycle found up to M = 10000 ticks (search incomplete" in out
    assert "no limit cycle predicted" not in out
    from types import SimpleNamespace

    from dfa.studies.design_document import absence_lines

    _dev, p = _delta_10nm()
    thr = tuple((m, growth_threshold(p, model=m, max_amplitude=1e4)) for m in ("half-delay", "zoh"))
    lines = absence_lines(SimpleNamespace(thresholds=thr))  # the report's sentences read only these
    assert len(lines) == 2 and all(
        "search incomplete" in s and "no limit cycle is predicted" not in s.lower() for s in lines
    )


def test_envelope_bound_default_range_is_complete_against_a_brute_force_range():
    """The automatic range stops where the eq. 41 envelope excludes roots: a 40 000-tick search finds nothing more."""
    for p in (dfa.Params(5.0, 0.48, 0.0201), dfa.Params(20.0, 0.49, 0.3), dfa.Params(2.0, 0.4, 0.1)):
        auto = limit_cycles(p)
        brute = limit_cycles(p, max_amplitude=4e4)
        assert auto.complete
        assert [round(c.amplitude, 9) for c in auto.cycles] == [round(c.amplitude, 9) for c in brute.cycles]
    assert envelope_bound(1.0) == math.inf and envelope_bound(1.0 + DF_ENVELOPE) == 2.0


def test_linear_loop_unstable_without_friction_is_said_and_true(capsys):
    """β = σ = 0: no cycle, and the loop diverges in simulation (eq. 4-5): say so, never "no limit cycle predicted"."""
    assert main(["limit-cycles", "--mu", "5", "--beta", "0", "--sigma", "0"]) == 0
    out = capsys.readouterr().out
    assert "linear loop" in out and "unstable" in out and "exact ZOH" in out and "no limit cycle predicted (" not in out
    assert main(["limit-cycles", "--mu", "5", "--beta", "0", "--sigma", "0", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["cycles"] == [] and d["linear_stable"] is False and d["linear_model"] == "zoh"
    assert dfa.simulate(5.0, 0.0, 0.0, 1.0, 20000, record=False).outcome == "unstable"
    assert main(["limit-cycles", "--mu", "5", "--beta", "0.8", "--sigma", "1"]) == 0
    bound = limit_cycles(dfa.Params(5.0, 0.8, 1.0)).search_bound
    assert (
        f"no limit cycle predicted (search complete: eq. 36 has no root beyond M = {bound:.4g} ticks)"
        in capsys.readouterr().out
    )


# ------------------------------------------------------------- 3. growth band, not a false threshold
CLUSTER = dfa.Params(5.0, 0.48, 0.0201)


def test_eq36_cluster_band_spans_smallest_to_largest_unstable_cycle():
    g = growth_threshold(CLUSTER)
    un = g.result.unstable_cycles
    assert g.is_band and g.unstable_count == len(un) >= 2
    assert g.amplitude == un[0].amplitude and g.amplitude_high == un[-1].amplitude
    assert g.xi_dot == pytest.approx(un[0].amplitude * un[0].frequency, rel=1e-15)
    assert g.xi_dot_high == pytest.approx(un[-1].amplitude * un[-1].frequency, rel=1e-15)
    # the issue's numbers: M_u·ω = 0.51 while simulation diverges from ξ'0 ≈ 2.3; the band's top is above that
    assert g.xi_dot == pytest.approx(0.51, abs=0.01) and g.xi_dot_high > 2.3
    assert (
        g.grows_above
        and "depends on its initial condition" in growth_meaning(g)
        and "first-harmonic" in growth_meaning(g)
    )
    d = g.to_dict()
    assert d["band"]["low"]["amplitude"] == g.amplitude and d["band"]["high"]["xi_dot"] == g.xi_dot_high
    json.dumps(d, allow_nan=False)


def _numbers(text):
    return [float(x) for x in re.findall(r"[-+]?\d+\.?\d*(?:e[-+]?\d+)?", text)]


def test_cli_prints_the_band_numbers_of_the_api(capsys):
    g = growth_threshold(CLUSTER)
    assert main(["limit-cycles", "--mu", "5", "--beta", "0.48", "--sigma", "0.0201"]) == 0
    out = unwrap(capsys.readouterr().out)
    line = next(s for s in out.splitlines() if s.startswith("growth band"))
    nums = _numbers(line)
    assert nums[0] == g.unstable_count
    assert nums[1] == pytest.approx(g.amplitude, rel=1e-3) and nums[2] == pytest.approx(g.amplitude_high, rel=1e-3)
    assert nums[3] == pytest.approx(g.xi_dot, rel=1e-3) and nums[4] == pytest.approx(g.xi_dot_high, rel=1e-3)
    assert main(["limit-cycles", "--mu", "5", "--beta", "0.48", "--sigma", "0.0201", "--json"]) == 0
    d = json.loads(capsys.readouterr().out)["growth_threshold"]
    assert d["band"]["high"]["amplitude"] == written(g.amplitude_high) and d["unstable_count"] == g.unstable_count


def test_cli_prints_the_single_threshold_of_the_api_with_units(capsys):
    entry = dfa.get_device("Delta")
    g = growth_threshold(entry.device.params(entry.stiffness), entry.device, model="zoh")
    assert g.unstable_count == 1 and not g.is_band
    assert main(["limit-cycles", "--device", "delta", "--model", "zoh"]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("growth threshold"))
    nums = _numbers(line)
    assert nums[0] == pytest.approx(g.amplitude, rel=1e-3) and nums[1] == pytest.approx(g.xi_dot, rel=1e-3)
    assert nums[2] == pytest.approx(g.velocity, rel=1e-3) and nums[3] == pytest.approx(g.position, rel=1e-3)


# ------------------------------------------------------------- 4. Loeb sign and few_samples, checked independently
def _independent_loeb(p, m, w, model="half-delay"):
    """∂U/∂M·∂V/∂ω − ∂U/∂ω·∂V/∂M of U + jV = 1/L + D by central differences of loop_response and quantizer_df."""

    def c(mm, ww):
        return 1 / loop_response(p, ww, mm if p.sigma > 0 else None, model=model) + quantizer_df(mm)

    hm, hw = 1e-6 * m, 1e-6 * w
    cm = (c(m + hm, w) - c(m - hm, w)) / (2 * hm)
    cw = (c(m, w + hw) - c(m, w - hw)) / (2 * hw)
    return cm.real * cw.imag - cw.real * cm.imag


@pytest.mark.parametrize("p", [dfa.Params(5.0, 0.4, 0.0), dfa.Params(100.0, 0.495, 0.0), dfa.Params(5.0, 0.48, 0.0201)])
@pytest.mark.parametrize("model", ["half-delay", "zoh"])
def test_loeb_sign_matches_an_independent_evaluation(p, model):
    res = limit_cycles(p, model=model)
    assert res.cycles
    for c in res.cycles:
        if abs(c.amplitude - round(c.amplitude)) < 1e-4:
            continue  # D' jumps at integers: no central difference there
        lo = _independent_loeb(p, c.amplitude, c.frequency, model)
        assert (lo > 0) == c.stable, (c, lo)
    if p.sigma == 0.0:  # σ = 0 path: the smallest cycle is stable, the next unstable (D falls, then rises, eq. 41)
        assert res.cycles[0].stable and not res.cycles[1].stable


@pytest.mark.parametrize("period, flag", [(7.999, True), (8.001, False)])
def test_few_samples_flag_at_eight_samples(period, flag):
    from dfa.analysis.cycles import limit_cycle_at

    c = limit_cycle_at(0.5, 2 * math.pi / period, 1.0, 0.0)
    assert c.few_samples is flag and c.period == pytest.approx(period)


def test_few_samples_flag_on_real_cycles_matches_their_period():
    res = limit_cycles(dfa.Params(5.0, 0.1, 0.3))
    assert any(c.few_samples for c in res.cycles) and any(not c.few_samples for c in res.cycles)
    assert all(c.few_samples == (c.period < 8.0) for c in res.cycles)


# ------------------------------------------------------------- issue 17: D(M) for large M
def _mp_df(m, dps=30):
    mpmath.mp.dps = dps
    mm = mpmath.mpf(m)
    n = int(mpmath.floor(mm))
    s = mpmath.fsum(mpmath.sqrt((mm - k) * (mm + k)) for k in range(1, n + 1))
    return (2 * mm + 4 * s) / (mpmath.pi * mm * mm)


@pytest.mark.parametrize("m", [1000.0, 1000.3, 1234.567, 4096.999, 20000.25])
def test_eq41_asymptotic_against_mpmath_sum(m):
    assert abs(dfcore.df_value(m) - float(_mp_df(m))) <= 2e-16


def test_eq41_asymptotic_switch_is_continuous_with_the_exact_sum():
    a = dfcore.ASYMPTOTIC_FROM
    for m in (a - 1e-9, a - 0.5, a - 0.9):
        exact = float(_mp_df(m))
        assert (
            abs(dfcore._asym_value(m, m % 1.0) + 1.0 - exact) <= 2e-16
        )  # the expansion already holds below the switch
    below, above = a * (1 - 1e-15), a  # exact 1000-term sum just below the switch, expansion at it
    assert abs(dfcore.df_value(below) - float(_mp_df(below))) <= 4e-15  # the sum's own rounding
    assert abs(dfcore.df_value(above) - float(_mp_df(above))) <= 2e-16
    assert abs(dfcore.df_value(above) - dfcore.df_value(below)) <= 5e-15
    for m in (a - 0.3, a + 0.3):  # D' on both sides against a central difference of the exact value
        h = 1e-5
        fd = (float(_mp_df(m + h)) - float(_mp_df(m - h))) / (2 * h)
        assert dfcore.df_derivative(m) == pytest.approx(fd, rel=1e-5)


def test_eq41_huge_amplitudes():
    # issue 17: 1e19 ticks used to overflow the level count (6.4e-20); D → 1 with 1 − D(n) ≈ 0.3743 n^{-3/2}
    assert quantizer_df(1e19) == 1.0
    d = quantizer_df(np.array([1e9, 1e9 + 0.25]))
    mpmath.mp.dps = 40
    z = lambda th: float(mpmath.zeta(-0.5, th))
    for m, val in zip((1e9, 1e9 + 0.25), d, strict=False):
        lead = 1 + 4 * math.sqrt(2) / math.pi * z(m % 1.0) * m**-1.5
        assert val == pytest.approx(lead, abs=1e-16)
    assert quantizer_df_derivative(1e9 + 0.25) == pytest.approx(
        float(
            mpmath.diff(
                lambda x: 4 * mpmath.sqrt(2) / mpmath.pi * mpmath.zeta(-0.5, x - int(1e9)) * x**-1.5, 1e9 + 0.25
            )
        ),
        rel=1e-6,
    )


def test_eq41_envelope_constant_from_the_expansion():
    """(4√2/π)|ζ(−½)| = 0.3743 is the integer excursion quoted in dfa.analysis.describing, below DF_ENVELOPE."""
    lead = 4 * math.sqrt(2) / math.pi * abs(float(mpmath.zeta(-0.5)))
    assert lead == pytest.approx(0.3743, abs=1e-4) and lead < DF_ENVELOPE
    assert (1 - dfcore.df_value(5000.0)) * 5000.0**1.5 == pytest.approx(lead, rel=1e-3)


# ------------------------------------------------------------- validation item 5: clusters against simulation
def test_validation_cluster_threshold_record_matches_independent_runs():
    from dfa.studies.validation import CLUSTER_POINTS, cluster_threshold
    from dfa.studies.validation_document import cluster_note

    name, p = CLUSTER_POINTS[0]
    speeds = [0.3, 0.6, 1.0, 2.3, 2.5, 9.0]
    rec = cluster_threshold(name, p, speeds, 40_000)
    div = [dfa.simulate(p.mu, p.beta, p.sigma, v, 40_000, record=False).outcome == "unstable" for v in speeds]
    assert rec["first_diverging"] == speeds[div.index(True)] == 2.3  # the issue's ξ'0 ≈ 2.3
    assert rec["last_non_diverging"] == max(v for v, d in zip(speeds, div, strict=False) if not d)
    assert rec["diverging"] == sum(div) and rec["linear_stable_zoh"] is False
    g = growth_threshold(p, model="zoh")
    assert rec["band_zoh"] == [g.xi_dot, g.xi_dot_high] and rec["unstable_zoh"] == g.unstable_count
    assert rec["band_zoh"][0] < rec["first_diverging"]  # no start below the band diverged
    cf = dfa.analysis.cycles.large_cycle_closed_form(p.mu, p.beta, p.sigma)
    assert rec["eq45_xi_dot"] == pytest.approx(cf[0] * cf[1], rel=1e-15)
    note = cluster_note([rec])
    assert f"{rec['first_diverging']:.3g}" in note and f"{g.xi_dot_high:.3g}" in note and "not a threshold" in note


def test_validation_eq45_worst_point_above_the_zoh_linear_bound_does_not_diverge():
    """Fig. 7's worst eq. 45 ratio (exact M_u 14.6× below eq. 45): β is above the exact ZOH linear bound, and no start diverges."""
    from dfa.analysis.linear import linear_stable
    from dfa.studies.validation import CLUSTER_POINTS

    _name, p = CLUSTER_POINTS[1]
    m45 = dfa.analysis.cycles.large_cycle_closed_form(p.mu, p.beta, p.sigma)[0]
    assert m45 / limit_cycles(p).unstable_cycles[0].amplitude == pytest.approx(14.64, abs=0.01)
    assert linear_stable(p.mu, p.beta)
    assert not growth_threshold(p, model="zoh").grows_above
    for v in (1.0, 7.35, 30.0):
        assert dfa.simulate(p.mu, p.beta, p.sigma, v, 40_000, record=False).outcome != "unstable"


def test_report_growth_paragraph_prints_the_band_of_the_api():
    from types import SimpleNamespace

    from dfa.studies.design_document import growth_text

    dev = dfa.get_device("Delta").device
    g = growth_threshold(CLUSTER, dev, model="zoh")
    text = growth_text(SimpleNamespace(threshold=lambda model: g, device=dev))
    assert text.startswith("**Growth band**") and f"{g.unstable_count} unstable cycles" in text
    for x in (g.amplitude, g.amplitude_high, g.xi_dot, g.xi_dot_high):
        assert f"{x:.4g}" in text
    assert f"{g.velocity_high:.4g}" in text or f"{g.velocity_high:.3g}" in text
    assert "depends on its initial condition" in text


def test_example_cluster_threshold_quick_writes_its_note(tmp_path):
    import os
    import subprocess
    import sys

    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    proc = subprocess.run(
        [sys.executable, os.path.join(root, "examples", "cluster_threshold.py"), "--quick", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    text = (tmp_path / "cluster_threshold.md").read_text()
    assert "first diverging" in text and "Long runs" in text


@pytest.mark.parametrize("p", [dfa.Params(5.0, 0.1, 0.3), dfa.Params(5.0, 0.4, 0.0), dfa.Params(2.0, 0.4, 0.1)])
def test_search_bound_no_root_beyond_it(p):
    """A complete search states where roots end: a search to 4× that bound finds no further cycle."""
    res = limit_cycles(p)
    assert res.complete and res.search_bound >= max(c.amplitude for c in res.cycles)
    far = limit_cycles(p, max_amplitude=4 * res.search_bound + 100)
    assert [c.amplitude for c in far.cycles if c.amplitude > res.search_bound] == []


def test_size_budget_ends_incomplete_not_open_ended(monkeypatch, capsys):
    """With a tiny interval budget the 10 nm Delta search (cycle at ~1.9e5 ticks) ends BUDGET, and nothing claims absence."""
    import dfa.analysis.cycles as cyc

    monkeypatch.setattr(cyc.search, "INTERVAL_BUDGET", 5)
    _dev, p = _delta_10nm()
    res = limit_cycles(p)
    assert res.status is SearchStatus.BUDGET and not res.complete and res.search_bound is None
    assert not res.cycles and res.search.reached == res.max_amplitude < 2e5
    assert "size budget" in search_text(res)
    assert main(["limit-cycles", "--device", "delta", "--resolution", "1e-8"]) == 0
    out = capsys.readouterr().out
    assert f"no limit cycle found up to M = {res.max_amplitude:g} ticks (search incomplete: " in out
    assert "no limit cycle predicted" not in out


def test_eq36_failed_omega_solve_in_the_scan_is_counted_not_skipped(monkeypatch):
    """A NaN ω(M) from the elementwise root finder makes the search incomplete (NUMERICAL), never silently shorter."""
    import dfa.analysis.cycles as cyc

    real = cyc.phase._omega_for_m

    def some_fail(lp, m, wa, wb):
        w = real(lp, m, wa, wb)
        w[::7] = np.nan
        return w

    monkeypatch.setattr(cyc.phase, "_omega_for_m", some_fail)
    with pytest.warns(LimitCycleSearchWarning, match="numerical failure"):
        res = limit_cycles(dfa.Params(5.0, 0.1, 0.3))
    assert res.status_code is SearchStatus.NUMERICAL and not res.complete


# ----------------------------------------------------------------------------- the μ range the search covers
@pytest.mark.parametrize(("mu", "beta", "sigma"), [(1e-6, 5e-9, 5.0), (1e8, 0.1, 0.3), (1e8, 0.1, 0.8)])
def test_eq36_cycles_at_the_ends_of_searched_mu_lie_well_inside_the_frequency_grid(mu, beta, sigma):
    """At both ends of SEARCHED_MU the extreme cycles are found, about 10× or more inside W_GRID's gaps: near Nyquist
    (π − ω ≈ 20μ, tiny μ) and at the large family's ω ≈ 1/√μ (large μ). The search is complete there."""
    from dfa.analysis.cycles import SEARCHED_MU, W_GRID

    assert mu in SEARCHED_MU
    res = limit_cycles(dfa.Params(mu, beta, sigma))
    assert res.status is SearchStatus.COMPLETE and res.cycles
    w = [c.frequency for c in res.cycles]
    assert min(w) >= 9.0 * W_GRID[0] and math.pi - max(w) >= 9.0 * (math.pi - W_GRID[-1])
    # beyond the ends the same cycle moves into the gap: π − ω and ω scale as predicted
    if mu < 1.0:
        assert math.pi - max(w) == pytest.approx(20.0 * mu, rel=0.1)
    else:
        assert min(w) * math.sqrt(mu) == pytest.approx(1.0, rel=0.1)


@pytest.mark.parametrize("mu", [1e-11, 1e10, 1e-49])
def test_eq36_outside_searched_mu_nothing_is_claimed_and_nothing_warns(mu, recwarn):
    # at μ = 1e-11 and 1e10 the search used to miss the cycle (ω in the grid's gap) and say "complete";
    # at μ = 1e-49 (dfa stiffness --coulomb 1e50) it printed a numerical-failure warning per stiffness
    res = limit_cycles(dfa.Params(mu, 0.005 * mu if mu < 1 else 0.1, 5.0 if mu < 1 else 0.3))
    assert res.status is SearchStatus.FREQUENCY_RANGE and not res.complete and res.cycles == ()
    assert res.search.frequency_range and res.to_dict()["search"]["frequency_range"] is True
    assert search_text(res).startswith(f"incomplete: not searched: μ = {mu:.3g} lies outside 1e-06 … 1e+08")
    assert not [w for w in recwarn if issubclass(w.category, LimitCycleSearchWarning)]
    # nor a claim on growth (it said "amplitudes grow without bound" from the linear loop alone)
    g = growth_threshold(res.params)
    assert g.status.value == "not_searched" and g.grows_above is None and g.amplitude is None


def test_eq36_stiffness_says_why_the_describing_function_has_no_limit_outside_searched_mu(capsys):
    argv = ["stiffness", "--mass", "0.1", "--damping", "0.5", "--coulomb", "1e50", "--resolution", "1e-5"]
    assert main([*argv, "--period", "1e-3", "--velocity", "0.1"]) == 0
    out, err = capsys.readouterr()
    assert "LimitCycleSearchWarning" not in err
    assert "describing function: none: undecided already at" in unwrap(out)
    assert "outside the range the cycle search covers (1e-6 … 1e8)" in unwrap(out)
