//! `bench reverify`: a small run's summary reverified on one of its seeds gains a
//! `provenance.reverified` entry and no other change; a tampered row is refused, named,
//! and the file left byte for byte; a seed that is not the run's, and dirty sources
//! without `--allow-dirty`, are refused.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn exe() -> &'static str {
    env!("CARGO_BIN_EXE_host-sim")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-reverify-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// The summary of a small run on seed 5 (one family, two trials, every
/// controller, the brush plant), made once for every test.
fn small_run() -> &'static Path {
    static RUN: OnceLock<PathBuf> = OnceLock::new();
    RUN.get_or_init(|| {
        let out = tmp("run");
        let o = Command::new(exe())
            .args(["bench", "--family", "lift-hold", "--trials", "2"])
            .args(["--seeds", "5", "--quiet", "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let o = Command::new(exe())
            .args(["bench", "summary"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        out.join("summary.json")
    })
}

/// A copy of the small run's summary, in a folder of its own: its path.
fn copy_of_run(name: &str) -> PathBuf {
    let dir = tmp(name);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("summary.json");
    std::fs::copy(small_run(), &path).unwrap();
    path
}

fn reverify(summary: &Path, seed: &str, extra: &[&str], dir: Option<&Path>) -> Output {
    let mut c = Command::new(exe());
    c.args(["bench", "reverify", "--quiet", "--seed", seed])
        .arg(summary)
        .args(extra);
    if let Some(d) = dir {
        c.current_dir(d);
    }
    c.output().unwrap()
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn refused(o: &Output) -> String {
    assert!(
        !o.status.success(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_reproduced_seed_appends_an_entry_and_changes_nothing_else() {
    let path = copy_of_run("pass");
    let before = std::fs::read_to_string(&path).unwrap();
    let o = reverify(&path, "5", &["--allow-dirty"], None);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let after = json(&path);
    let entries = after["provenance"]["reverified"].as_array().unwrap();
    assert_eq!(entries.len(), 1);
    let e = &entries[0];
    // One family: a default row per controller.
    assert_eq!(e["rows_compared"], 7);
    assert_eq!(e["seed"], 5);
    assert_eq!(
        e["constants_digest"].as_str(),
        Some(host_sim::provenance::CONSTANTS_DIGEST)
    );
    assert_eq!(
        e["configuration"],
        host_sim::bench::summary::configuration()
    );
    for field in ["commit", "dirty", "constants"] {
        assert!(e.get(field).is_some(), "{field}");
    }
    // Without the entry, the summary is the one before, line for line but provenance's.
    let mut stripped = after.clone();
    let p = stripped["provenance"].as_object_mut().unwrap();
    p.remove("reverified");
    assert_eq!(stripped, serde_json::from_str::<Value>(&before).unwrap());
    let text = std::fs::read_to_string(&path).unwrap();
    let changed: Vec<&str> = before
        .lines()
        .zip(text.lines())
        .filter(|(a, b)| a != b)
        .map(|(a, _)| a)
        .collect();
    assert_eq!(before.lines().count(), text.lines().count());
    assert!(
        changed.len() == 1 && changed[0].starts_with("\"provenance\":"),
        "{changed:?}"
    );
}

#[test]
fn a_tampered_row_a_foreign_seed_and_dirty_sources_are_refused_and_nothing_is_written() {
    let path = copy_of_run("refuse");
    let mut v = json(&path);
    let rows = v["per_seed_defaults"].as_array_mut().unwrap();
    let row = rows
        .iter_mut()
        .find(|r| r["family"] == "lift-hold" && r["controller"] == "coulomb")
        .unwrap();
    let was = row["mean_force_n"].as_f64().unwrap();
    let tampered = f64::from_bits(was.to_bits() + 1);
    row["mean_force_n"] = tampered.into();
    host_sim::bench::summary::write(&path, &v).unwrap();
    let bytes = std::fs::read(&path).unwrap();

    let why = refused(&reverify(&path, "5", &["--allow-dirty"], None));
    assert!(
        why.contains("lift-hold coulomb (seed 5): mean_force_n")
            && why.contains(&format!("published {tampered:?}, now {was:?}")),
        "{why}"
    );
    assert_eq!(std::fs::read(&path).unwrap(), bytes);

    let why = refused(&reverify(&path, "6", &["--allow-dirty"], None));
    assert!(
        why.contains("--seed 6: not one of the run's seeds (5)"),
        "{why}"
    );
    assert_eq!(std::fs::read(&path).unwrap(), bytes);

    // Outside any checkout the sources have no commit: dirty, refused without the flag.
    let outside = path.parent().unwrap();
    let why = refused(&reverify(&path, "5", &[], Some(outside)));
    assert!(why.contains("--allow-dirty"), "{why}");
    assert_eq!(std::fs::read(&path).unwrap(), bytes);
}
