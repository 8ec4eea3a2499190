"""softgrip.calibrate with the margin protocols' files (cyclic=, hold=): the same margins
as host-sim calibrate --cyclic --hold, "not measured" without them, and a finger TOML whose
[margins] load_finger returns as Controller keywords."""

import json
import subprocess

import pytest

import softgrip


@pytest.fixture(scope="module")
def lab(host_sim, tmp_path_factory):
    out = tmp_path_factory.mktemp("margins")
    for kind in ["all", "cyclic", "hold"]:
        subprocess.run(
            [host_sim, "experiment", kind, "--shape", "disc", "--noise", "0.02",
             "--seed", "3", "--out", out],
            check=True, capture_output=True,
        )
    return out


def files(lab):
    return lab / "indentation.csv", lab / "slip.csv"


def test_margins_equal_the_cli(host_sim, lab, tmp_path):
    ind, slip = files(lab)
    toml_path = tmp_path / "finger.toml"
    cli = subprocess.run(
        [host_sim, "calibrate", "--shape", "disc", "--indentation", ind, "--slip", slip,
         "--cyclic", lab / "cyclic.csv", "--hold", lab / "hold.csv", "--format", "json",
         "--out", toml_path],
        check=True, capture_output=True, text=True,
    )
    want = json.loads(cli.stdout)
    got = softgrip.calibrate(ind, slip, shape="disc", cyclic=lab / "cyclic.csv",
                             hold=lab / "hold.csv")
    assert got["margins"] == want["margins"]
    # The fls plant neither ratchets nor creeps: every factor's interval holds 1.
    factor = got["margins"]["cyclic"]["cyclic_factor"]
    assert factor["ci95"][0] <= 1.0 <= factor["ci95"][1]
    assert got["finger_toml"] == toml_path.read_text()
    loaded = softgrip.load_finger(toml_path)
    assert loaded == got["controller"]
    assert loaded["cyclic_factor"] == factor["value"]
    assert loaded["disc_torsion_factor"] >= 1.0
    c = softgrip.Controller(**loaded, mode="table")
    assert c.config["cyclic_factor"] == factor["value"]


def test_without_the_files_the_margins_are_not_measured(lab):
    ind, slip = files(lab)
    got = softgrip.calibrate(ind, slip, shape="disc")
    for kind in ["cyclic", "hold"]:
        m = got["margins"][kind]
        assert m["measured"] is False
        assert m["reason"] == f"not measured: run `host-sim experiment {kind}`"
    assert "cyclic_factor" not in got["controller"]
    assert "# cyclic_factor: not measured" in got["finger_toml"]


def test_a_margins_key_that_is_not_one_is_refused(tmp_path):
    path = tmp_path / "finger.toml"
    path.write_text(
        '[finger]\nshape = "rect"\nmu = 0.8\nc = 2.5e-3\ngamma = 0.5\n\n[margins]\nsafety = 2.0\n'
    )
    with pytest.raises(softgrip.ConfigError, match="margins.safety: unknown key"):
        softgrip.load_finger(path)
