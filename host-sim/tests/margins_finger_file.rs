//! A finger file's `[margins]` (what `host-sim calibrate --cyclic/--hold` writes) reaches
//! the controller of the commands that configure one from the file: `simulate --finger`
//! runs with its `cyclic_factor`, `required-force --finger` asks with its
//! `disc_torsion_factor`; a key that is not a margin, a value out of range and a key set
//! in both `[margins]` and `[controller]` are refused by name, in a finger file and in a
//! scene.

mod common;

use host_sim::sim::scene::Scene;
use std::path::{Path, PathBuf};

const FINGER: &str = "[finger]\nshape = \"rect\"\nmu = 0.8\nc = 2.5e-3\ngamma = 0.5\n\
                      half_length_m = 0.01\n";

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "softgrip-margins-file-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn file(d: &Path, name: &str, text: &str) -> String {
    let p = d.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_str().unwrap().to_string()
}

/// The greatest `load_factor` of `simulate shake.toml --finger finger`.
fn shake_load_factor(d: &Path, finger: &str) -> f64 {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/shake.toml");
    let out = d.join("sim");
    let args = [
        "simulate",
        scene,
        "--finger",
        finger,
        "--link",
        "direct",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ];
    let (code, _, err) = common::host_sim(&args);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(out.join("timeseries_shake_softgrip.csv")).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "load_factor").unwrap();
    lines
        .map(|l| l.split(',').nth(col).unwrap().parse::<f64>().unwrap())
        .fold(0.0, f64::max)
}

#[test]
fn simulate_runs_with_the_finger_files_cyclic_factor() {
    let d = dir("simulate");
    let plain = file(&d, "plain.toml", FINGER);
    let margins = file(
        &d,
        "margins.toml",
        &format!("{FINGER}\n[margins]\ncyclic_factor = 1.2\n"),
    );
    let default = softgrip::controller::ControllerConfig::default().cyclic_factor;
    assert_eq!(shake_load_factor(&d, &plain), default);
    assert_eq!(shake_load_factor(&d, &margins), 1.2);
}

fn required_force(finger: &str) -> f64 {
    let args = [
        "required-force",
        "--finger",
        finger,
        "--ft",
        "0",
        "--mn",
        "0.002",
        "--format",
        "json",
    ];
    let (code, out, err) = common::host_sim(&args);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    v["normal_force"].as_f64().unwrap()
}

#[test]
fn required_force_asks_with_the_finger_files_disc_torsion_factor() {
    let d = dir("required-force");
    let disc = FINGER.replace("\"rect\"", "\"disc\"");
    let plain = required_force(&file(&d, "plain.toml", &disc));
    let one = required_force(&file(
        &d,
        "one.toml",
        &format!("{disc}\n[margins]\ndisc_torsion_factor = 1.0\n"),
    ));
    assert!(one < plain, "{one} against {plain}");
}

#[test]
fn what_a_margins_table_may_not_say_is_refused_by_name() {
    let d = dir("refused");
    for (margins, controller, said) in [
        ("safety = 2.0", "", "margins.safety: unknown key"),
        (
            "cyclic_factor = 0.5",
            "",
            "margins.cyclic_factor: 0.5 is out of range",
        ),
        (
            "cyclic_factor = 1.2",
            "[controller]\ncyclic_factor = 1.3\n",
            "margins.cyclic_factor: set in [margins] and in [controller]",
        ),
    ] {
        let text = format!("{FINGER}{controller}\n[margins]\n{margins}\n");
        let f = file(&d, "bad.toml", &text);
        let (code, _, err) =
            common::host_sim(&["required-force", "--finger", &f, "--ft", "1", "--mn", "0"]);
        assert_eq!(code, 2, "{text}");
        assert!(err.contains(said), "{err}");
        let scene = format!("duration_s = 1.0\n{text}\n[object]\nmass_kg = 0.1\n");
        let e = Scene::parse(&scene).unwrap_err().to_string();
        assert!(e.contains(said) && e.starts_with("line "), "{e}");
    }
}
