//! The closed vocabularies of `--controller` and `--link` (issue 25): one enum each,
//! shared by `simulate` and `bench`; unknown names are refused with clap's list of the
//! possible values; `pty` and its alias `inprocess` are the same link.

use clap::ValueEnum;
use host_sim::args::LinkName;
use host_sim::sim::controllers::{ControllerChoice, ControllerKind};
use std::path::{Path, PathBuf};
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_host-sim");

fn run(args: &[&str]) -> (Option<i32>, String) {
    let o = Command::new(BIN).args(args).output().unwrap();
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("softgrip-vocab-{}-{name}", std::process::id()))
}

fn scene() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/lift_hold.toml")
        .to_str()
        .unwrap()
        .to_string()
}

/// The names are today's strings, clap parses each to its controller, and `is_softgrip`
/// is true for softgrip's three modes only.
#[test]
fn controller_names_parse_back_to_their_kind() {
    let names: Vec<&str> = ControllerKind::NAMES.map(ControllerKind::name).to_vec();
    assert_eq!(
        names,
        [
            "softgrip",
            "softgrip-ellipse",
            "softgrip-table",
            "constant",
            "coulomb",
            "box",
            "fixed-torsion",
            "slip-servo"
        ]
    );
    for k in ControllerKind::NAMES {
        assert_eq!(ControllerKind::from_str(k.name(), false), Ok(k));
        assert_eq!(
            ControllerChoice::from_str(k.name(), false),
            Ok(ControllerChoice::One(k))
        );
        assert_eq!(k.is_softgrip(), k.name().starts_with("softgrip"), "{k:?}");
    }
    assert_eq!(
        ControllerChoice::from_str("all", false),
        Ok(ControllerChoice::All)
    );
    assert_eq!(
        ControllerChoice::kinds(&[ControllerChoice::All]),
        ControllerKind::ALL
    );
    assert_eq!(LinkName::from_str("inprocess", false), Ok(LinkName::Pty));
    assert_eq!(LinkName::from_str("pty", false), Ok(LinkName::Pty));
}

/// An unknown controller or link is a usage error listing the possible values, in both
/// commands.
#[test]
fn unknown_names_are_refused_with_the_possible_values() {
    let s = scene();
    for (args, listed) in [
        (
            vec!["simulate", s.as_str(), "--controller", "pid"],
            "slip-servo",
        ),
        (vec!["bench", "--controller", "pid"], "slip-servo"),
        (
            vec!["simulate", s.as_str(), "--link", "carrier-pigeon"],
            "pty",
        ),
        (vec!["bench", "--link", "carrier-pigeon"], "pty"),
    ] {
        let (code, err) = run(&args);
        assert_eq!(code, Some(2), "{args:?}: {err}");
        assert!(
            err.contains("possible values") && err.contains(listed),
            "{args:?}: {err}"
        );
    }
}

/// bench runs softgrip on the direct link (and the pty as a check): the firmware's links
/// are refused, naming the flag.
#[test]
fn bench_refuses_the_firmware_links() {
    for link in ["qemu", "serial"] {
        let (code, err) = run(&["bench", "--link", link, "--trials", "1"]);
        assert_eq!(code, Some(2), "{err}");
        assert!(err.contains(&format!("--link {link}")), "{err}");
    }
}

/// `--link pty` and `--link inprocess` run the same link in simulate.
#[test]
fn simulate_takes_pty_and_inprocess() {
    let s = scene();
    let mut series = Vec::new();
    for link in ["pty", "inprocess"] {
        let out = tmp(&format!("sim-{link}"));
        let (code, err) = run(&[
            "simulate",
            &s,
            "--link",
            link,
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, Some(0), "{link}: {err}");
        series.push(std::fs::read(out.join("timeseries_lift_hold_softgrip.csv")).unwrap());
        let _ = std::fs::remove_dir_all(&out);
    }
    assert_eq!(series[0], series[1]);
}

/// `--link pty` and `--link inprocess` run the same check in bench, and bench.json names
/// the link `pty` either way (in its `key`, since the pooled-seed bench).
#[test]
fn bench_takes_pty_and_inprocess() {
    for link in ["pty", "inprocess"] {
        let out = tmp(&format!("bench-{link}"));
        let (code, err) = run(&[
            "bench",
            "--link",
            link,
            "--family",
            "twist",
            "--controller",
            "softgrip",
            "--trials",
            "1",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, Some(0), "{link}: {err}");
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap())
                .unwrap();
        assert_eq!(json["key"]["link"], "pty", "{link}");
        let _ = std::fs::remove_dir_all(&out);
    }
}
