//! Every tuning figure in a comment of the workspace's Rust sources names where it is shown
//! (issue 56: "every number left in a code comment names the test or decision page that
//! shows it"). Scanned: `src/`, `calibrate/src/` and `host-sim/src/`.
//!
//! The rule, read from the sources:
//! - A *comment line* is a line whose first non-blank characters are `//` (so `//`, `///`
//!   and `//!`). A *comment block* is a run of consecutive comment lines of the same kind,
//!   ended by a line that is not one, or by a blank comment line (a paragraph break).
//! - A *tuning figure* is a number with a decimal point (`0.85`), a percentage (`30 %`,
//!   `30%`) or a factor (`2 ×`, `2x`), not part of a word (`f32`, `M4F` are no numbers).
//! - A block with a tuning figure must name a *source*: a test file (a path with
//!   `tests/` ending in `.rs`, such as `tests/creep.rs` or `host-sim/tests/bench.rs`) or a
//!   decision page (`docs/decisions/SLUG.md`).
//! - A `///` block that is command-line help (the text `--help` prints) may take its
//!   source from a plain `//` line directly above it, so the help stays free of test
//!   paths: `// host-sim/tests/help_figures.rs` over `/// ... [default: 0.8]`.
//! - Every source named in any comment must exist (relative to the repository root), and a
//!   test named as `FILE.rs::NAME` must have a `fn NAME` in that file.
//!
//! A file not yet held to the rule would be listed in [`NOT_YET_CHECKED`] (paths
//! relative to the workspace root; none is); an entry that passes fails the test, so the
//! list cannot go stale.

use std::path::{Path, PathBuf};

/// Files (relative to the workspace root) not yet held to the rule; each one must still
/// break it.
const NOT_YET_CHECKED: [&str; 0] = [];

/// The directories scanned, relative to the workspace root.
const SCANNED: [&str; 3] = ["src", "calibrate/src", "host-sim/src"];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Every `.rs` file under `dir`, sorted.
fn sources(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("read_dir") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            out.extend(sources(&path));
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    out.sort();
    out
}

/// The comment blocks of `source`: (first line, 1-based; the blocks' lines).
fn blocks(source: &str) -> Vec<(usize, Vec<String>)> {
    let mut out: Vec<(usize, Vec<String>)> = Vec::new();
    let mut open: Option<(&str, usize, Vec<String>)> = None;
    for (i, line) in source.lines().enumerate() {
        let t = line.trim_start();
        let kind = if t.starts_with("//!") {
            Some("//!")
        } else if t.starts_with("///") {
            Some("///")
        } else if t.starts_with("//") {
            Some("//")
        } else {
            None
        };
        let text = kind.map(|k| t[k.len()..].trim());
        let same = matches!((&open, kind), (Some((k, ..)), Some(k2)) if *k == k2);
        if !same || text == Some("") {
            if let Some((_, first, lines)) = open.take() {
                out.push((first, lines));
            }
        }
        if let (Some(k), Some(text)) = (kind, text) {
            if !text.is_empty() {
                open.get_or_insert((k, i + 1, Vec::new()))
                    .2
                    .push(text.to_string());
            }
        }
    }
    if let Some((_, first, lines)) = open {
        out.push((first, lines));
    }
    out
}

/// The tuning figures of `text` (see the module's docs).
fn figures(text: &str) -> Vec<String> {
    let c: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < c.len() {
        let word_before = i > 0 && (c[i - 1].is_alphanumeric() || c[i - 1] == '_');
        if !c[i].is_ascii_digit() || word_before {
            i += 1;
            continue;
        }
        let start = i;
        while i < c.len() && c[i].is_ascii_digit() {
            i += 1;
        }
        let decimal = i + 1 < c.len() && c[i] == '.' && c[i + 1].is_ascii_digit();
        if decimal {
            i += 1;
            while i < c.len() && c[i].is_ascii_digit() {
                i += 1;
            }
        }
        let number: String = c[start..i].iter().collect();
        let next = |k: usize| c.get(k).copied();
        let spaced = if next(i) == Some(' ') { i + 1 } else { i };
        let percent = next(spaced) == Some('%');
        let times = next(spaced) == Some('×');
        let x_factor =
            next(i) == Some('x') && !next(i + 1).is_some_and(|n| n.is_alphanumeric() || n == '_');
        if decimal || percent || times || x_factor {
            out.push(number);
        }
        while i < c.len() && (c[i].is_alphanumeric() || c[i] == '_' || c[i] == '.') {
            i += 1;
        }
    }
    out
}

/// The sources named in `text`: `(path, test name)` for `…tests/….rs[::name]` and
/// `docs/decisions/….md`.
fn sources_named(text: &str) -> Vec<(String, Option<String>)> {
    let is_path = |ch: char| ch.is_alphanumeric() || "_-/.".contains(ch);
    let mut out = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(|ch: char| is_path(ch)) {
        let tail = &rest[at..];
        let end = tail.find(|ch: char| !is_path(ch)).unwrap_or(tail.len());
        let token = tail[..end].trim_end_matches('.');
        let token = token.strip_prefix("../").unwrap_or(token);
        let mut after = &tail[end..];
        let is_test = token.contains("tests/") && token.ends_with(".rs");
        let is_page = token.starts_with("docs/decisions/") && token.ends_with(".md");
        if is_test || is_page {
            let name = if is_test && after.starts_with("::") {
                let n = &after[2..];
                let len = n
                    .find(|ch: char| !(ch.is_alphanumeric() || ch == '_'))
                    .unwrap_or(n.len());
                after = &n[len..];
                Some(n[..len].to_string())
            } else {
                None
            };
            out.push((token.to_string(), name));
        }
        rest = after;
    }
    out
}

/// What is wrong with `file`'s comments, one line each.
fn problems(file: &Path) -> Vec<String> {
    let source = std::fs::read_to_string(file).expect("read");
    let shown = file
        .strip_prefix(root())
        .unwrap_or(file)
        .display()
        .to_string();
    let mut out = Vec::new();
    let lines: Vec<&str> = source.lines().collect();
    for (line, block) in blocks(&source) {
        let text = block.join(" ");
        let named = sources_named(&text);
        let above = above_doc(&lines, line);
        for (path, name) in &named {
            let target = root().join(path);
            match std::fs::read_to_string(&target) {
                Err(_) => out.push(format!(
                    "{shown}:{line}: names {path}, which does not exist"
                )),
                Ok(body) => {
                    if let Some(name) = name {
                        if !body.contains(&format!("fn {name}")) {
                            out.push(format!("{shown}:{line}: {path} has no fn {name}"));
                        }
                    }
                }
            }
        }
        let found = figures(&text);
        if !found.is_empty() && named.is_empty() && above.is_empty() {
            out.push(format!(
                "{shown}:{line}: {} without a test or decision page: {}",
                found.join(", "),
                block.first().map_or("", |l| l.as_str())
            ));
        }
    }
    out
}

/// The sources a plain `//` line directly above line `line` (1-based) names, when that
/// line opens a `///` block.
fn above_doc(lines: &[&str], line: usize) -> Vec<(String, Option<String>)> {
    let here = lines.get(line - 1).map_or("", |l| l.trim_start());
    let prev = line
        .checked_sub(2)
        .and_then(|i| lines.get(i))
        .map_or("", |l| l.trim_start());
    let plain = prev.starts_with("//") && !prev.starts_with("///") && !prev.starts_with("//!");
    if here.starts_with("///") && plain {
        sources_named(prev)
    } else {
        Vec::new()
    }
}

fn is_listed(file: &Path) -> bool {
    let rel = file.strip_prefix(root()).unwrap_or(file);
    NOT_YET_CHECKED.iter().any(|l| rel == Path::new(l))
}

#[test]
fn every_tuning_figure_in_a_source_comment_names_its_source() {
    let mut all = Vec::new();
    for file in SCANNED.iter().flat_map(|d| sources(&root().join(d))) {
        if !is_listed(&file) {
            all.extend(problems(&file));
        }
    }
    assert!(all.is_empty(), "\n{}", all.join("\n"));
}

#[test]
fn the_files_not_yet_checked_still_break_the_rule() {
    for listed in NOT_YET_CHECKED {
        let file = root().join(listed);
        assert!(
            file.exists(),
            "{listed} is gone: take it off NOT_YET_CHECKED"
        );
        assert!(
            !problems(&file).is_empty(),
            "{listed} passes now: take it off NOT_YET_CHECKED"
        );
    }
}

#[test]
fn the_rule_sees_what_it_should() {
    // Figures: decimals, percentages, factors; not words or plain counts.
    assert_eq!(
        figures("asks 1.15·N_slip, 30 % or 12%, 2 × and 3x"),
        ["1.15", "30", "12", "2", "3"]
    );
    assert!(
        figures("f32 on the M4F, 2 000 instructions, 0x1F, 64 nodes, docs/model.md").is_empty()
    );
    // Sources: test files (with a test's name) and decision pages.
    assert_eq!(
        sources_named("(`tests/creep.rs`; host-sim/tests/bench.rs::a_test, docs/decisions/x.md.)"),
        [
            ("tests/creep.rs".to_string(), None),
            (
                "host-sim/tests/bench.rs".to_string(),
                Some("a_test".to_string())
            ),
            ("docs/decisions/x.md".to_string(), None),
        ]
    );
    // A paragraph break ends a block; a doc comment and a plain comment are two blocks.
    let b = blocks("//! a 0.5\n//!\n//! b\n/// c\n// d\nfn x() {}\n");
    assert_eq!(b.len(), 4);
    // A tuning figure without a source in the same block is found.
    let dir = std::env::temp_dir().join(format!("comment_numbers_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("sample.rs");
    std::fs::write(
        &file,
        "/// The factor \\[-\\]: 0.85 kept table mode at 1.75 (docs/bench.md, \"The default\").\n\
         pub const F: f64 = 0.85;\n\
         /// Shown by `tests/creep.rs`: 0.7.\n\
         pub const G: f64 = 0.7;\n\
         // Help text, shown by tests/creep.rs.\n\
         /// The help: 0.4.\n\
         pub const H: f64 = 0.4;\n\
         // No source here.\n\
         /// The help: 0.3.\n\
         pub const I: f64 = 0.3;\n",
    )
    .unwrap();
    let found = problems(&file);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].contains(":1: 0.85, 1.75 without"), "{found:?}");
    assert!(found[1].contains(":9: 0.3 without"), "{found:?}");
}
