//! The published bench runs know their version: each committed `summary.json` records the
//! commit it was made at, the full default configuration and the digest of every constant
//! that can change its results. A run stands for this build when those are this build's,
//! or when its last `provenance.reverified` entry's are (`host-sim bench reverify`: one
//! seed rerun on a clean commit, its rows equal bit for bit); otherwise this test fails,
//! naming the constants that differ and saying how to regenerate the runs, or to
//! reverify them after a bit-identical refactor. The scanner behind the digest
//! (`host_sim::provenance::scan`) is checked on hand-made sources.

use host_sim::provenance::{self, scan};
use serde_json::Value;
use std::path::{Path, PathBuf};

/// The committed runs: (summary, the command that makes the run again).
const RUNS: [(&str, &str); 2] = [
    (
        "docs/bench/summary.json",
        "the published run (docs/bench.md, \"The published run\")",
    ),
    (
        "docs/bench/heldout/summary.json",
        "the held-out run (docs/bench.md, \"The held-out run\")",
    ),
];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn summary(rel: &str) -> Value {
    let text = std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// The `(name, item)` pairs a provenance (a summary's, or one of its `reverified`
/// entries) lists.
fn constants_of(p: &Value) -> Vec<(String, String)> {
    serde_json::from_value(p["constants"].clone()).expect("provenance.constants")
}

/// Whether `commit` is a full git hash.
fn is_commit(commit: &str) -> bool {
    commit.len() == 40 && commit.chars().all(|c| c.is_ascii_hexdigit())
}

/// The last entry of a provenance's `reverified`, if it has one.
fn last_reverified(p: &Value) -> Option<&Value> {
    p.get("reverified").and_then(Value::as_array)?.last()
}

/// Whether a record (a provenance or a `reverified` entry) names this build's constants
/// digest and default configuration.
fn is_this_build(r: &Value) -> bool {
    r["constants_digest"].as_str() == Some(provenance::CONSTANTS_DIGEST)
        && r["configuration"] == host_sim::bench::summary::configuration()
}

/// Whether summary `v` (written to `rel`, made again by `how`) stands for this build: its
/// own provenance is this build's, or its last `reverified` entry is, and that entry is
/// clean and names a commit. Otherwise, what to do about it.
fn stands_for_this_build(rel: &str, how: &str, v: &Value) -> Result<(), String> {
    let p = &v["provenance"];
    let last = last_reverified(p);
    let vouched = last.is_some_and(|e| {
        is_this_build(e) && e["dirty"] == false && e["commit"].as_str().is_some_and(is_commit)
    });
    if is_this_build(p) || vouched {
        return Ok(());
    }
    // The newest record of the run: what this build is compared with.
    let (record, what) = match last {
        Some(e) => (e, format!("last reverified at commit {}", e["commit"])),
        None => (p, format!("made at commit {}", p["commit"])),
    };
    let changed =
        provenance::differences(&constants_of(record), &provenance::this_builds_constants());
    let configuration = if record["configuration"] == host_sim::bench::summary::configuration() {
        "the same".to_string()
    } else {
        format!(
            "{} there against {} here",
            record["configuration"],
            host_sim::bench::summary::configuration()
        )
    };
    let seeds: Vec<String> = v["key"]["seeds"]
        .as_array()
        .map(|s| s.iter().map(Value::to_string).collect())
        .unwrap_or_default();
    Err(format!(
        "{rel} ({what}, constants digest {}) does not stand for this build (digest {}, dirty \
         entries and entries without a commit not counted). Constants that differ (then -> \
         this build):\n  {}\nDefault configuration: {configuration}.\nIf the change moves \
         results, its figures no longer describe this code: run {how} again, copy its \
         summary.json, printed tables and plots into {}, then `SOFTGRIP_WRITE_DOCS=1 cargo \
         test --release -p host-sim --test bench_claims --test default_choice` regenerates \
         the pages. If it is a refactor meant to keep every output bit-identical, instead \
         commit it and run `host-sim bench reverify {rel} --seed <one of {}>` on a clean \
         checkout, then commit the rewritten summary.",
        record["constants_digest"],
        provenance::CONSTANTS_DIGEST,
        changed.join("\n  "),
        Path::new(rel).parent().unwrap().display(),
        seeds.join(", "),
    ))
}

#[test]
fn the_published_runs_stand_for_this_builds_constants_and_configuration() {
    let failures: Vec<String> = RUNS
        .iter()
        .filter_map(|(rel, how)| stands_for_this_build(rel, how, &summary(rel)).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

/// Checks that `r` (a provenance or a `reverified` entry of `rel`) names a clean commit
/// and lists every constant its digest covers.
fn check_record(rel: &str, what: &str, r: &Value) {
    let commit = r["commit"].as_str().unwrap_or("");
    assert!(is_commit(commit), "{rel}: {what}: commit {commit}");
    assert_eq!(
        r["dirty"], false,
        "{rel}: {what}: made from uncommitted sources"
    );
    // The list is the digest's own input: the digest of the list is the digest.
    assert_eq!(
        scan::digest(&constants_of(r)),
        r["constants_digest"].as_str().unwrap(),
        "{rel}: {what}"
    );
    assert!(
        r["configuration"].is_object(),
        "{rel}: {what}: configuration"
    );
}

#[test]
fn a_published_run_names_a_clean_commit_and_every_constant() {
    for (rel, _) in RUNS {
        let v = summary(rel);
        check_record(rel, "provenance", &v["provenance"]);
    }
}

/// Checks the `reverified` entries of summary `v`: each is a clean record, names one of
/// the run's seeds and compared every published default row of it.
fn check_reverified(rel: &str, v: &Value) {
    let Some(entries) = v["provenance"].get("reverified") else {
        return;
    };
    let entries = entries
        .as_array()
        .unwrap_or_else(|| panic!("{rel}: reverified"));
    assert!(!entries.is_empty(), "{rel}: reverified is empty");
    let seeds = v["key"]["seeds"].as_array().expect("key.seeds");
    for (i, e) in entries.iter().enumerate() {
        let what = format!("reverified[{i}]");
        check_record(rel, &what, e);
        let seed = &e["seed"];
        assert!(
            seeds.contains(seed),
            "{rel}: {what}: seed {seed} is not the run's"
        );
        let rows = v["per_seed_defaults"]
            .as_array()
            .map_or(0, |r| r.iter().filter(|r| r["seed"] == *seed).count());
        assert!(rows > 0, "{rel}: {what}: no published row of seed {seed}");
        assert_eq!(e["rows_compared"], rows, "{rel}: {what}: rows_compared");
    }
}

#[test]
fn a_reverified_entry_names_a_clean_commit_a_seed_of_the_run_and_its_rows() {
    for (rel, _) in RUNS {
        check_reverified(rel, &summary(rel));
    }
}

/// A summary like the published ones, whose own provenance is another build's.
fn an_older_run() -> Value {
    let mut v = summary(RUNS[0].0);
    v["provenance"]["constants_digest"] = "0000000000000000".into();
    v["provenance"]["constants"] = serde_json::json!([["OLD", "OLD: f64 = 1.0"]]);
    v["provenance"]
        .as_object_mut()
        .unwrap()
        .remove("reverified");
    v
}

/// An entry `bench reverify` appends on this build, clean, on the run's first seed.
fn this_builds_entry(v: &Value) -> Value {
    let seed = v["key"]["seeds"][0].clone();
    let rows = v["per_seed_defaults"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["seed"] == seed)
        .count();
    let mut e = serde_json::json!({
        "commit": "0123456789abcdef0123456789abcdef01234567",
        "dirty": false,
        "constants_digest": provenance::CONSTANTS_DIGEST,
        "constants": provenance::this_builds_constants(),
        "configuration": host_sim::bench::summary::configuration(),
    });
    e["seed"] = seed;
    e["rows_compared"] = rows.into();
    e
}

#[test]
fn a_run_stands_for_this_build_through_its_last_clean_reverified_entry() {
    let (rel, how) = RUNS[0];
    let mut v = an_older_run();
    let refused = stands_for_this_build(rel, how, &v).unwrap_err();
    assert!(refused.contains("OLD: OLD: f64 = 1.0 -> -"), "{refused}");
    assert!(refused.contains(&format!("host-sim bench reverify {rel} --seed <one of 17")));
    let entry = this_builds_entry(&v);
    v["provenance"]["reverified"] = serde_json::json!([entry.clone()]);
    assert_eq!(stands_for_this_build(rel, how, &v), Ok(()));
    check_reverified(rel, &v);
    // Only the last entry counts: an older build's after it takes the vouch back.
    let mut older = entry.clone();
    older["constants_digest"] = "0000000000000000".into();
    v["provenance"]["reverified"] = serde_json::json!([entry.clone(), older]);
    assert!(stands_for_this_build(rel, how, &v).is_err());
    // A dirty entry, or one without a commit, vouches for nothing.
    for (field, value) in [("dirty", Value::Bool(true)), ("commit", "unknown".into())] {
        let mut e = entry.clone();
        e[field] = value;
        v["provenance"]["reverified"] = serde_json::json!([e]);
        let refused = stands_for_this_build(rel, how, &v).unwrap_err();
        assert!(refused.contains("bench reverify"), "{field}: {refused}");
    }
}

#[test]
fn this_builds_constants_are_read_from_every_scanned_source() {
    let names: Vec<&str> = provenance::CONSTANTS.iter().map(|c| c.1).collect();
    for name in [
        "DEFAULT",
        "CYCLIC_SAFETY_FACTOR",
        "DISC_TORSION_SAFETY_FACTOR",
        "CONSTANT_DEFAULT_N",
    ] {
        assert!(names.contains(&name), "{name} not scanned");
    }
    let files: Vec<&str> = provenance::CONSTANTS.iter().map(|c| c.0).collect();
    for dir in [
        "src/",
        "calibrate/src/",
        "host-sim/src/bench/",
        "host-sim/src/brush/",
    ] {
        assert!(
            files.iter().any(|f| f.starts_with(dir)),
            "nothing from {dir}"
        );
    }
    assert!(files.iter().all(|f| scan::is_scanned(f)));
    assert_eq!(
        scan::digest(&provenance::this_builds_constants()),
        provenance::CONSTANTS_DIGEST
    );
}

const SOURCE: &str = r##"
//! const NOT_AN_ITEM: f64 = 1.0;
/// The margin.
pub const MARGIN: f64 = 1.45; // why
const TABLE: [f64; 2] = [0.5, /* inline */ 2.0];
const TEXT: &str = "a // b; c";
const C: char = '"';
const R: &str = r#"x"; y"#;
struct S<const N: usize>;
const fn f(p: *const u8) -> usize { 0 }
impl S<1> {
    pub const DEFAULT: Self = Self {};
}
#[cfg(test)]
mod tests {
    const IN_TESTS: f64 = 3.0;
}
"##;

#[test]
fn the_scanner_reads_items_and_skips_comments_generics_pointers_and_tests() {
    let found = scan::constants(SOURCE);
    let names: Vec<&str> = found.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["MARGIN", "TABLE", "TEXT", "C", "R", "DEFAULT"]);
    assert_eq!(found[0].1, "MARGIN: f64 = 1.45");
    assert_eq!(found[1].1, "TABLE: [f64; 2] = [0.5, 2.0]");
    assert_eq!(found[2].1, "TEXT: &str = \"a // b; c\"");
    assert_eq!(found[4].1, "R: &str = r#\"x\"; y\"#");
}

#[test]
fn the_digest_follows_values_and_names_not_comments_or_places() {
    let base = scan::digest(&scan::constants(SOURCE));
    let changed = SOURCE.replace("1.45", "1.5");
    assert_ne!(scan::digest(&scan::constants(&changed)), base);
    let renamed = SOURCE.replace("MARGIN", "CYCLIC");
    assert_ne!(scan::digest(&scan::constants(&renamed)), base);
    let commented = SOURCE.replace("/// The margin.", "/// The margin, 1.45: see tests.");
    assert_eq!(scan::digest(&scan::constants(&commented)), base);
    let moved = SOURCE.replace("pub const MARGIN: f64 = 1.45; // why\n", "")
        + "pub const MARGIN: f64 =\n    1.45;\n";
    assert_eq!(scan::digest(&scan::constants(&moved)), base);
    // The differences name the constant, with both values.
    let d = provenance::differences(&scan::constants(SOURCE), &scan::constants(&changed));
    assert_eq!(d, ["MARGIN: MARGIN: f64 = 1.45 -> MARGIN: f64 = 1.5"]);
}
