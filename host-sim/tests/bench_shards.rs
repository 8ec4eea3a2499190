//! `bench --shard I/N`, `bench merge` and `bench select`: the merged shards write exactly
//! the files of the whole run, byte for byte, and so do the merged runs of some of its
//! seeds each, and of some of its controllers each; a merge refuses a missing unit, a
//! duplicate and shards of different runs, naming the problem; and `bench rejudge` gives
//! back a run's own bench.json from its rows.

use std::path::{Path, PathBuf};
use std::process::Command;

fn exe() -> &'static str {
    env!("CARGO_BIN_EXE_host-sim")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-shards-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

/// A small run: two families, two seeds, three trials, two controllers, on the limit
/// surface (cheap to draw).
const RUN: [&str; 12] = [
    "--family",
    "twist,mu-mismatch",
    "--trials",
    "3",
    "--seeds",
    "5,6",
    "--controller",
    "fixed-torsion,softgrip-table",
    "--plant",
    "fls",
    "--quiet",
    "--out",
];

fn bench(extra: &[&str], out: &Path) -> std::process::Output {
    bench_seeds(RUN[5], extra, out)
}

/// `bench` with the run's options but `seeds` for its seeds.
fn bench_seeds(seeds: &str, extra: &[&str], out: &Path) -> std::process::Output {
    bench_with(seeds, RUN[7], extra, out)
}

/// `bench` with the run's options but `seeds` and `controllers`.
fn bench_with(seeds: &str, controllers: &str, extra: &[&str], out: &Path) -> std::process::Output {
    let mut args: Vec<&str> = RUN.to_vec();
    args[5] = seeds;
    args[7] = controllers;
    let o = Command::new(exe())
        .arg("bench")
        .args(args)
        .arg(out)
        .args(extra)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn merge(out: &Path, shards: &[PathBuf]) -> std::process::Output {
    Command::new(exe())
        .args(["bench", "merge", "--out"])
        .arg(out)
        .args(shards)
        .output()
        .unwrap()
}

fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file())
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read(&p).unwrap())
        })
        .collect();
    v.sort();
    v
}

#[test]
fn merged_shards_equal_the_whole_run_byte_for_byte() {
    let whole = tmp("whole");
    bench(&[], &whole);
    let parts = tmp("parts");
    for i in 0..3 {
        bench(&["--shard", &format!("{i}/3")], &parts);
    }
    let shards: Vec<PathBuf> = (0..3)
        .map(|i| parts.join(format!("shard-{i}-of-3.json")))
        .collect();
    let merged = tmp("merged");
    let o = merge(&merged, &shards);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let a = files(&whole);
    let names: Vec<&str> = a.iter().map(|f| f.0.as_str()).collect();
    assert!(
        names.contains(&"bench.json") && names.contains(&"pareto-twist.png"),
        "{names:?}"
    );
    assert_same_files(&whole, &merged);
    // bench.json keeps the per-seed rows beside the pooled ones.
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(whole.join("bench.json")).unwrap()).unwrap();
    let pooled = json["rows"].as_array().unwrap();
    let per_seed = json["per_seed"].as_array().unwrap();
    assert_eq!(per_seed.len(), 2 * pooled.len());
    assert_eq!(pooled[0]["trials"], 6);
    assert_eq!(per_seed[0]["trials"], 3);
    assert_eq!(json["key"]["seeds"], serde_json::json!([5, 6]));

    // A missing shard, a shard given twice, and a shard of another run are refused.
    let o = merge(&tmp("m1"), &shards[..2]);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success() && e.contains("is in no shard"), "{e}");
    let twice = [
        shards[0].clone(),
        shards[1].clone(),
        shards[2].clone(),
        shards[2].clone(),
    ];
    let o = merge(&tmp("m2"), &twice);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        !o.status.success() && e.contains("more than one shard"),
        "{e}"
    );
    let other = tmp("other");
    bench(&["--shard", "2/3", "--hard"], &other);
    let mixed = [
        shards[0].clone(),
        shards[1].clone(),
        other.join("shard-2-of-3.json"),
    ];
    let o = merge(&tmp("m3"), &mixed);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success() && e.contains("different runs"), "{e}");
    assert!(e.contains("options hard"), "{e}");
    for d in [whole, parts, merged, other] {
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn runs_of_some_seeds_each_merge_into_the_run_over_all_of_them() {
    let whole = tmp("pool-whole");
    bench(&[], &whole);
    // Seed 5 as one run in two shards, seed 6 as another run in one.
    let (five, six) = (tmp("pool-5"), tmp("pool-6"));
    bench_seeds("5", &["--shard", "0/2"], &five);
    bench_seeds("5", &["--shard", "1/2"], &five);
    bench_seeds("6", &["--shard", "0/1"], &six);
    let shards = [
        five.join("shard-0-of-2.json"),
        five.join("shard-1-of-2.json"),
        six.join("shard-0-of-1.json"),
    ];
    let merged = tmp("pool-merged");
    let o = merge(&merged, &shards);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_same_files(&whole, &merged);
    // The seeds come in the order the files first name them: 6 then 5 is another run.
    let swapped = tmp("pool-swapped");
    let o = merge(
        &swapped,
        &[shards[2].clone(), shards[0].clone(), shards[1].clone()],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(swapped.join("bench.json")).unwrap()).unwrap();
    assert_eq!(json["key"]["seeds"], serde_json::json!([6, 5]));
    // A run missing one of its shards leaves its seed's units in no shard; a seed in two
    // runs puts its units in more than one; runs that differ in more than their seeds
    // are refused.
    let o = merge(&tmp("pool-m1"), &shards[1..]);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success() && e.contains("is in no shard"), "{e}");
    let both = tmp("pool-both");
    bench(&["--shard", "0/1"], &both);
    let o = merge(
        &tmp("pool-m2"),
        &[shards[2].clone(), both.join("shard-0-of-1.json")],
    );
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        !o.status.success() && e.contains("more than one shard"),
        "{e}"
    );
    let hard = tmp("pool-hard");
    bench_seeds("6", &["--shard", "0/1", "--hard"], &hard);
    let o = merge(
        &tmp("pool-m3"),
        &[
            shards[0].clone(),
            shards[1].clone(),
            hard.join("shard-0-of-1.json"),
        ],
    );
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success() && e.contains("options hard"), "{e}");
    assert!(!e.contains("seeds"), "{e}");
    for d in [whole, five, six, merged, swapped, both, hard] {
        let _ = std::fs::remove_dir_all(d);
    }
}

fn select(out: &Path, controllers: &str, shards: &[PathBuf]) -> std::process::Output {
    Command::new(exe())
        .args(["bench", "select", "--controller", controllers, "--out"])
        .arg(out)
        .args(shards)
        .output()
        .unwrap()
}

/// The files of the whole run and of the merge: the same names, each byte for byte.
fn assert_same_files(whole: &Path, merged: &Path) {
    let (a, b) = (files(whole), files(merged));
    assert_eq!(
        a.iter().map(|f| &f.0).collect::<Vec<_>>(),
        b.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(
            x == y,
            "{name} differs between the whole run and the merged runs"
        );
    }
}

#[test]
fn runs_of_some_controllers_each_merge_into_the_run_over_all_of_them() {
    let whole = tmp("ctl-whole");
    bench(&[], &whole);
    // An earlier run of both controllers, of which only fixed-torsion is kept, and a
    // rerun of softgrip-table alone, as two runs of one seed each.
    let (old, kept) = (tmp("ctl-old"), tmp("ctl-kept"));
    bench(&["--shard", "0/2"], &old);
    bench(&["--shard", "1/2"], &old);
    let old_shards = [old.join("shard-0-of-2.json"), old.join("shard-1-of-2.json")];
    let o = select(&kept, "fixed-torsion", &old_shards);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let kept_shards = [
        kept.join("shard-0-of-2.json"),
        kept.join("shard-1-of-2.json"),
    ];
    let (five, six) = (tmp("ctl-5"), tmp("ctl-6"));
    bench_with("5", "softgrip-table", &["--shard", "0/1"], &five);
    bench_with("6", "softgrip-table", &["--shard", "0/1"], &six);
    let reruns = [
        five.join("shard-0-of-1.json"),
        six.join("shard-0-of-1.json"),
    ];
    let all: Vec<PathBuf> = kept_shards.iter().chain(&reruns).cloned().collect();
    let merged = tmp("ctl-merged");
    let o = merge(&merged, &all);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_same_files(&whole, &merged);

    // softgrip-table from both the earlier run and the rerun is given twice; without
    // seed 6's rerun, its units lack softgrip-table's runs.
    let twice: Vec<PathBuf> = old_shards.iter().chain(&reruns).cloned().collect();
    let o = merge(&tmp("ctl-m1"), &twice);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        !o.status.success() && e.contains("more than one shard") && e.contains("softgrip-table"),
        "{e}"
    );
    let o = merge(&tmp("ctl-m2"), &all[..3]);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        !o.status.success() && e.contains("no shard with runs of softgrip-table"),
        "{e}"
    );
    // A trial whose own facts differ between files (as another build's would) is refused.
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&reruns[1]).unwrap()).unwrap();
    let oracle = &mut json["units"][0]["result"]["oracle_mean_n"];
    *oracle = serde_json::json!(oracle.as_f64().unwrap() * 1.001);
    let other = tmp("ctl-other");
    std::fs::create_dir_all(&other).unwrap();
    let tampered = other.join("shard-0-of-1.json");
    std::fs::write(&tampered, serde_json::to_string(&json).unwrap()).unwrap();
    let o = merge(
        &tmp("ctl-m3"),
        &[
            kept_shards[0].clone(),
            kept_shards[1].clone(),
            reruns[0].clone(),
            tampered,
        ],
    );
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success() && e.contains("different builds"), "{e}");
    // select refuses a controller a file lacks, and a file it would overwrite.
    let o = select(&tmp("ctl-s1"), "box", &old_shards);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        !o.status.success() && e.contains("has no runs of box"),
        "{e}"
    );
    let o = select(&old, "fixed-torsion", &old_shards);
    let e = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success() && e.contains("overwrite"), "{e}");
    for d in [whole, old, kept, five, six, merged, other] {
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn a_bad_shard_or_seed_list_is_refused_by_name() {
    for (args, key) in [
        (&["--shard", "3/3"][..], "--shard"),
        (&["--shard", "x"][..], "--shard"),
        (&["--seeds", "4,4"][..], "--seeds"),
    ] {
        let o = Command::new(exe())
            .args(["bench", "--quiet", "--out"])
            .arg(tmp("bad"))
            .args(args)
            .output()
            .unwrap();
        let e = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(2), "{args:?}: {e}");
        assert!(e.contains(key), "{e}");
    }
}

#[test]
fn a_rejudged_run_is_the_run_byte_for_byte() {
    // A run of all five families, whose choices `bench rejudge` rewrites from its rows
    // alone: after the choices are blanked, it gives back the run's bench.json exactly.
    let out = tmp("rejudge");
    let mut args: Vec<&str> = RUN.to_vec();
    args[1] = "lift-hold,shake,twist,mu-mismatch,faults";
    args[3] = "2";
    args[5] = "5";
    let o = Command::new(exe())
        .arg("bench")
        .args(args)
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let path = out.join("bench.json");
    let written = std::fs::read(&path).unwrap();
    let mut v: serde_json::Value = serde_json::from_slice(&written).unwrap();
    assert!(v["default_choice"]["chosen"]["controller"] == "softgrip-table");
    assert_eq!(v["baseline_default_choices"].as_array().unwrap().len(), 1);
    v["default_choice"] = serde_json::Value::Null;
    v["baseline_default_choices"] = serde_json::json!([]);
    std::fs::write(&path, serde_json::to_string_pretty(&v).unwrap() + "\n").unwrap();
    assert_ne!(std::fs::read(&path).unwrap(), written);
    let o = Command::new(exe())
        .args(["bench", "rejudge"])
        .arg(&path)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("softgrip-table@"));
    assert!(
        std::fs::read(&path).unwrap() == written,
        "rejudge changed other bytes"
    );
    let _ = std::fs::remove_dir_all(out);
}
