"""Outcome classes of the exact simulator (paper eq. 4-5, Fig. 4, Table 2 devices): rest only at the
absorbing state, chatter below one tick (σ < ½ can never rest: |⌊ξ⌋ + ½| >= ½ > σ), undecided when the
run is too short, and the force step in KΔ and newtons (issue 12, items 3 and 6)."""

import inspect
import json
import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from result_json import written

import dfa
from dfa.analysis.maps import StabilityMap, load_map, stability_map
from dfa.analysis.simulation import OUTCOMES, _tail_length, default_samples, simulate
from dfa.cli import main
from dfa.core import kernel
from dfa.model.wall import Wall, WallParams

BELOW_HALF = math.nextafter(0.5, 0.0)


# ---------------------------------------------------------------- chatter and rest


def test_fig4_region_c_reproducer_chatters_and_never_rests():
    """μ = 100, β = σ = 0.3, ξ'0 = 1: `dfa check` says globally unstable (region c); the run never rests."""
    r = simulate(100.0, 0.3, 0.3, 1.0)
    assert r.outcome == "chatter" and r.rest_sample is None
    assert 0.0 < r.amplitude < 1.0 and r.force_peak_to_peak == 1.0  # toggles between two levels: one step KΔ
    assert dfa.passivity_criterion(0.3, 0.3, 1.0).region == "c"


@settings(max_examples=60, deadline=None)
@given(st.floats(0.5, 500.0), st.floats(0.0, 1.5), st.floats(0.0, BELOW_HALF), st.floats(-6.0, 6.0))
@example(100.0, 0.3, 0.0, 1.0)  # σ = 0
@example(100.0, 0.0, 0.3, 1.0)  # β = 0
@example(100.0, 0.8, BELOW_HALF, 1.0)  # σ just below ½
@example(5.0, 0.8, BELOW_HALF, 0.0)  # starts at rest on ξ = 0, but |φ| = ½ > σ pushes it off
def test_sigma_below_half_never_rests(mu, beta, sigma, v0):
    """With the encoder |φ| = |⌊ξ⌋ + ½| >= ½ > σ at every level (eq. 5): the device can never stick."""
    r = simulate(mu, beta, sigma, v0, 4000, record=False)
    assert r.rest_sample is None
    assert r.outcome in ("chatter", "oscillating", "unstable", "undecided")


@settings(max_examples=60, deadline=None)
@given(st.floats(0.5, 300.0), st.floats(0.0, 1.5), st.floats(0.0, 2.5), st.floats(-4.0, 4.0), st.integers(0, 2))
@example(100.0, 0.3, 1.5, 2.0, 0)
@example(5.0, 0.2, 0.5, 0.0, 0)  # σ = ½ exactly at ξ = 0: |φ| = σ sticks at once
def test_rest_only_at_the_absorbing_state(mu, beta, sigma, v0, delay):
    """ "rest" iff the kernel found the absorbing state: ξ' = 0, |φ| <= σ, every pending force equal."""
    r = simulate(mu, beta, sigma, v0, 4000, wall=WallParams.of(delay=delay))
    assert (r.outcome == "rest") == (r.rest_sample is not None)
    if r.outcome == "rest":
        phi = -(math.floor(r.final_xi) + 0.5)
        assert r.final_xi_dot == 0.0 and abs(phi) <= sigma
        k = r.rest_sample
        assert np.all(r.xi[k:] == r.final_xi) and np.all(r.xi_dot[k:] == 0.0)
        assert r.force_peak_to_peak == 0.0 and r.amplitude == 0.0


def test_sub_tick_motion_that_is_not_at_rest_is_never_called_rest():
    """The old rule called every sub-tick tail 'stable'; chatter around ξ = 0 with σ < ½ is not rest."""
    r = simulate(5.0, 0.8, 0.2, 0.0, 20000)
    assert r.outcome == "chatter" and r.rest_sample is None and r.frequency > 0


def test_fig4_region_b_is_light_not_white():
    """Paper Fig. 4 paints region b (β > ½, σ < ½) light: persisting oscillation, never rest.

    At σ = 0 a few points keep a settled cycle of 1.3-4.4 ticks (the exact D exceeds 1 near M ≈ 1.24, eq. 41)."""
    m = stability_map(
        100.0,
        [1.0, 5.0],
        beta_range=(0.55, 1.0),
        sigma_range=(0.0, 0.45),
        grid=5,
        samples=50_000,
        n_jobs=1,
        progress=False,
    )
    names = [OUTCOMES[c] for c in m.outcome.ravel()]
    assert set(names) == {"chatter", "oscillating"}
    assert names.count("chatter") >= 40
    assert {OUTCOMES[c] for c in m.outcome[:, 1:, :].ravel()} == {"chatter"}  # σ > 0: all chatter


# ---------------------------------------------------------------- run length and undecided

IMPULSE_50KG = dict(
    mu=156250.0, beta=0.125, sigma=0.024 / (80.0 * 314e-6)
)  # Impulse Engine, m overridden to 50 kg, K = 80 N/m


def _impulse_50kg():
    e = dfa.get_device("impulse").device
    dev = dfa.Device(50.0, e.damping, e.coulomb, e.resolution, e.period, "Impulse Engine 50 kg")
    return dev, dev.params(80.0), dev.xi_dot(0.1)


def test_table2_impulse_engine_at_50kg_is_not_an_oscillation():
    """Reproducer: 50 000 samples ended in a decaying 200-tick transient called 'oscillating'; it rests at 181 900."""
    _dev, p, xd = _impulse_50kg()
    short = simulate(p.mu, p.beta, p.sigma, xd, 50_000, record=False)
    assert short.outcome == "undecided" and short.suggested_samples >= 181_900
    env = short.envelope
    assert env[5] > env[6] > env[7]  # still decaying
    auto = simulate(p.mu, p.beta, p.sigma, xd, record=False)
    assert auto.samples_auto and auto.samples >= 181_900
    assert auto.outcome == "rest" and auto.rest_sample == 181_900
    again = simulate(p.mu, p.beta, p.sigma, xd, short.suggested_samples, record=False)
    assert again.outcome == "rest"


def test_cli_table2_impulse_engine_at_50kg_rests(capsys):
    assert main(["simulate", "--device", "impulse", "--mass", "50", "--velocity", "0.1"]) == 0
    out = capsys.readouterr().out
    assert "rest: came to rest" in out and "181900" in out and "oscillating" not in out
    assert (
        main(["simulate", "--device", "impulse", "--mass", "50", "--velocity", "0.1", "--samples", "50000", "--json"])
        == 0
    )
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == "undecided" and d["suggested_samples"] >= 181_900 and d["samples_auto"] is False


def test_default_samples_closed_form():
    """σ = 0, β > ½: dA/dτ = −aA, a = (β − ½)/(2μ), t_d = ln(A0)/a, A0 = √μ·ξ'0; default = 2 t_d + 40·2π√μ."""
    mu, beta, v0 = 100.0, 0.51, 2.0
    a = (beta - 0.5) / (2 * mu)
    expect = 2 * math.log(math.sqrt(mu) * v0) / a + 40 * 2 * math.pi * math.sqrt(mu)
    assert default_samples(mu, beta, 0.0, v0) == math.ceil(expect)
    # Coulomb only at β = ½: linear decay of 4σ ticks per period, t_d = (A0 − 1)/c, c = 2σ/(π√μ)
    c = 2 * 0.3 / (math.pi * 10.0)
    assert default_samples(100.0, 0.5, 0.3, 60.0) == math.ceil(2 * (600 - 1) / c + 80 * math.pi * 10)
    assert default_samples(100.0, 0.3, 1.5, 2.0) == 50_000  # never below the paper's run
    assert default_samples(100.0, 0.5, 0.0, 2.0) == 10_000_000  # no decay at all: the cap
    assert default_samples(100.0, 0.5, 0.0, 2.0, cap=False) == 100_000_000
    # the averaged decay time matches the simulated rest of the 50 kg reproducer within 1 %
    _dev, p, xd = _impulse_50kg()
    td = (default_samples(p.mu, p.beta, p.sigma, xd) - 80 * math.pi * math.sqrt(p.mu)) / 2
    assert td == pytest.approx(181_900, rel=0.01)


# ---------------------------------------------------------------- thresholds, either side


def _stats(peaks, tmin=-0.3, tmax=0.3, count=10, fmin=-1.0, fmax=0.0):
    s = np.zeros(kernel.NSTATS)
    s[: kernel.NSEG] = peaks
    s[kernel.NSEG], s[kernel.NSEG + 1], s[kernel.NSEG + 2] = tmin, tmax, count
    s[kernel.NSEG + 3], s[kernel.NSEG + 4] = 1.0, 91.0
    s[kernel.NSEG + 8], s[kernel.NSEG + 9] = fmin, fmax
    return s


def _name(stats, sa=1.0, growth=1.25, settle=1e-3, rest=-1):
    return OUTCOMES[kernel.classify(1000, 1000, rest, stats, sa, growth, settle, True, 1.0)[0]]


def test_rule_defaults_are_the_documented_ones():
    for fn in (simulate, stability_map):
        ps = inspect.signature(fn).parameters
        assert (ps["stable_amplitude"].default, ps["growth"].default, ps["settle"].default, ps["bound"].default) == (
            1.0,
            1.25,
            1e-3,
            None,  # None: dfa.analysis.simulation.divergence_bound, max(1e6, 100(A0 + 1)) (eq. 18-19)
        )
    assert OUTCOMES == ("rest", "oscillating", "unstable", "chatter", "undecided", "left", "saturated", "end_stop")
    codes = (kernel.REST, kernel.OSCILLATING, kernel.UNSTABLE, kernel.CHATTER, kernel.UNDECIDED, kernel.LEFT)
    assert codes + (kernel.SATURATED,) == (0, 1, 2, 3, 4, 5, 6)


def test_growth_threshold_either_side():
    eps = 1e-9
    assert _name(_stats([1, 1, 1, 1, 10, 11, 12, 12.5 * (1 + eps)])) == "unstable"
    assert _name(_stats([1, 1, 1, 1, 10, 11, 12, 12.5])) == "undecided"  # not above growth × P4: still changing
    # the 1-tick floor: a tiny envelope that grows is not called unstable
    assert _name(_stats([0, 0, 0, 0, 0.5, 0.6, 0.7, 1.0 + eps])) == "unstable"
    assert _name(_stats([0, 0, 0, 0, 0.5, 0.6, 0.7, 1.0])) == "undecided"
    # a dip in the last four eighths is not growth
    assert _name(_stats([1, 1, 1, 1, 10, 9.9, 12, 13])) == "undecided"


def test_growth_threshold_either_side_on_a_real_run():
    """A slowly growing linear run (β < ½, eq. 7 loop): its own envelope ratio P7/P4 sits on the threshold."""
    base = dict(mu=100.0, beta=0.45, sigma=0.0, xi_dot0=1.0, samples=30000, quantize=False, bound=1e300, record=False)
    r = simulate(**base)
    ratio = r.envelope[7] / r.envelope[4]
    assert ratio > 2.0 and r.outcome == "unstable"
    assert simulate(**base, growth=ratio * (1 - 1e-9)).outcome == "unstable"
    assert simulate(**base, growth=ratio * (1 + 1e-9)).outcome == "undecided"


def test_stable_amplitude_threshold_either_side():
    steady = [5, 5, 5, 5, 5, 5, 5, 5]
    assert _name(_stats(steady, -0.5, 1.5)) == "oscillating"  # amplitude (half the peak-to-peak) exactly 1 tick
    assert _name(_stats(steady, -0.5, math.nextafter(1.5, 0.0))) == "chatter"
    # on a real run: its own amplitude is the boundary
    r = simulate(2.0, 0.4, 0.1, 2.0, 20000, record=False)
    assert r.outcome == "oscillating"
    assert simulate(2.0, 0.4, 0.1, 2.0, 20000, record=False, stable_amplitude=r.amplitude).outcome == "oscillating"
    assert (
        simulate(
            2.0, 0.4, 0.1, 2.0, 20000, record=False, stable_amplitude=math.nextafter(r.amplitude, math.inf)
        ).outcome
        == "chatter"
    )


def test_settle_threshold_either_side():
    top = 10.0
    assert _name(_stats([9, 9, 9, 9, 9, top, top - 1e-2, top])) == "chatter"  # spread = settle × max
    assert _name(_stats([9, 9, 9, 9, 9, top, top - 1e-2 * (1 + 1e-6), top])) == "undecided"
    assert _name(_stats([5] * 8, count=1)) == "undecided"  # less than one full cycle in the tail
    assert _name(_stats([5] * 8), rest=7) == "rest"


def test_undecided_suggests_a_longer_run():
    r = simulate(100.0, 0.5, 0.0, 10.0, 50_000, record=False)  # β = ½, σ = 0: marginal, decays very slowly
    assert r.outcome == "undecided" and r.suggested_samples >= 4 * 50_000


# ---------------------------------------------------------------- force step


@settings(max_examples=40, deadline=None)
@given(st.floats(1.0, 200.0), st.floats(0.0, 1.2), st.floats(0.0, 0.6), st.floats(0.1, 3.0), st.booleans())
@example(100.0, 0.3, 0.3, 1.0, True)
def test_force_step_is_the_range_of_levels_read_in_the_tail(mu, beta, sigma, v0, quantize):
    """force_peak_to_peak = max − min of ⌊ξ⌋ (eq. 5 levels) over the tail's sample instants, recomputed from the trajectory."""
    n = 6000
    r = simulate(mu, beta, sigma, v0, n, quantize=quantize)
    if r.outcome in ("rest", "unstable"):
        return
    tail = r.xi[n + 1 - _tail_length(n, mu) :]
    levels = np.floor(tail) if quantize else tail
    assert r.force_peak_to_peak == levels.max() - levels.min()


def test_cli_simulate_catalogue_device_chatter_text_and_json(capsys):
    """Impulse Engine at K = 255 N/m (σ = 0.2997 < ½), 0.02 m/s: chatter; one force step KΔ = 255 N/m × 314 µm."""
    argv = ["simulate", "--device", "impulse", "--stiffness", "255", "--velocity", "0.02"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    kd = 255.0 * 314e-6
    assert "chatter: never comes to rest" in out
    assert f"force peak-to-peak  1 KΔ = {kd:.4g} N" in out
    assert main(argv + ["--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["outcome"] == "chatter" and d["force_peak_to_peak"] == 1.0 and d["force_unit"] == "N"
    assert d["force_peak_to_peak_si"] == written(kd)  # JSON's 12 digits: two rounded values agree to 1e-11
    assert d["frequency_hz"] == pytest.approx(d["frequency"] / (2 * math.pi * 0.002), rel=1e-11)
    assert f"{d['frequency_hz']:.4g} Hz" in out
    assert 30.0 <= d["frequency_hz"] <= 250.0  # the audible buzz of the issue


def test_rotary_device_force_step_in_newton_metres():
    dev = dfa.Device(6.28e-6, 9e-5, 0.02, 2 * math.pi / 8192, 1e-3, "RE35", rotary=True)
    r = simulate(100.0, 0.3, 0.3, 1.0, record=False)
    ph = r.physical(dev, 0.5)
    assert ph["force_unit"] == "N·m" and ph["force_peak_to_peak_si"] == pytest.approx(0.5 * 2 * math.pi / 8192)
    assert ph["frequency_hz"] == pytest.approx(r.frequency / (2 * math.pi * 1e-3))


def test_report_sentence_names_the_buzz_in_newtons_and_hertz():
    from types import SimpleNamespace

    from dfa.studies.design_document import outcome_text

    dev = dfa.get_device("impulse").device
    p = dev.params(255.0)
    r = simulate(p.mu, p.beta, p.sigma, dev.xi_dot(0.02), record=False)
    text = outcome_text(SimpleNamespace(outcome=r, device=dev, stiffness=255.0, velocity=0.02))
    hz = r.frequency / (2 * math.pi * dev.period)
    assert "chatter" in text and "never comes to rest" in text
    assert f"{255.0 * 314e-6:.4g} N" in text and f"{hz:.4g} Hz" in text


# ---------------------------------------------------------------- maps: codes and figure


def _all_classes_map():
    beta = np.linspace(0.0, 1.0, 10)
    sigma = np.linspace(0.0, 2.0, 10)
    out = np.tile((np.arange(10) // 2).astype(np.int8), (10, 1))[None]  # column bands 0..4
    nan = np.full(out.shape, np.nan)
    return StabilityMap(
        mu=100.0, xi_dots=(0.0,), beta=beta, sigma=sigma, outcome=out, amplitude=nan, frequency=nan, samples=1000
    )


def test_fig4_map_codes_round_trip_with_their_names(tmp_path):
    m = _all_classes_map()
    back = load_map(m.save(tmp_path / "all.npz"))
    assert np.array_equal(back.outcome, m.outcome)
    assert back.counts() == [{name: 20 for name in OUTCOMES[:5]}]  # "left" (a one-sided wall's) only where present
    with np.load(tmp_path / "all.npz") as z:
        assert [str(v) for v in z["outcome_names"]] == list(OUTCOMES)
        fields = {k: z[k] for k in z.files}
    # a file whose names are in another order is mapped back by name
    perm = [2, 0, 4, 1, 3]
    fields["outcome_names"] = np.array([OUTCOMES[i] for i in perm])
    fields["outcome"] = np.array([perm.index(c) for c in m.outcome.ravel()], dtype=np.int8).reshape(m.outcome.shape)
    np.savez(tmp_path / "perm.npz", **fields)
    assert np.array_equal(load_map(tmp_path / "perm.npz").outcome, m.outcome)
    # a file from before these classes ('stable' mixed rest with chatter) is refused, not misread
    del fields["outcome_names"]
    np.savez(tmp_path / "old.npz", **fields)
    with pytest.raises(dfa.DFAValueError, match="older dfa"):
        load_map(tmp_path / "old.npz")


def test_fig4_plot_colours_and_legend_per_class():
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.colors import to_rgb

    from dfa.render import figures

    m = _all_classes_map()
    axes = figures.stability_map_plot(m)
    ax = axes[0]
    fig = ax.figure
    fig.canvas.draw()
    img = np.asarray(fig.canvas.buffer_rgba())[..., :3] / 255.0
    from matplotlib.patches import Patch

    (legend,) = fig.legends  # the panels' legend is the figure's
    leg = {
        t.get_text().split(" ")[0]: to_rgb(h.get_facecolor())
        for t, h in zip(legend.get_texts(), legend.legend_handles, strict=False)
        if isinstance(h, Patch)
    }
    assert set(OUTCOMES[:5]) <= set(leg)  # a map of a bilateral wall has no "left": its legend names the five
    colours = {}
    for code, name in enumerate(OUTCOMES[:5]):
        x, y = ax.transData.transform((m.beta[2 * code], m.sigma[1]))
        px = img[int(round(img.shape[0] - y)), int(round(x))]
        assert px == pytest.approx(np.array(leg[name]), abs=2 / 255), name
        colours[name] = px
    lum = {k: float(np.mean(v)) for k, v in colours.items()}
    assert lum["rest"] == pytest.approx(1.0)  # white
    assert 0.5 < lum["oscillating"] < lum["chatter"] < 1.0  # two light shades, chatter the lighter
    assert lum["unstable"] < 0.25  # dark
    und = colours["undecided"]
    assert np.ptp(und) > 0.3  # a colour, not a grey: visible against all others


def test_cli_map_text_counts_every_class(capsys, tmp_path):
    out_file = tmp_path / "m.npz"
    argv = [
        "map",
        "--mu",
        "100",
        "--xi-dot",
        "1",
        "--beta-range",
        "0.6",
        "1",
        "--sigma-range",
        "0",
        "0.4",
        "--grid",
        "3",
        "--samples",
        "20000",
        "--jobs",
        "1",
        "--out",
        str(out_file),
        "--quiet",
    ]
    assert main(argv) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].split() == ["ξ'0", "rest", "chatter", "oscillating", "unstable", "undecided"]
    counts = load_map(out_file).counts()[0]
    assert lines[3].split() == [
        "1",
        *(str(counts[k]) for k in ("rest", "chatter", "oscillating", "unstable", "undecided")),
    ]
    assert counts["rest"] == 0 and counts["chatter"] >= 6  # region b: never at rest


@pytest.mark.parametrize("delay", [0, 1, 2])
def test_gil_linear_loop_outcome_flips_at_the_exact_linear_bound(delay):
    """Without quantization the outcome is scale-free: from a tiny impact the linear loop is
    'unstable' just above the exact linear bound (dfa.analysis.linear) and 'rest' (decaying) just below it."""
    from dfa.analysis.linear import critical_stiffness
    from dfa.model.device import Device

    dev = Device(0.01, 5.0, 0.0, 1e-5, 0.01)  # bT/m = 5: the z = -1 condition binds at d = 0
    k = critical_stiffness(dev.mass, dev.damping, dev.period, wall=Wall.of(1.0, delay=delay))
    out = {}
    for f in (0.98, 1.02):
        p = dev.params(k * f)
        out[f] = simulate(
            p.mu, p.beta, 0.0, 1e-3, 4000, quantize=False, record=False, wall=WallParams.of(delay=delay)
        ).outcome
    assert out == {0.98: "rest", 1.02: "unstable"}


@pytest.mark.parametrize(
    "args", [(3e7, 0.5, 0.5, 0.002, 5000), (1e10, 0.8, 0.8, 0.5, 50_000), (1e6, 0.6, 0.6, 0.3, 3000)]
)
def test_eq6_passive_short_runs_are_never_called_unstable(args):
    """Red-team finding: a run shorter than a few periods 2π√μ was called 'unstable' by the envelope rule while
    |ξ| was only rising from the impact; these points are proven passive (eq. 6), so the answer is 'undecided'."""
    mu, beta, sigma, v, n = args
    assert dfa.passivity_criterion(beta, sigma, v).passive
    r = simulate(mu, beta, sigma, v, n, record=False)
    assert r.outcome == "undecided" and r.suggested_samples > n


def test_eq7_linear_loop_decayed_to_denormals_is_rest_not_chatter():
    """Red-team finding: a stable linear loop that decayed into denormal numbers was called 'chatter'."""
    from dfa.analysis.linear import linear_stable

    assert linear_stable(1.0, 0.5)
    r = simulate(1.0, 0.5, 0.0, 2.0, 200_000, quantize=False, record=False)
    assert r.outcome == "rest"
