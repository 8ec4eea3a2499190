"""softgrip.calibrate and softgrip.load_finger: the same fit as host-sim calibrate, on lab
files host-sim experiment writes, and a calibrated finger that Controller runs."""

import csv
import json
import math
import subprocess
import warnings

import pytest

import softgrip


@pytest.fixture(scope="module")
def lab(host_sim, tmp_path_factory):
    out = tmp_path_factory.mktemp("lab")
    subprocess.run(
        [host_sim, "experiment", "all", "--plant", "fls", "--k", "3", "--mu", "0.7",
         "--noise", "0.02", "--seed", "5", "--out", out],
        check=True, capture_output=True,
    )
    return out


def test_calibrate_equals_the_cli(host_sim, lab, tmp_path):
    toml_path = tmp_path / "finger.toml"
    cli = subprocess.run(
        [host_sim, "calibrate", "--indentation", lab / "indentation.csv", "--slip",
         lab / "slip.csv", "--format", "json", "--out", toml_path],
        check=True, capture_output=True, text=True,
    )
    want = json.loads(cli.stdout)
    got = softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv")
    for key in want:
        assert got[key] == want[key], key
    # The recovered finger is close to the one the data came from.
    assert got["mu"]["ci95"][0] <= 0.7 <= got["mu"]["ci95"][1]
    # The TOML the CLI writes reads back as the same Controller keywords.
    assert softgrip.load_finger(toml_path) == got["controller"]
    c = softgrip.Controller(**got["controller"], mode="table")
    assert c.config["mu"] == got["mu"]["value"]
    assert c.config["c_m_per_n_gamma"] == got["c"]["value"]


def test_conservative_lowers_mu(lab):
    fit = softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv")
    low = softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv", conservative=True)
    assert low["mu"]["value"] == fit["mu"]["ci95"][0] < fit["mu"]["value"]
    assert low["conservative"] is True
    # The safety factor mu's interval needs: none left once mu is at its lower bound.
    assert fit["safety_for_mu"] == fit["mu"]["value"] / fit["mu"]["ci95"][0] > 1.0
    assert low["safety_for_mu"] == 1.0


def test_friction_contact_equals_the_cli(host_sim, lab):
    cli = subprocess.run(
        [host_sim, "calibrate", "--indentation", lab / "indentation.csv", "--slip",
         lab / "slip.csv", "--format", "json", "--friction-contact"],
        check=True, capture_output=True, text=True,
    )
    want = json.loads(cli.stdout)
    got = softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv", friction_contact=True)
    for key in want:
        assert got[key] == want[key], key
    fit = softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv")
    # On data from the model the refit moves c (not the half-length), and the refitted
    # finger's pure-torsion limit matches the pure-torsion onsets on average.
    assert got["friction_contact"]["refit"] == "scale"
    assert got["friction_contact"]["joint_mu"] == fit["mu"]["value"]
    assert got["controller"]["c_m_per_n_gamma"] == got["c"]["value"]
    assert got["half_length_m"] == 0.01
    assert "friction_contact" not in fit
    with open(lab / "slip.csv") as f:
        rows = csv.DictReader(line for line in f if not line.startswith("#"))
        torsion = [r for r in rows if float(r["tangential_force_n"]) == 0.0]
    n = [float(r["normal_force_n"]) for r in torsion]
    m = [float(r["torsional_moment_nm"]) for r in torsion]
    kw = dict(got["controller"], safety=1.0, mode="table")
    n_slip = softgrip.required_force([0.0] * len(m), m, **kw)["n_slip"]
    mean_ln = sum(math.log(a / b) for a, b in zip(n_slip, n)) / len(n)
    assert abs(mean_ln) < 0.01, mean_ln


def test_friction_contact_is_not_conservative(lab):
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv", conservative=True,
                           friction_contact=True)
    assert e.value.param == "friction_contact"


def test_a_bad_row_names_the_file_line_and_column(lab, tmp_path):
    bad = tmp_path / "slip.csv"
    lines = (lab / "slip.csv").read_text().splitlines()
    lines[3] = "1.0,abc,0"
    bad.write_text("\n".join(lines) + "\n")
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.calibrate(lab / "indentation.csv", bad)
    assert e.value.param == "slip"
    assert f"{bad}:4:2" in str(e.value), str(e.value)


def test_too_few_rows_state_the_minimum(lab, tmp_path):
    few = tmp_path / "indentation.csv"
    few.write_text("normal_force_n,half_width_m\n1.0,0.0025\n")
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.calibrate(few, lab / "slip.csv")
    assert e.value.param == "indentation"
    assert "at least" in str(e.value)


def test_load_finger_reads_a_scene_with_the_believed_mu():
    import pathlib

    scene = pathlib.Path(__file__).resolve().parents[2] / "host-sim/scenes/brush_lift_hold.toml"
    f = softgrip.load_finger(scene)
    assert f["mu"] != 0.8  # the brush's true static μ is not what softgrip believes
    assert f["shape"] == "rect" and f["k"] == 1.0
    softgrip.Controller(**f)


def test_the_files_record_the_rig_and_a_contradicting_keyword_is_refused(lab, monkeypatch):
    text = (lab / "slip.csv").read_text()
    assert "# shape = rect\n# half_length_m = 0.01\n" in text
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv", shape="disc")
    assert e.value.param == "shape"
    assert "disc" in str(e.value) and "shape = rect" in str(e.value), str(e.value)
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv", half_length_m=0.02)
    assert e.value.param == "half_length_m"
    assert "0.02" in str(e.value) and "half_length_m = 0.01" in str(e.value), str(e.value)
    # Values that agree with the record are taken; the finger TOML's heading names the
    # files relative to the current directory, as they would be typed there.
    monkeypatch.chdir(lab)
    fit = softgrip.calibrate(lab / "indentation.csv", lab / "slip.csv", shape="rect",
                             half_length_m=0.01)
    assert fit["shape"] == "rect" and fit["half_length_m"] == 0.01
    heading = fit["finger_toml"].splitlines()[0]
    assert heading.startswith("# softgrip finger calibrated from indentation.csv and slip.csv:")


def test_a_hemisphere_calibrated_as_a_rectangle_warns(host_sim, tmp_path):
    # Rows of a hemisphere, without the lines that record its shape (an older lab's
    # files): calibrated with the default shape, a rectangle, the rows contradict the
    # fit; as a disc they do not (docs/calibration.md, "A fit the rows contradict").
    subprocess.run(
        [host_sim, "experiment", "all", "--shape", "disc", "--mu", "0.6", "--c", "3e-3",
         "--gamma", "0.33", "--noise", "0.02", "--seed", "2", "--out", tmp_path],
        check=True, capture_output=True,
    )
    for name in ("indentation.csv", "slip.csv"):
        lines = (tmp_path / name).read_text().splitlines(keepends=True)
        assert lines[1] == "# shape = disc\n"
        (tmp_path / f"old-{name}").write_text("".join(l for l in lines if l[0] != "#"))
    ind, slip = tmp_path / "old-indentation.csv", tmp_path / "old-slip.csv"
    with pytest.warns(softgrip.CalibrationWarning, match="hemisphere") as caught:
        rect = softgrip.calibrate(ind, slip)
    assert rect["shape"] == "rect" and rect["fit"]["lack_of_fit"]["contradicted"]
    assert [str(w.message) for w in caught] == rect["warnings"]
    assert "only the defaults" in rect["warnings"][0]
    assert rect["finger_toml"].splitlines()[1].startswith("# WARNING: the rows contradict")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        disc = softgrip.calibrate(ind, slip, shape="disc")
        recorded = softgrip.calibrate(tmp_path / "indentation.csv", tmp_path / "slip.csv")
    assert disc["warnings"] == [] and not disc["fit"]["lack_of_fit"]["contradicted"]
    assert recorded["shape"] == "disc" and recorded["mu"] == disc["mu"]
    assert disc["mu"]["ci95"][0] <= 0.6 <= disc["mu"]["ci95"][1]
