//! A calibrated finger file (`host-sim calibrate --out`) is read unchanged by
//! `required-force`, `simulate` and `tables` (`--finger`), as by `experiment` and the
//! Python package: each answers as with the same finger given another way.

use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_host-sim");

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-finger-file-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

fn run(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(BIN).args(args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// A finger file as calibrate writes it, from an fls experiment with known parameters.
fn calibrated() -> PathBuf {
    let lab = tmp("lab");
    let lab_s = lab.to_str().unwrap();
    let (code, _, err) = run(&[
        "experiment",
        "all",
        "--k",
        "3",
        "--mu",
        "0.7",
        "--c",
        "2e-3",
        "--gamma",
        "0.4",
        "--noise",
        "0.01",
        "--seed",
        "3",
        "--out",
        lab_s,
    ]);
    assert_eq!(code, 0, "{err}");
    let out = tmp("finger.toml");
    let (code, _, err) = run(&[
        "calibrate",
        "--indentation",
        lab.join("indentation.csv").to_str().unwrap(),
        "--slip",
        lab.join("slip.csv").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    out
}

fn finger_value(file: &Path, key: &str) -> String {
    let doc: toml::Table = toml::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    let v = &doc["finger"][key];
    v.as_float()
        .map_or_else(|| v.to_string(), |x| format!("{x:?}"))
}

#[test]
fn required_force_reads_the_file_as_the_flags() {
    let f = calibrated();
    let fs = f.to_str().unwrap();
    let load = [
        "--ft", "1.2", "--mn", "0.005", "--mode", "table", "--format", "json",
    ];
    let (code, by_file, err) = run(&[&["required-force", "--finger", fs][..], &load].concat());
    assert_eq!(code, 0, "{err}");
    let flags: Vec<String> = ["mu", "c", "gamma", "k"]
        .iter()
        .flat_map(|k| [format!("--{k}"), finger_value(&f, k)])
        .chain(["--length".into(), finger_value(&f, "half_length_m")])
        .collect();
    let flags: Vec<&str> = flags.iter().map(String::as_str).collect();
    let (code, by_flags, err) = run(&[&["required-force"][..], &flags, &load].concat());
    assert_eq!(code, 0, "{err}");
    assert_eq!(by_file, by_flags);
    // The file and the flags it stands for do not mix.
    let (code, _, err) = run(&[
        &["required-force", "--finger", fs, "--mu", "0.5"][..],
        &load,
    ]
    .concat());
    assert_eq!(code, 2);
    assert!(err.contains("--finger") && err.contains("--mu"), "{err}");
}

#[test]
fn simulate_and_tables_read_the_file() {
    let f = calibrated();
    let fs = f.to_str().unwrap();
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lift_hold.toml");
    let out = tmp("sim");
    let (code, _, err) = run(&[
        "simulate",
        scene.to_str().unwrap(),
        "--finger",
        fs,
        "--link",
        "direct",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let base = tmp("sim-base");
    let (code, _, err) = run(&[
        "simulate",
        scene.to_str().unwrap(),
        "--link",
        "direct",
        "--quiet",
        "--out",
        base.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let mean = |d: &Path| {
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(d.join("summary.json")).unwrap())
                .unwrap();
        v["runs"][0]["mean_normal_force_n"].as_f64().unwrap()
    };
    // μ 0.7 instead of the scene's 0.8, and another contact: another grip.
    assert!(
        mean(&out) > mean(&base),
        "{} vs {}",
        mean(&out),
        mean(&base)
    );

    let (code, _, err) = run(&[
        "tables",
        "--finger",
        fs,
        "--format",
        "csv",
        "--out",
        tmp("tables").to_str().unwrap(),
        "--quiet",
    ]);
    assert_eq!(code, 0, "{err}");

    // A bad finger file is refused before anything runs, naming the flag and the key.
    let bad = tmp("bad.toml");
    std::fs::write(&bad, "[finger]\nmu = -1\nc = 2e-3\ngamma = 0.4\n").unwrap();
    let (code, _, err) = run(&[
        "simulate",
        scene.to_str().unwrap(),
        "--finger",
        bad.to_str().unwrap(),
        "--out",
        tmp("sim-bad").to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--finger") && err.contains("finger.mu"),
        "{err}"
    );
}

#[test]
fn bench_runs_every_trial_on_the_file_s_finger() {
    let f = calibrated();
    let out = tmp("bench");
    let (code, _, err) = run(&[
        "bench",
        "--finger",
        f.to_str().unwrap(),
        "--family",
        "lift-hold",
        "--trials",
        "2",
        "--controller",
        "softgrip",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let csv = std::fs::read_to_string(out.join("trials-lift-hold.csv")).unwrap();
    let mu: f64 = finger_value(&f, "mu").parse().unwrap();
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert!(!rows.is_empty());
    for row in rows {
        let true_mu: f64 = row.split(',').nth(2).unwrap().parse().unwrap();
        assert_eq!(true_mu, mu, "{row}");
    }
    // The brush finger is a plant of its own, not a bench finger.
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/brush_lift_hold.toml");
    let (code, _, err) = run(&[
        "bench",
        "--finger",
        scene.to_str().unwrap(),
        "--trials",
        "1",
        "--quiet",
        "--out",
        tmp("bench-brush").to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("model = \"fls\""), "{err}");
}
