"""A hand on the device (paper Table 2's human operator; issue 28 §2): mass and damping added to the device's.

Checks: a hand of zero mass and damping reproduces the bare device; a hand's mass and damping give the results
of a device with m + m_h and b + b_h, through every command (the JSON numbers users read); β = (b + b_h)/(K T)
from Table 1 by hand; a hand stiffness goes to the wall (dfa.hold), never left out; the grip sweep against closed forms (eq. 11
solved for b), the exact linear bound at its answer, and exact simulation at the criterion's answer (a proof
must not diverge); the report states the grasp and its grip table.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from fixed_keywords import small_design_searches, small_report_map

import dfa
from dfa.analysis.limits.grip import GripSweep, grip_sweep
from dfa.analysis.limits.kmax import linear_limit
from dfa.analysis.simulation import divergence_bound, simulate
from dfa.cli import main
from dfa.formatting import number
from dfa.model.hand import HAND_PRESETS, Hand, HandNotCovered, get_hand
from dfa.render.hand import at_least

IMPULSE = dfa.get_device("impulse").device


def _json(capsys, *argv: str) -> dict:
    code = main([*argv, "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(out)


def _refused(capsys, *argv: str) -> str:
    code = main(list(argv))
    out, err = capsys.readouterr()
    assert code == 2, (argv, out, err)
    assert err.count("\n") == 1 and "Traceback" not in err, err
    return err


def _without_hand(d: object) -> object:
    """The JSON with the hand's own keys (``hand``, a label naming it) removed, for comparing numbers."""
    if isinstance(d, dict):
        return {k: _without_hand(v) for k, v in d.items() if k != "hand"}
    if isinstance(d, list):
        return [_without_hand(v) for v in d]
    return d


COMMANDS = [
    ("check", "--velocity", "0.1"),
    ("simulate", "--velocity", "0.1", "--samples", "4000"),
    ("limit-cycles",),
    ("stiffness", "--velocity", "0.05"),
    ("zwidth", "--velocity", "0.05", "--grid", "3", "--speeds", "1"),
]


@pytest.mark.parametrize("cmd", COMMANDS, ids=[c[0] for c in COMMANDS])
def test_table2_hand_mass_damping_is_the_heavier_device(capsys, cmd):
    """--hand-mass/--hand-damping give every number of --mass m + m_h --damping b + b_h (issue 28 §2, tests)."""
    m_h, b_h = 0.1, 0.07
    held = _json(capsys, *cmd, "--device", "impulse", "--hand-mass", str(m_h), "--hand-damping", str(b_h))
    heavy = _json(
        capsys, *cmd, "--device", "impulse", "--mass", repr(IMPULSE.mass + m_h), "--damping",
        repr(IMPULSE.damping + b_h), "--name", IMPULSE.name,
    )  # fmt: skip
    assert held["hand"] == {"name": "hand", "source": "", "mass": m_h, "damping": b_h, "stiffness": 0.0}
    assert "hand" not in heavy
    assert _without_hand(held) == _without_hand(heavy)


@pytest.mark.parametrize("cmd", COMMANDS[:3], ids=[c[0] for c in COMMANDS[:3]])
def test_table2_hand_of_nothing_is_the_bare_device(capsys, cmd):
    """A hand of zero mass, damping and stiffness reproduces the bare device exactly (issue 28 §2, tests)."""
    nothing = _json(capsys, *cmd, "--device", "impulse", "--hand-mass", "0", "--hand-damping", "0")
    none = _json(capsys, *cmd, "--device", "impulse", "--hand", "none")  # the preset: no hand at all
    bare = _json(capsys, *cmd, "--device", "impulse")
    assert nothing["hand"]["mass"] == 0.0 and "hand" not in bare and none == bare
    assert _without_hand(nothing) == bare
    assert IMPULSE.holding(get_hand("none")).params(80.0) == IMPULSE.params(80.0)


def test_table2_hand_paper_preset_beta_by_table1(capsys):
    """The paper's human operator (Table 2: 0.150 kg, 4.8 N·s/m) adds to the device: β = (b + b_h)/(K T) (Table 1)."""
    h = HAND_PRESETS["paper"]
    assert (h.mass, h.damping, h.stiffness) == (0.150, 4.8, 0.0) and "Table 2" in h.source
    d = _json(capsys, "check", "--device", "impulse", "--hand", "paper", "--velocity", "0.1")
    k, t = 80.0, 2e-3
    assert d["beta"] == pytest.approx((0.02 + 4.8) / (k * t), rel=1e-12)
    assert d["mu"] == pytest.approx((0.032 + 0.150) / (k * t * t), rel=1e-12)
    assert d["hand"]["name"] == h.name
    code = main(["check", "--device", "impulse", "--hand", "paper", "--velocity", "0.1"])
    out = capsys.readouterr().out
    assert code == 0 and out.splitlines()[0].endswith("held by human operator (paper Table 2): 0.15 kg, 4.8 N·s/m")


def test_table2_hand_light_preset_is_the_paper_mass_without_damping(capsys):
    """`--hand light`: Table 2's hand mass with no damping (a bound, said in its source): μ grows with the mass,
    β is the bare device's, and the criterion's verdict is the bare device's at that μ (β and σ unchanged)."""
    h = HAND_PRESETS["light"]
    assert (h.mass, h.damping, h.stiffness) == (HAND_PRESETS["paper"].mass, 0.0, 0.0) and "bound" in h.source
    d = _json(capsys, "check", "--device", "impulse", "--hand", "light", "--velocity", "0.1")
    bare = _json(capsys, "check", "--device", "impulse", "--velocity", "0.1")
    k, t = 80.0, 2e-3
    assert d["beta"] == bare["beta"] and d["sigma"] == bare["sigma"] and d["passive"] == bare["passive"]
    assert d["mu"] == pytest.approx((0.032 + 0.150) / (k * t * t), rel=1e-12) and d["hand"]["name"] == h.name


def test_table2_hand_stiffness_goes_to_the_wall_not_left_out(capsys):
    """holding() alone refuses a hand stiffness (it would be left out) and names dfa.hold; the CLI puts it in the
    wall (dfa.HandSpring), so the check's JSON states κ_h = k_h/K."""
    with pytest.raises(HandNotCovered, match="hand_stiffness = 135.*dfa.hold"):
        IMPULSE.holding(Hand(0.554, 6.45, 135.0))
    d = _json(capsys, "check", "--device", "impulse", "--velocity", "0.1", "--hand-stiffness", "135")
    k = dfa.get_device("impulse").stiffness
    assert d["wall"]["hand_stiffness"] == 135.0 and d["wall"]["units"]["hand_stiffness"] == "N/m"
    assert d["wall"]["dimensionless"]["hand_stiffness"] == pytest.approx(135.0 / k, rel=1e-15)


@pytest.mark.parametrize(
    "argv, words",
    [
        (("--device", "impulse", "--hand", "firm"), ("--hand 'firm'", "none, paper")),
        (("--device", "impulse", "--hand-mass", "-0.1"), ("--hand-mass -0.1", ">= 0")),
        (("--device", "impulse", "--hand-damping", "nan"), ("--hand-damping",)),
        (("--mu", "100", "--beta", "0.1", "--sigma", "1", "--hand", "paper"), ("--hand", "dimensionless")),
        (("--device", "impulse", "--rotary", "--hand", "paper"), ("rotary", "--hand-mass")),
        (
            (
                "--hand",
                "paper",
            ),
            ("no device given",),
        ),
    ],
)
def test_table2_hand_bad_flags_one_line(capsys, argv, words):
    """Bad hand flags: one line on stderr naming the flag, exit code 2."""
    err = _refused(capsys, "check", "--xi-dot", "1", *argv)
    for w in words:
        assert w in err, err


def test_table2_hand_api_rules():
    """Hand values are checked by name; a device holds one hand at most; bare() undoes holding()."""
    with pytest.raises(dfa.DFAValueError, match="hand_mass"):
        Hand(-1.0)
    with pytest.raises(dfa.DFAValueError, match="not a hand preset"):
        get_hand("firm")
    held = IMPULSE.holding(get_hand("paper"))
    with pytest.raises(dfa.DFAValueError, match="already holds"):
        held.holding(Hand(0.1))
    assert held.bare.mass == pytest.approx(IMPULSE.mass, rel=1e-14) and held.bare.hand is None
    assert held.to_dict()["hand"]["damping"] == 4.8 and "hand" not in IMPULSE.to_dict()
    with pytest.raises(TypeError):  # a hand is set by holding() only: mass and damping then include it
        dfa.Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000, hand=get_hand("paper"))  # type: ignore[call-arg]


def test_table2_hand_params_json_and_labels(capsys):
    """`dfa params` states the hand in its JSON and names the groups of the moving mass and damping."""
    d = _json(capsys, "params", "--device", "impulse", "--hand", "paper")
    assert d["hand"]["mass"] == 0.15 and d["beta"] == pytest.approx(4.82 / (80.0 * 2e-3), rel=1e-12)
    assert main(["params", "--device", "impulse", "--hand", "paper"]) == 0
    out = capsys.readouterr().out
    assert "μ = (m + m_h)/(K T²)" in out and "β = (b + b_h)/(K T)" in out


def test_table2_hand_mass_slip_warned(capsys):
    """A hand of 150 kg (grams written as kg) gets the plausibility warning naming --hand-mass."""
    assert main(["check", "--device", "impulse", "--xi-dot", "1", "--hand-mass", "150"]) == 0
    err = capsys.readouterr().err
    assert "--hand-mass" in err and "150" in err


def _eq11_hand_damping(dev: dfa.Device, k: float, v: float) -> float:
    """Eq. 11 solved for b: K = 2(b|ẋ0| + c)/(T|ẋ0| + Δ) ⇒ b = (K(T v + Δ)/2 − c)/v; less the device's own."""
    return (0.5 * k * (dev.period * v + dev.resolution) - dev.coulomb) / v - dev.damping


@pytest.mark.parametrize("name, v", [("phantom", 0.1), ("phantom", 0.3), ("toolhandle", 0.2)])
def test_table2_grip_criterion_is_eq11_solved_for_b(name, v):
    """The grip sweep's criterion answer equals eq. 11 solved for the damping (σ >= ½ at these K)."""
    e = dfa.get_device(name)
    g = grip_sweep(e.device, e.stiffness, v, hand_mass=0.15, simulate_scan=False)
    crit = g.need("criterion")
    expect = _eq11_hand_damping(e.device, e.stiffness, v)
    assert expect > 0 and crit.status.value == "at_least"
    assert crit.hand_damping == pytest.approx(expect, rel=1e-6)


def test_table2_grip_linear_answer_is_the_linear_limit():
    """At the linear answer's hand damping the target K is the exact linear bound's limit."""
    e = dfa.get_device("phantom")
    g = grip_sweep(e.device, e.stiffness, 0.1, hand_mass=0.15, simulate_scan=False)
    b_h = g.need("linear").hand_damping
    assert b_h is not None and b_h > 0
    held = e.device.holding(Hand(0.15, b_h))
    assert linear_limit(held, dfa.Wall(e.stiffness)) == pytest.approx(e.stiffness, rel=1e-6)
    lighter = e.device.holding(Hand(0.15, 0.98 * b_h))
    assert linear_limit(lighter, dfa.Wall(e.stiffness)) < e.stiffness


@pytest.mark.parametrize("name, v, delay", [("phantom", 0.1, 0), ("phantom", 0.05, 1), ("toolhandle", 0.2, 0)])
def test_table2_grip_criterion_answer_does_not_diverge(name, v, delay):
    """A grip the criterion proves passive does not diverge in exact simulation (impacts up to V, two starts)."""
    e = dfa.get_device(name)
    wall = dfa.Wall.of(e.stiffness, delay=delay)
    g = grip_sweep(e.device, wall, v, hand_mass=0.15, simulate_scan=False)
    b_h = g.need("criterion").hand_damping
    assert b_h is not None
    p = e.device.holding(Hand(0.15, b_h)).params(e.stiffness)
    wp = wall.params(e.device.period)
    for frac in (0.25, 0.5, 1.0):
        xd = frac * e.device.xi_dot(v)
        for xi0 in (0.0, 0.5):
            r = simulate(p.mu, p.beta, p.sigma, xd, 200_000, xi0=xi0, record=False,
                         bound=divergence_bound(xi0, xd, p.mu), wall=wp)  # fmt: skip
            assert r.outcome.value != "unstable", (frac, xi0, r.outcome)


def test_table2_grip_scan_and_json():
    """The simulated scan: b_h = 0 and K T 2^i, and the least grip from which none diverges; JSON carries it all."""
    e = dfa.get_device("phantom")
    g = grip_sweep(e.device, e.stiffness, 0.1)
    kt = e.stiffness * e.device.period
    assert g.scan_damping[0] == 0.0 and g.scan_damping[1] == pytest.approx(kt / 64)
    i = g.scan_damping.index(g.simulated_damping)
    assert all(o != "unstable" for o in g.scan_outcome[i:])
    assert i == 0 or g.scan_outcome[i - 1] == "unstable"
    d = g.to_dict()
    json.dumps(d, allow_nan=False)
    assert [n["method"] for n in d["needs"]] == ["criterion", "linear"] and d["units"]["hand_mass"] == "kg"
    with pytest.raises(dfa.DFAValueError, match="already holds"):
        grip_sweep(e.device.holding(Hand(0.1)), e.stiffness, 0.1)
    assert isinstance(g, GripSweep) and math.isfinite(g.hand_mass)


def test_table2_hand_report_states_grasp_and_grip(tmp_path: Path, capsys, monkeypatch):
    """`dfa report --hand paper` writes a separate _held report stating the grasp and the grip table's numbers."""
    small_report_map(monkeypatch)  # the grasp and the grip table read neither the stability map nor K_max's search
    small_design_searches(monkeypatch)
    code = main(["report", "--device", "phantom", "--hand", "paper", "--velocity", "0.1", "--out", str(tmp_path),
                 "--format", "md", "--quiet"])  # fmt: skip
    written = capsys.readouterr()
    assert code == 0, written.err
    md = (tmp_path / "design_report_phantom-1-0_held.md").read_text(encoding="utf-8")
    assert md.startswith("# Design report: Phantom 1.0, held by human operator (paper Table 2)")
    assert "| grasp | human operator (paper Table 2): 0.15 kg, 4.8 N·s/m" in md
    e = dfa.get_device("phantom")
    g = grip_sweep(e.device, e.stiffness, 0.1, hand_mass=0.15)
    for n in g.needs:
        printed = at_least(n.hand_damping)
        assert f"| {printed} N·s/m |" in md and float(printed) >= n.hand_damping
    crit = at_least(g.need("criterion").hand_damping)  # the least value as printed: the criterion holds there
    d = _json(
        capsys, "check", "--device", "phantom", "--velocity", "0.1", "--hand-mass", "0.15", "--hand-damping", crit
    )
    assert d["passive"] is True
    meta = json.loads((tmp_path / "design_report_phantom-1-0_held.json").read_text(encoding="utf-8"))
    assert meta["identity"]["device"]["hand"]["mass"] == 0.15
    assert not (tmp_path / "design_report_phantom-1-0.md").exists()


def test_table2_hand_require_labels_the_total_damping(capsys):
    """Found by review: `dfa require` with a hand labelled the total damping b + b_h as the device's b; the row
    now says it is the device's and the hand's, and its value is their sum."""
    assert main(["require", "--device", "delta", "--hand", "paper", "--stiffness", "20000", "--velocity", "0.1"]) == 0
    out = capsys.readouterr().out
    row = next(line for line in out.splitlines() if line.startswith("damping b + b_h (device and hand)"))
    assert f"{number(0.01 + 4.8, 4)} N·s/m" in row


def test_table2_grip_prose_says_the_hand_mass_and_the_scanned_grips_in_words_with_units():
    """The report read "for a hand of mass m_h = 0 kg" and "13 grips (0 and K T·2^i)": no hand mass is a hand that
    adds none, and the scan is named by its range in N·s/m."""
    from dfa.render.hand import grip_rows, grip_text

    e = dfa.get_device("delta")
    g = grip_sweep(e.device, e.stiffness, 0.1)
    text, scan = grip_text(g), grip_rows(g)[-1][2]
    assert "m_h = 0" not in text and "adds damping but no mass" in text
    lo, hi = sorted(b for b in g.scan_damping if b > 0)[:: len(g.scan_damping) - 2]
    assert "2^i" not in scan and "K T" not in scan
    assert f"with no grip and with 12 grips from {number(lo, 4)} to {number(hi, 4)} N·s/m" in scan
    held = grip_text(grip_sweep(e.device, e.stiffness, 0.1, hand_mass=0.15, simulate_scan=False))
    assert "a hand that adds 0.15 kg to the moving mass" in held
