"""The bindings against the Rust CLI's JSON for the same inputs, to 1e-12."""

import json
import subprocess

import numpy as np
import pytest

import softgrip

TOL = 1e-12


def close(a, b):
    a, b = float(a), float(b)
    return abs(a - b) <= TOL * max(1.0, abs(b))


def cli(exe, *args):
    out = subprocess.run([str(exe), *map(str, args)], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


FLS_CASES = [
    dict(),
    dict(shape="disc"),
    dict(shape="rect", k=4.0, aspect=2.6, samples=32),
    dict(shape="rect", aspect=0.5, skew=0.9, alpha=1.1, samples=48),
    dict(shape="disc", skew=0.5, alpha=2.0, locus=0.1, samples=16),
    dict(shape="rect", k=float("inf"), aspect=1.0, samples=16),
]


def fls_args(case):
    args = ["fls", "--format", "json"]
    for key, flag in (("shape", "--shape"), ("k", "--k"), ("aspect", "--aspect"),
                      ("skew", "--skew"), ("alpha", "--alpha"), ("locus", "--locus"),
                      ("samples", "--samples")):
        if key in case:
            v = case[key]
            args += [flag, "inf" if v == float("inf") else v]
    return args


@pytest.mark.parametrize("case", FLS_CASES, ids=lambda c: ",".join(f"{k}={v}" for k, v in c.items()) or "default")
def test_fls_matches_cli(host_sim, case):
    ref = cli(host_sim, *fls_args(case))
    got = softgrip.fls(**case)
    assert close(got["pitch"], ref["pitch"])
    assert got["star_shaped"] == ref["star_shaped"]
    for key in ("f_semi_axis", "m_semi_axis", "rms_residual", "max_radial_gap",
                "max_relative_gap", "max_outside"):
        assert close(got["ellipse"][key], ref["ellipse"][key]), key
    for key in ("d", "f", "m"):
        assert close(got["ellipse"]["max_gap_at"][key], ref["ellipse"]["max_gap_at"][key])
    for key in ("f_semi_axis", "m_over_pitch_semi_axis", "force_over_exact_max_pct",
                "force_over_exact_mean_pct"):
        assert close(got["inscribed"][key], ref["inscribed"][key]), key
    assert isinstance(got["d"], np.ndarray)
    assert len(got["d"]) == len(ref["samples"])
    for key in ("d", "f", "m"):
        want = np.array([s[key] for s in ref["samples"]])
        np.testing.assert_allclose(got[key], want, rtol=TOL, atol=TOL)


def test_fls_at_points_match_cli(host_sim):
    ref = cli(host_sim, "fls", "--format", "json", "--at", "0,0.3,1,4.5")
    got = softgrip.fls(at=[0, 0.3, 1, 4.5])
    for key in ("d", "f", "m"):
        np.testing.assert_allclose(got[key], [s[key] for s in ref["samples"]], rtol=TOL, atol=TOL)


RF_CASES = [
    dict(mu=0.8, c_m_per_n_gamma=2.5e-3, gamma=0.5),
    dict(mu=0.8, c_m_per_n_gamma=2.5e-3, gamma=0.5, mode="table"),
    dict(mu=0.5, c_m_per_n_gamma=3e-3, gamma=1 / 3, shape="disc", safety=1.5),
    dict(mu=1.2, c_m_per_n_gamma=2e-3, gamma=0.0, half_length_m=0.02, k=4.0),
    dict(mu=0.8, c_m_per_n_gamma=2.5e-3, gamma=0.5, mode="table", skew=0.9),
    dict(mu=0.8, c_m_per_n_gamma=2.5e-3, gamma=0.5, n_min_n=0.5, n_max_n=10.0),
]
LOADS = [(1.0, 0.004), (0.0, 0.0), (0.05, 0.0), (0.0, 0.01), (3.0, 0.02), (-2.0, -0.001),
         (12.0, 0.1)]

# Python's keyword -> host-sim required-force's flag.
RF_FLAGS = dict(mu="--mu", c_m_per_n_gamma="--c", gamma="--gamma", shape="--shape",
                half_length_m="--length", k="--k", safety="--safety", mode="--mode",
                skew="--skew", n_min_n="--n-min", n_max_n="--n-max")


@pytest.mark.parametrize("case", RF_CASES, ids=lambda c: ",".join(f"{k}={v:.4g}" if isinstance(v, float) else f"{k}={v}" for k, v in c.items()))
def test_required_force_matches_cli(host_sim, case):
    ft = np.array([l[0] for l in LOADS])
    mn = np.array([l[1] for l in LOADS])
    got = softgrip.required_force(ft, mn, **case)
    assert got["normal_force"].shape == ft.shape
    for i, (f, m) in enumerate(LOADS):
        args = ["required-force", "--format", "json", "--ft", f, "--mn", m]
        for key, v in case.items():
            args += [RF_FLAGS[key], v]
        ref = cli(host_sim, *args)
        for key in ("normal_force", "n_slip", "a", "utilisation", "command"):
            assert close(got[key][i], ref[key]), (key, f, m)
        assert got["status"][i] == ref["status"]
        assert got["mode"] == ref["mode"]
        assert all(close(x, y) for x, y in zip(got["ellipse_axes"], ref["ellipse_axes"]))


def test_required_force_broadcasts():
    r = softgrip.required_force(np.array([[1.0], [2.0]]), np.array([0.0, 0.004, 0.008]))
    assert r["normal_force"].shape == (2, 3)
    # More load, more force.
    assert np.all(np.diff(r["normal_force"], axis=0) > 0)
    assert np.all(np.diff(r["normal_force"], axis=1) > 0)
    scalar = softgrip.required_force(1.0, 0.004)
    assert scalar["normal_force"].shape == ()
    assert close(scalar["normal_force"], r["normal_force"][0, 1])
