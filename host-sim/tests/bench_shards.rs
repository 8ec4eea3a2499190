//! `bench --shard I/N` and `bench merge`: the merged shards write exactly the files of the
//! whole run, byte for byte, and so do the merged runs of some of its seeds each; a merge
//! refuses a missing unit, a duplicate and shards of different runs, naming the problem.

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
    let mut args: Vec<&str> = RUN.to_vec();
    args[5] = seeds;
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
    let (a, b) = (files(&whole), files(&merged));
    let names: Vec<&str> = a.iter().map(|f| f.0.as_str()).collect();
    assert!(
        names.contains(&"bench.json") && names.contains(&"pareto-twist.png"),
        "{names:?}"
    );
    assert_eq!(names, b.iter().map(|f| f.0.as_str()).collect::<Vec<_>>());
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(
            x == y,
            "{name} differs between the whole run and the merged shards"
        );
    }
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
    let (a, b) = (files(&whole), files(&merged));
    assert_eq!(
        a.iter().map(|f| &f.0).collect::<Vec<_>>(),
        b.iter().map(|f| &f.0).collect::<Vec<_>>()
    );
    for ((name, x), (_, y)) in a.iter().zip(&b) {
        assert!(
            x == y,
            "{name} differs between the run over seeds 5,6 and the merged runs"
        );
    }
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
