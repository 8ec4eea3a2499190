//! `host-sim experiment` and `host-sim calibrate` on the command line: bad rows named by
//! file, line and column; too few rows refused with the minimum; the JSON's shape;
//! `--conservative`'s directions; and the round trip experiment → calibrate → a finger
//! TOML the scene format reads.

mod common;

use host_sim::sim::effects::EffectSettings;
use host_sim::sim::scene::Scene;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn host_sim(args: &[&str]) -> (i32, String, String) {
    common::host_sim(args)
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-calibrate-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `experiment all` into `d` with these finger flags and 2 % noise.
fn experiment(d: &Path, finger: &[&str]) {
    let mut args = vec![
        "experiment",
        "all",
        "--noise",
        "0.02",
        "--seed",
        "3",
        "--out",
        s(d),
    ];
    args.extend_from_slice(finger);
    let (code, _, err) = host_sim(&args);
    assert_eq!(code, 0, "{err}");
    for f in ["indentation.csv", "slip.csv", "indentation.svg", "slip.svg"] {
        assert!(d.join(f).is_file(), "{f}");
    }
}

fn calibrate(d: &Path, extra: &[&str]) -> (i32, String, String) {
    let (ind, slip) = (d.join("indentation.csv"), d.join("slip.csv"));
    let mut args = vec!["calibrate", "--indentation", s(&ind), "--slip", s(&slip)];
    args.extend_from_slice(extra);
    host_sim(&args)
}

#[test]
fn a_bad_row_is_named_by_file_line_and_column() {
    let d = dir("bad-row");
    experiment(&d, &[]);
    let slip = d.join("slip.csv");
    let mut text = std::fs::read_to_string(&slip).unwrap();
    text.push_str("2.0,abc,0\n");
    let line = text.lines().count();
    std::fs::write(&slip, text).unwrap();
    let (code, _, err) = calibrate(&d, &[]);
    assert_eq!(code, 2, "{err}");
    let want = format!("{}:{line}:2: \"abc\" is not a number", slip.display());
    assert!(err.contains(&want), "{err}\nwant {want}");
    // A wrong header names the expected one.
    std::fs::write(&slip, "normal_force_n,tangential_force_n\n1,0.5\n").unwrap();
    let (code, _, err) = calibrate(&d, &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("normal_force_n,tangential_force_n,torsional_moment_nm"),
        "{err}"
    );
}

#[test]
fn too_few_rows_are_refused_with_the_minimum() {
    let d = dir("too-few");
    experiment(&d, &[]);
    let ind = d.join("indentation.csv");
    std::fs::write(&ind, "normal_force_n,half_width_m\n1,0.0025\n2,0.0035\n").unwrap();
    let (code, _, err) = calibrate(&d, &[]);
    assert_eq!(code, 2);
    assert!(err.contains("indentation needs at least 3 rows"), "{err}");
    let slip = d.join("slip.csv");
    std::fs::write(
        &slip,
        "normal_force_n,tangential_force_n,torsional_moment_nm\n1,0.8,0\n2,1.6,0\n",
    )
    .unwrap();
    std::fs::write(
        &ind,
        "normal_force_n,half_width_m\n1,0.0025\n2,0.0035\n4,0.005\n",
    )
    .unwrap();
    let (code, _, err) = calibrate(&d, &[]);
    assert_eq!(code, 2);
    assert!(
        err.contains("slip needs at least 3 onsets with a tangential force"),
        "{err}"
    );
}

fn json(d: &Path, extra: &[&str]) -> Value {
    let mut args = vec!["--format", "json"];
    args.extend_from_slice(extra);
    let (code, out, err) = calibrate(d, &args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn json_has_every_parameter_with_value_interval_and_identification() {
    let d = dir("json");
    experiment(&d, &["--k", "3", "--gamma", "0.45"]);
    let v = json(&d, &[]);
    assert_eq!(v["shape"], "rect");
    for key in ["mu", "k", "c", "gamma"] {
        let p = &v[key];
        let (value, ci) = (p["value"].as_f64().unwrap(), p["ci95"].as_array().unwrap());
        let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
        assert!(lo <= value && value <= hi, "{key}: {p}");
        assert_eq!(p["identified"], true, "{key}");
        assert!(p.get("reason").is_none());
    }
    let skew = &v["skewed_pressure"];
    for key in ["delta_over_a", "alpha", "locus_over_a"] {
        assert!(skew[key]["value"].is_f64(), "{key}");
        assert_eq!(skew[key]["identified"], false, "{key}");
        assert!(
            skew[key]["reason"].as_str().unwrap().contains("kept at"),
            "{key}"
        );
    }
    assert_eq!(skew["delta_over_a"]["value"], 0.0);
    // No torsion data: k is held at 2 and says so.
    let slip = d.join("slip.csv");
    let text = std::fs::read_to_string(&slip).unwrap();
    let forces: String = text
        .lines()
        .filter(|l| l.ends_with(",0") || l.starts_with("normal"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&slip, forces).unwrap();
    let v = json(&d, &[]);
    assert_eq!(v["k"]["identified"], false);
    assert_eq!(v["k"]["value"], 2.0);
    assert!(v["k"]["reason"]
        .as_str()
        .unwrap()
        .contains("kept at 2 (conservative"));
    let (_, text_out, _) = calibrate(&d, &[]);
    assert!(
        text_out.contains("not identified: needs 2 onsets with a torsional moment"),
        "{text_out}"
    );
}

#[test]
fn conservative_moves_each_parameter_toward_less_capacity() {
    let d = dir("conservative");
    experiment(&d, &["--k", "3", "--gamma", "0.45"]);
    let (fit, cons) = (json(&d, &[]), json(&d, &["--conservative"]));
    assert_eq!(cons["conservative"], true);
    let val = |v: &Value, k: &str| v[k]["value"].as_f64().unwrap();
    let lower = |v: &Value, k: &str| v[k]["ci95"][0].as_f64().unwrap();
    // mu, k and gamma at their lower bounds, below the fit.
    for key in ["mu", "k", "gamma"] {
        assert_eq!(val(&cons, key), lower(&fit, key), "{key}");
        assert!(val(&cons, key) < val(&fit, key), "{key}");
    }
    // The contact law: a(N) below the fitted one at every indentation force.
    let a = |v: &Value, n: f64| val(v, "c") * n.powf(val(v, "gamma"));
    let text = std::fs::read_to_string(d.join("indentation.csv")).unwrap();
    // The rows after the header and the rig's record (`# shape = ...` lines).
    for line in text.lines().skip(1).filter(|l| !l.starts_with('#')) {
        let n: f64 = line.split(',').next().unwrap().parse().unwrap();
        assert!(a(&cons, n) < a(&fit, n), "N = {n}");
    }
    assert_eq!(cons["skewed_pressure"]["delta_over_a"]["value"], 0.0);
}

#[test]
fn the_safety_factor_mu_needs_is_mu_over_its_lower_bound() {
    let d = dir("safety-for-mu");
    experiment(&d, &[]);
    let (fit, cons) = (json(&d, &[]), json(&d, &["--conservative"]));
    let mu = fit["mu"]["value"].as_f64().unwrap();
    let lo = fit["mu"]["ci95"][0].as_f64().unwrap();
    let s = fit["safety_for_mu"].as_f64().unwrap();
    assert_eq!(s, mu / lo);
    // 2 % noise: an interval of a few per cent, so a factor just above 1.
    assert!(s > 1.0 && s < 1.1, "{s}");
    // The conservative finger's mu is the lower bound already: nothing left to cover.
    assert_eq!(cons["safety_for_mu"].as_f64(), Some(1.0));
    let (code, text, err) = calibrate(&d, &[]);
    assert_eq!(code, 0, "{err}");
    let line = format!("safety >= {:.3} covers mu's 95 % interval", s);
    assert!(text.contains(&line), "{line}\n{text}");
}

fn scene_with(finger_toml: &str) -> Scene {
    let text = format!("duration_s = 1.0\n{finger_toml}\n[object]\nmass_kg = 0.1\n");
    Scene::parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

#[test]
fn round_trip_experiment_calibrate_scene() {
    let d = dir("round-trip");
    experiment(
        &d,
        &[
            "--k",
            "3",
            "--mu",
            "0.7",
            "--c",
            "3e-3",
            "--gamma",
            "0.4",
            "--half-length",
            "0.012",
        ],
    );
    let toml = d.join("finger.toml");
    let (code, _, err) = calibrate(
        &d,
        &[
            "--half-length",
            "0.012",
            "--out",
            s(&toml),
            "--plot",
            s(&d.join("fit.svg")),
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(d.join("fit.svg"))
        .unwrap()
        .contains("<svg"));
    let scene = scene_with(&std::fs::read_to_string(&toml).unwrap());
    let f = &scene.finger;
    assert!((f.mu / 0.7 - 1.0).abs() < 0.03, "{f:?}");
    assert!(
        (f.c / 3e-3 - 1.0).abs() < 0.05 && (f.gamma - 0.4).abs() < 0.03,
        "{f:?}"
    );
    assert!(f.k > 1.0 && f.half_length_m == 0.012);
    assert!(scene.effect_settings.is_empty());
    // The file drives the experiments too.
    let (code, _, err) = host_sim(&[
        "experiment",
        "slip",
        "--finger",
        s(&toml),
        "--out",
        s(&d.join("again")),
    ]);
    assert_eq!(code, 0, "{err}");
}

#[test]
fn round_trip_of_an_identified_skew() {
    let d = dir("skew");
    // A strong skew (k = 1.25, Δ/a = 0.9), noiseless: the fit identifies it.
    let args = [
        "experiment",
        "all",
        "--k",
        "1.25",
        "--skew",
        "0.9",
        "--repeats",
        "1",
        "--ratios",
        "0.0005,0.001,0.0025,0.006",
        "--out",
        s(&d),
    ];
    let (code, _, err) = host_sim(&args);
    assert_eq!(code, 0, "{err}");
    let toml = d.join("finger.toml");
    let (code, out, err) = calibrate(&d, &["--out", s(&toml)]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&toml).unwrap();
    assert!(text.contains("[effect.skewed_pressure]"), "{out}\n{text}");
    let scene = scene_with(&text);
    let Some(EffectSettings::SkewedPressure(sp)) = scene.effect_settings.first() else {
        panic!("{:?}", scene.effect_settings);
    };
    assert!((sp.delta_over_a - 0.9).abs() < 0.05, "{sp:?}");
    assert_eq!(sp.alpha, 1.1);
}
