//! The published bench runs know their version: each committed `summary.json` records the
//! commit it was made at, the full default configuration and the digest of every constant
//! that can change its results, and this test fails when this build's are not the same,
//! naming the constants that differ and saying how to regenerate the runs. The scanner
//! behind the digest (`host_sim::provenance::scan`) is checked on hand-made sources.

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

/// The `(name, item)` pairs a summary's provenance lists.
fn constants_of(v: &Value) -> Vec<(String, String)> {
    serde_json::from_value(v["provenance"]["constants"].clone()).expect("provenance.constants")
}

#[test]
fn the_published_runs_were_made_with_this_builds_constants_and_configuration() {
    let mut failures = Vec::new();
    for (rel, how) in RUNS {
        let v = summary(rel);
        let p = &v["provenance"];
        let digest = p["constants_digest"].as_str().expect("constants_digest");
        if digest != provenance::CONSTANTS_DIGEST {
            let changed =
                provenance::differences(&constants_of(&v), &provenance::this_builds_constants());
            failures.push(format!(
                "{rel} was made at commit {} with constants digest {digest}; this build's is \
                 {}. Constants that differ (published -> this build):\n  {}\nIts figures no \
                 longer describe this code: run {how} again, copy its summary.json, printed \
                 tables and plots into {}, then `SOFTGRIP_WRITE_DOCS=1 cargo test --release \
                 -p host-sim --test bench_claims --test default_choice` regenerates the pages.",
                p["commit"],
                provenance::CONSTANTS_DIGEST,
                changed.join("\n  "),
                Path::new(rel).parent().unwrap().display(),
            ));
        }
        if p["configuration"] != host_sim::bench::summary::configuration() {
            failures.push(format!(
                "{rel}: its default configuration is not this build's (published {} against \
                 {}): run {how} again as above",
                p["configuration"],
                host_sim::bench::summary::configuration()
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn a_published_run_names_a_clean_commit_and_every_constant() {
    for (rel, _) in RUNS {
        let v = summary(rel);
        let p = &v["provenance"];
        let commit = p["commit"].as_str().unwrap();
        assert!(
            commit.len() == 40 && commit.chars().all(|c| c.is_ascii_hexdigit()),
            "{rel}: commit {commit}"
        );
        assert_eq!(p["dirty"], false, "{rel}: made from uncommitted sources");
        // The list is the digest's own input: the digest of the list is the digest.
        assert_eq!(
            scan::digest(&constants_of(&v)),
            p["constants_digest"].as_str().unwrap(),
            "{rel}"
        );
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
