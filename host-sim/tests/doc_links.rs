//! The README and docs/ hold together: every relative link of README.md, docs/*.md and
//! docs/decisions/*.md names a file that exists (relative to its page), the README's index
//! lists every docs page, and the README stays a front door of at most 250 lines.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn pages() -> Vec<PathBuf> {
    let mut pages: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.sort();
    pages
}

/// docs/decisions/'s pages, its index among them.
fn decision_pages() -> Vec<PathBuf> {
    let dir = root().join("docs/decisions");
    let mut pages: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("docs/decisions/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.sort();
    pages
}

/// The targets of the markdown links and images of `text`, `[text](target)`, outside code
/// blocks.
fn links(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        let mut rest = line;
        while let Some(i) = rest.find("](") {
            let after = &rest[i + 2..];
            let Some(end) = after.find(')') else { break };
            out.push(after[..end].to_string());
            rest = &after[end..];
        }
    }
    out
}

/// The path, relative to the repository root, of `target` linked from `page`.
fn resolve(page: &Path, target: &str) -> Option<PathBuf> {
    if target.contains("://") || target.starts_with('#') || target.starts_with("mailto:") {
        return None;
    }
    let file = target.split('#').next().unwrap_or_default();
    let dir = page.parent().unwrap_or(Path::new(""));
    let mut parts: Vec<String> = Vec::new();
    for c in dir.join(file).components() {
        match c {
            std::path::Component::ParentDir => {
                parts.pop();
            }
            std::path::Component::Normal(s) => parts.push(s.to_string_lossy().into_owned()),
            _ => {}
        }
    }
    Some(PathBuf::from(parts.join("/")))
}

#[test]
fn every_relative_link_names_a_file_that_exists() {
    let mut files = vec![PathBuf::from("README.md")];
    files.extend(pages().iter().chain(&decision_pages()).map(|p| {
        p.strip_prefix(root())
            .expect("under the root")
            .to_path_buf()
    }));
    let mut broken = Vec::new();
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(root().join(file)).expect("readable");
        for target in links(&text) {
            let Some(path) = resolve(file, &target) else {
                continue;
            };
            checked += 1;
            let name = path.to_string_lossy().into_owned();
            if !root().join(&path).exists() {
                broken.push(format!("{}: ({target}) -> {name}", file.display()));
            }
        }
    }
    assert!(
        checked > 30,
        "only {checked} links found: is the parser right?"
    );
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
}

#[test]
fn the_readme_indexes_every_docs_page() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let linked: Vec<String> = links(&readme);
    for page in pages() {
        let name = format!(
            "docs/{}",
            page.file_name().unwrap().to_string_lossy().into_owned()
        );
        assert!(
            linked.contains(&name),
            "README.md's index does not list {name}"
        );
    }
}

#[test]
fn the_readme_is_a_front_door() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let lines = readme.lines().count();
    assert!(
        lines <= 250,
        "README.md has {lines} lines; the limit is 250"
    );
    for needed in [
        "cargo run --release -p host-sim -- simulate host-sim/scenes/lift_hold.toml\n",
        "bash scripts/test.sh\n",
    ] {
        assert!(readme.contains(needed), "README.md lacks {needed:?}");
    }
}

/// The README's first-run figure is the measured one of docs/first-run.md (the row of
/// this version), at most 75 s.
#[test]
fn the_readme_states_the_measured_first_run() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let page = std::fs::read_to_string(root().join("docs/first-run.md")).unwrap();
    let row = page
        .lines()
        .find(|l| l.starts_with("| this version |"))
        .expect("docs/first-run.md has no row for this version");
    let seconds = row.split('|').nth(2).unwrap().trim();
    let value: f64 = seconds.trim_end_matches(" s").parse().unwrap();
    assert!(
        value <= 75.0,
        "first run {seconds}: the aim is 75 s or less"
    );
    assert!(
        readme.contains(&format!("first run, build included, takes {seconds} on")),
        "README.md does not state docs/first-run.md's {seconds}"
    );
}
