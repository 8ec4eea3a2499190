"""The MuJoCo rig end to end: the grasp's fingertip in the lab protocols, the CSVs,
softgrip.calibrate on them, and the grasp on the calibrated finger.

Tolerances, and why:
- the onsets lie on MuJoCo's elliptic cone within 1e-4 (the cone is what MuJoCo is
  configured to do; the onset is read at the step the contact reaches it);
- the calibrated mu, and the finger's torsional limit mu·a·pitch at gamma = 0, within
  0.5 % of MuJoCo's mu and mu_t (the onsets are on the cone far closer than that: the
  rest is room for the fit);
- each pure onset's N_slip/N on the calibrated finger within 0.5 % of 1; each combined
  one in [1, 1.075]: the finger never predicts a later slip than MuJoCo's, and earlier
  by no more than the distance of softgrip's disc surfaces inside MuJoCo's ellipse when
  their axes match (at most 6.6 %, for uniform pressure: checked below with softgrip.fls).
"""

import importlib.util
import json
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import softgrip

mujoco = pytest.importorskip("mujoco")

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def load(name):
    spec = importlib.util.spec_from_file_location(name, EXAMPLES / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod  # dataclasses look their module up
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def rig():
    return load("mujoco_rig")


@pytest.fixture(scope="module")
def pipeline(rig, tmp_path_factory):
    """rig → CSVs → calibrate → grasp, through the example's command line."""
    out = tmp_path_factory.mktemp("mujoco_lab")
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert rig.main(["all", "--out", str(out), "--calibrate", "--grasp", "--json"]) == 0
    return out, json.loads(buf.getvalue())


def test_the_rig_writes_host_sims_lab_files(pipeline, host_sim, tmp_path):
    out, report = pipeline
    subprocess.run(
        [host_sim, "experiment", "all", "--shape", "disc", "--out", tmp_path],
        check=True, capture_output=True,
    )
    for name in ("indentation.csv", "slip.csv"):
        assert (out / name).read_text().splitlines()[0] == (
            (tmp_path / name).read_text().splitlines()[0]
        )
    slip = (out / "slip.csv").read_text().splitlines()[1:]
    # 6 forces × (1 force + 1 torsion + 3 combined ramps); none ran out of ramp.
    assert len(slip) == 6 * 5
    assert (out / "finger.toml").exists()


def test_onsets_lie_on_mujocos_cone(rig, pipeline):
    out, _ = pipeline
    mu, mu_t = rig.grasp.FINGER["mu"], rig.Rig().mu_t
    rows = np.array(rig.read_slip(out / "slip.csv"))
    n, ft, mn = rows.T
    radius = np.hypot(ft / (mu * n), mn / (mu_t * n))
    assert np.all(np.abs(radius - 1.0) < 1e-4), radius
    # The combined ramps' onsets are near their ramp's ratio (the contact's wrench turns a
    # little along the cone within the step the onset is read at).
    mixed = rows[(ft > 0) & (mn > 0)]
    ratios = mixed[:, 2] / mixed[:, 1]
    for r in rig.RATIOS:
        near = ratios[np.abs(ratios / r - 1.0) < 0.1]
        assert len(near) == 6, (r, ratios)


def test_calibrated_friction_is_mujocos(rig, pipeline):
    _, report = pipeline
    cal = report["calibration"]
    assert abs(cal["mu"]["fitted"] / cal["mu"]["mujoco"] - 1.0) < 5e-3, cal["mu"]
    mt = cal["torsional_friction_m"]
    assert abs(mt["fitted"] / mt["mujoco"] - 1.0) < 5e-3, mt
    assert cal["gamma"] == 0.0  # held: the indentation is at one force


def test_calibrated_finger_predicts_the_onsets(rig, pipeline):
    _, report = pipeline
    pred = report["calibration"]["onsets_n_slip_over_n"]
    for kind in ("force", "torsion"):
        assert pred[kind]["count"] == 6
        assert 0.995 < pred[kind]["min"] <= pred[kind]["max"] < 1.005, (kind, pred[kind])
    assert pred["mixed"]["count"] == 18
    assert 1.0 <= pred["mixed"]["min"] <= pred["mixed"]["max"] <= 1.075, pred["mixed"]
    # The bound: every disc surface of softgrip lies inside the ellipse with its axes,
    # by at most 6.6 % (uniform pressure; 5.1 % at k = 1).
    for k in (1.0, 2.0, float("inf")):
        s = softgrip.fls(shape="disc", k=k, samples=256)
        radius = np.hypot(s["f"], s["m"] / s["pitch"])
        assert 0.93 < radius.min() and radius.max() <= 1.0 + 1e-9, (k, radius.min())
        assert 1.0 / radius.min() <= 1.075


def test_the_grasp_holds_on_the_calibrated_finger(pipeline):
    _, report = pipeline
    g = report["grasp"]
    assert g["least_holding_constant_n"] is not None
    for name in ("calibrated", "example"):
        run = g["runs"][name]
        assert run["held"], (name, run)
        assert run["over_least"] > 1.0, (name, run)  # the constant was chosen knowing the scene


def test_the_rigs_margins_bring_the_grasp_within_1_10_of_the_least_constant(rig, tmp_path):
    """Calibrated with the rig's own hold and cyclic rows, the finger carries MuJoCo's
    margins (no ratchet, no turn: cyclic and disc torsion factors 1), and the grasp at
    softgrip's defaults holds with at most 1.10 x the least constant grip that holds."""
    import contextlib
    import io

    buf = io.StringIO()
    args = ["all", "--margins", "--out", str(tmp_path), "--calibrate", "--grasp", "--json"]
    with contextlib.redirect_stdout(buf):
        assert rig.main(args) == 0
    finger = softgrip.load_finger(tmp_path / "finger.toml")
    assert finger["cyclic_factor"] == 1.0 and finger["disc_torsion_factor"] == 1.0, finger
    run = json.loads(buf.getvalue())["grasp"]["runs"]["calibrated"]
    assert run["held"], run
    assert 1.0 < run["over_least"] <= 1.10, run


def test_the_overlap_is_not_the_contact_friction_sees(rig, tmp_path):
    """With the overlap at every force the fit takes gamma ≈ 1/2 from MuJoCo's soft
    constraint, and the finger mispredicts the torsion onsets by tens of per cent: why the
    rig presses at one force."""
    r = rig.Rig()
    rows = rig.experiment(r, "all", indentation_forces=rig.FORCES)
    rig.write_csvs(rows, tmp_path)
    fit = rig.calibrate(tmp_path)
    assert 0.45 < fit["gamma"]["value"] <= 0.5
    pred = [p["over"] for p in rig.predicted_onsets(fit["controller"], rows["slip"])
            if p["kind"] == "torsion"]
    assert min(pred) < 0.7 and max(pred) > 1.5, pred


def test_grasp_reads_the_calibrated_finger(pipeline, capsys):
    out, _ = pipeline
    grasp = load("mujoco_grasp")
    assert grasp.main(["--finger", str(out / "finger.toml"), "--json", "--duration", "0.5"]) == 0
    got = json.loads(capsys.readouterr().out)
    want = softgrip.load_finger(out / "finger.toml")
    assert got["softgrip_finger"]["c_m_per_n_gamma"] == want["c_m_per_n_gamma"]
    # An infinite k (uniform pressure) is JSON's null.
    assert got["softgrip_finger"]["k"] == (None if want["k"] == float("inf") else want["k"])
    assert got["finger"] == grasp.FINGER  # the scene keeps its own


def test_mujocos_contact_neither_creeps_nor_ratchets(rig):
    """The margin protocols below the onset: a sustained load held 1.5 s, and 10 load
    cycles at 4 Hz, at half and nine tenths of each axis's onset (4 N). In torsion the
    plate does not turn at all (1e-9 rad is rounding); along the force it moves by the
    residue of MuJoCo's noslip solve, under 1 µm a cycle and 5 µm/s held, and no cycle
    moves it more than the first two (no ratchet)."""
    r = rig.Rig()
    fractions = (0.5, 0.9)
    for row in rig.hold(r, fractions=fractions):
        axis, _, fraction, _, _, time_s, slide, turn, slide_rate, turn_rate = row
        if time_s == 0.0:
            continue  # the onset
        assert time_s == pytest.approx(rig.HOLD_RAMP_S + rig.HOLD_S), row  # held throughout
        assert turn < 1e-9 and turn_rate < 1e-9, row
        assert slide < 1e-5 and slide_rate < 5e-6, row
    cycles = {}
    for row in rig.cyclic(r, fractions=fractions):
        axis, _, fraction, cycle, _, _, slide, turn = row
        if cycle == 0:
            continue
        assert turn < 1e-9, row
        assert slide < 1e-6, row
        cycles.setdefault((axis, fraction), []).append(slide)
    for key, slides in cycles.items():
        assert len(slides) == rig.CYCLES, key
        assert max(slides[2:]) <= max(slides[:2]) + 1e-7, (key, slides)
