//! The one way the host reads a controller configuration, from the command line: `--config
//! FILE` and the per-field flags generated from `ControllerConfig` (one per serialized
//! field, spelled by the rename table), the flags over the file; unknown or ill-typed keys
//! named by file and key or by flag; a scene's `[controller]` read the same way.

use host_sim::config::names::flag;
use softgrip::controller::ControllerConfig;
use std::path::PathBuf;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_host-sim");

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("softgrip-config-{}-{name}", std::process::id()))
}

/// Exit code, stdout and stderr of `host-sim ARGS`.
fn run(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(BIN).args(args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

const LOAD: [&str; 6] = ["required-force", "--ft", "1", "--mn", "0.004", "--format"];

#[test]
fn every_serialized_field_has_a_flag() {
    let table = toml::Table::try_from(ControllerConfig::default()).unwrap();
    for cmd in ["required-force", "tables", "simulate"] {
        let (code, help, _) = run(&[cmd, "--help"]);
        assert_eq!(code, 0);
        assert!(help.contains("--config <FILE>"), "{cmd}");
        for field in table.keys() {
            let f = format!("--{} <", flag(field));
            assert!(help.contains(&f), "{cmd}: no {f} for {field}");
        }
    }
}

#[test]
fn a_config_file_equals_the_flags_and_the_flags_win() {
    let file = tmp("rule.toml");
    std::fs::write(
        &file,
        "mu = 0.6\nc_m_per_n_gamma = 3e-3\nsafety = 1.7\nmode = \"table\"\n",
    )
    .unwrap();
    let by_flags = run(&[
        &LOAD[..],
        &["json", "--mu", "0.6", "--c", "3e-3", "--safety", "1.7"],
        &["--mode", "table"],
    ]
    .concat());
    let by_file = run(&[&LOAD[..], &["json", "--config", file.to_str().unwrap()]].concat());
    assert_eq!(by_flags.0, 0, "{}", by_flags.2);
    assert_eq!(by_flags.1, by_file.1);
    // A flag over the file: back to the default safety factor.
    let default_safety = ControllerConfig::DEFAULT.safety.to_string();
    let over = run(&[
        &LOAD[..],
        &[
            "json",
            "--config",
            file.to_str().unwrap(),
            "--safety",
            &default_safety,
        ],
    ]
    .concat());
    let plain = run(&[
        &LOAD[..],
        &["json", "--mu", "0.6", "--c", "3e-3"],
        &["--mode", "table"],
    ]
    .concat());
    let _ = std::fs::remove_file(&file);
    assert_eq!(over.1, plain.1);
    assert_ne!(over.1, by_file.1);
}

#[test]
fn unknown_and_ill_typed_keys_are_named() {
    let file = tmp("bad.toml");
    std::fs::write(&file, "mu = 0.6\nfriction = 0.5\n").unwrap();
    let (code, _, err) = run(&[&LOAD[..], &["json", "--config", file.to_str().unwrap()]].concat());
    assert_eq!(code, 2);
    assert!(
        err.contains("--config:") && err.contains("friction: unknown key"),
        "{err}"
    );
    std::fs::write(&file, "force_nodes = \"many\"\n").unwrap();
    let (code, _, err) = run(&[&LOAD[..], &["json", "--config", file.to_str().unwrap()]].concat());
    let _ = std::fs::remove_file(&file);
    assert_eq!(code, 2);
    assert!(err.contains("force_nodes:"), "{err}");
    let (code, _, err) = run(&[&LOAD[..], &["json", "--shape", "cone"]].concat());
    assert_eq!(code, 2);
    assert!(err.contains("--shape:") && err.contains("cone"), "{err}");
    // A value out of range is named by the flag the user typed (the rename table).
    let (code, _, err) = run(&[&LOAD[..], &["json", "--n-min", "-1"]].concat());
    assert_eq!(code, 2);
    assert!(err.contains("--n-min:"), "{err}");
}

#[test]
fn a_scene_controller_key_is_read_by_the_configuration() {
    let shipped = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/lift_hold.toml");
    let text = std::fs::read_to_string(shipped).unwrap();
    let scene = tmp("scene.toml");
    let bad = text.replace("[controller]\n", "[controller]\nfriction = 0.5\n");
    std::fs::write(&scene, &bad).unwrap();
    let (code, _, err) = run(&["simulate", scene.to_str().unwrap(), "--out", "/nonexistent"]);
    let line = bad.lines().position(|l| l.starts_with("friction")).unwrap() + 1;
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(&format!("line {line}: controller.friction: unknown key")),
        "{err}"
    );
    // Any field, here one the hand-written settings did not have: read, then checked.
    std::fs::write(
        &scene,
        text.replace("[controller]\n", "[controller]\nforce_nodes = 1\n"),
    )
    .unwrap();
    let (code, _, err) = run(&["simulate", scene.to_str().unwrap(), "--out", "/nonexistent"]);
    let _ = std::fs::remove_file(&scene);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("controller.force_nodes"), "{err}");
}
