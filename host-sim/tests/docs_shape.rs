//! The docs stay a manual of bounded size: no page over 400 lines, docs/ under 3 MB with
//! the committed run data under 2 MB, no experiment kept as a `.patch` file, and every
//! decision page short (at most 60 lines), in the form Question, Measurement, Choice,
//! Commit (naming a commit), and listed in docs/decisions/README.md.

use std::path::{Path, PathBuf};

const MAX_PAGE_LINES: usize = 400;
const MAX_DECISION_LINES: usize = 60;
const MAX_DOCS_BYTES: u64 = 3_000_000;
const MAX_RUN_DATA_BYTES: u64 = 2_000_000;
/// Folders of the checkout that are not the project's sources.
const NOT_SOURCES: [&str; 5] = ["target", ".git", ".venv", ".firmware", "bench-out"];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every file under `dir`, sorted, skipping [`NOT_SOURCES`].
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if path.is_dir() {
                if !NOT_SOURCES.contains(&name.as_str()) {
                    stack.push(path);
                }
            } else {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

fn has_ext(p: &Path, exts: &[&str]) -> bool {
    p.extension()
        .is_some_and(|e| exts.contains(&e.to_string_lossy().as_ref()))
}

fn size(p: &Path) -> u64 {
    std::fs::metadata(p).unwrap().len()
}

#[test]
fn no_docs_page_is_over_400_lines() {
    let long: Vec<String> = files(&root().join("docs"))
        .into_iter()
        .filter(|p| has_ext(p, &["md"]))
        .filter_map(|p| {
            let n = std::fs::read_to_string(&p).unwrap().lines().count();
            (n > MAX_PAGE_LINES).then(|| format!("{}: {n} lines", p.display()))
        })
        .collect();
    assert!(
        long.is_empty(),
        "over {MAX_PAGE_LINES} lines:\n{}",
        long.join("\n")
    );
}

#[test]
fn docs_and_the_committed_run_data_stay_small() {
    let docs = files(&root().join("docs"));
    let total: u64 = docs.iter().map(|p| size(p)).sum();
    assert!(total < MAX_DOCS_BYTES, "docs/ holds {total} bytes");
    let data: u64 = files(&root().join("docs/bench"))
        .iter()
        .filter(|p| has_ext(p, &["json", "csv", "txt"]))
        .map(|p| size(p))
        .sum();
    assert!(
        data < MAX_RUN_DATA_BYTES,
        "docs/bench/ holds {data} bytes of run data: commit summaries (`host-sim bench \
         summary`), not whole runs"
    );
}

#[test]
fn no_experiment_is_kept_as_a_patch_file() {
    let patches: Vec<String> = files(&root())
        .into_iter()
        .filter(|p| has_ext(p, &["patch", "diff"]))
        .map(|p| p.display().to_string())
        .collect();
    assert!(
        patches.is_empty(),
        "cite a tried change by its commit in a docs/decisions/ page instead: {patches:?}"
    );
}

#[test]
fn every_decision_page_is_short_complete_and_listed() {
    let dir = root().join("docs/decisions");
    let index = std::fs::read_to_string(dir.join("README.md")).expect("docs/decisions/README.md");
    let pages: Vec<PathBuf> = files(&dir)
        .into_iter()
        .filter(|p| has_ext(p, &["md"]) && !p.ends_with("README.md"))
        .collect();
    assert!(pages.len() >= 10, "only {} decision pages", pages.len());
    let mut problems = Vec::new();
    for p in &pages {
        let name = p.file_name().unwrap().to_string_lossy().into_owned();
        let text = std::fs::read_to_string(p).unwrap();
        let lines = text.lines().count();
        if lines > MAX_DECISION_LINES {
            problems.push(format!("{name}: {lines} lines"));
        }
        let heads: Vec<&str> = text.lines().filter(|l| l.starts_with("## ")).collect();
        let order: Vec<&str> = ["## Question", "## Measurement", "## Choice", "## Commit"]
            .into_iter()
            .filter(|h| heads.contains(h))
            .collect();
        let positions: Vec<usize> = order
            .iter()
            .map(|h| heads.iter().position(|x| x == h).unwrap())
            .collect();
        if order.len() != 4 || !positions.windows(2).all(|w| w[0] < w[1]) {
            problems.push(format!("{name}: sections {heads:?}"));
        }
        let commit = text.split("## Commit").nth(1).unwrap_or_default();
        let names_a_commit = commit.split(|c: char| !c.is_ascii_alphanumeric()).any(|w| {
            w.len() >= 7
                && w.chars().all(|c| c.is_ascii_hexdigit())
                && w.chars().any(char::is_numeric)
        });
        if !names_a_commit {
            problems.push(format!("{name}: its Commit section names no commit"));
        }
        if !index.contains(&format!("({name})")) {
            problems.push(format!("{name}: not listed in docs/decisions/README.md"));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
