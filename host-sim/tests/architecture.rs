//! The layout stays a picture of the architecture: no import circle between the modules of
//! the core, of host-sim or of calibrate (at every depth of the module tree), and no
//! command importing another. Read from the sources' paths, `crate::`, `self::`, `super::`
//! and bare paths into a submodule, `use` groups expanded (the code's own imports; comments
//! and inline test modules left out), so a new circle fails here before it is built upon.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every module of the crate whose sources are under `src`, by path (`a::b`), with its file.
fn modules(src: &Path) -> BTreeMap<String, PathBuf> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            if path.extension().is_none_or(|e| e != "rs") {
                continue;
            }
            let rel = path.strip_prefix(src).unwrap().with_extension("");
            let mut parts: Vec<String> = rel
                .components()
                .map(|c| c.as_os_str().to_string_lossy().into_owned())
                .collect();
            if matches!(
                parts.last().map(String::as_str),
                Some("mod" | "lib" | "main")
            ) {
                parts.pop();
            }
            out.insert(parts.join("::"), path);
        }
    }
    out
}

/// The file's code: line comments dropped, and inline `#[cfg(test)] mod NAME { .. }`
/// blocks cut out (their `super::` is the file's own module, not its parent).
fn code_of(text: &str) -> String {
    let code: String = text
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let mut out = String::new();
    let mut rest = code.as_str();
    while let Some(i) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..i]);
        let after = &rest[i..];
        let Some(open) = after.find('{') else {
            return out;
        };
        // Only a module's block is cut; a test-only item is a line or two.
        if !after[..open].contains("mod ") {
            out.push_str("#[cfg(test)]");
            rest = &after["#[cfg(test)]".len()..];
            continue;
        }
        let mut depth = 0;
        let mut end = after.len();
        for (j, c) in after[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + j + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

fn is_path_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_' || c == ':'
}

/// The paths a path expression starting at `text` spells, as segments: `a::b::C`, or a
/// group `a::{b::C, d::{e, f}}` expanded, relative to its base.
fn expand(text: &str) -> Vec<Vec<String>> {
    let head: String = text.chars().take_while(|c| is_path_char(*c)).collect();
    let segs: Vec<String> = head
        .split("::")
        .filter(|s| !s.is_empty())
        .map(String::from)
        .collect();
    let after = &text[head.len()..];
    if !(head.ends_with("::") && after.starts_with('{')) {
        return vec![segs];
    }
    // The group's items, split at its top-level commas.
    let mut items = Vec::new();
    let (mut depth, mut start) = (0, 1);
    for (i, c) in after.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    items.push(&after[start..i]);
                    break;
                }
            }
            ',' if depth == 1 => {
                items.push(&after[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    let mut out = vec![segs.clone()];
    for item in items {
        for tail in expand(item.trim_start()) {
            out.push(segs.iter().cloned().chain(tail).collect());
        }
    }
    out
}

/// The module paths each module refers to, cut to `depth` segments: through `crate::`,
/// `self::` and `super::` (relative to the module, repeated `super::` included), and
/// through a bare path whose first segment is one of the module's own submodules; `use`
/// groups are expanded.
fn edges(src: &Path, depth: usize) -> BTreeMap<String, BTreeSet<String>> {
    let mods = modules(src);
    let cut = |m: &str| m.split("::").take(depth).collect::<Vec<_>>().join("::");
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (m, file) in &mods {
        let code = code_of(&std::fs::read_to_string(file).unwrap());
        let here: Vec<String> = m
            .split("::")
            .filter(|s| !s.is_empty())
            .map(String::from)
            .collect();
        let chars: Vec<(usize, char)> = code.char_indices().collect();
        for (k, &(i, c)) in chars.iter().enumerate() {
            // The start of a path: a letter not preceded by a path character.
            if !(c.is_ascii_lowercase()) || (k > 0 && is_path_char(chars[k - 1].1)) {
                continue;
            }
            for path in expand(&code[i..]) {
                let Some(target) = resolve(&here, &path, &mods) else {
                    continue;
                };
                // A module and its own ancestors (a parent's items used by its child, a
                // child re-exported by its parent) are one unit, not a circle.
                if is_within(m, &target) || is_within(&target, m) {
                    continue;
                }
                let (a, b) = (cut(m), cut(&target));
                if !a.is_empty() && !b.is_empty() && a != b {
                    out.entry(a).or_default().insert(b);
                }
            }
        }
    }
    out
}

/// Whether module `inner` is `outer` or inside it.
fn is_within(inner: &str, outer: &str) -> bool {
    outer.is_empty() || inner == outer || inner.starts_with(&format!("{outer}::"))
}

/// The module a path written in module `here` refers to (the longest prefix that is a
/// module), if it is one of the crate's.
fn resolve(here: &[String], path: &[String], mods: &BTreeMap<String, PathBuf>) -> Option<String> {
    let (mut base, mut rest): (Vec<String>, &[String]) = match path.first()?.as_str() {
        "crate" => (Vec::new(), &path[1..]),
        "self" => (here.to_vec(), &path[1..]),
        "super" => (here.to_vec(), path),
        // A bare path into one of this module's submodules.
        first => {
            let child = here
                .iter()
                .cloned()
                .chain([first.to_string()])
                .collect::<Vec<_>>();
            if path.len() < 2 || !mods.contains_key(&child.join("::")) {
                return None;
            }
            (here.to_vec(), path)
        }
    };
    while rest.first().map(String::as_str) == Some("super") {
        base.pop()?;
        rest = &rest[1..];
    }
    let full: Vec<String> = base.into_iter().chain(rest.iter().cloned()).collect();
    (1..=full.len())
        .rev()
        .map(|k| full[..k].join("::"))
        .find(|p| mods.contains_key(p))
}

/// A circle in `graph`, if there is one.
fn circle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == n) {
            return Some(path[i..].to_vec());
        }
        if done.contains(n) {
            return None;
        }
        path.push(n.to_string());
        for next in graph.get(n).into_iter().flatten() {
            if let Some(c) = visit(next, graph, path, done) {
                return Some(c);
            }
        }
        path.pop();
        done.insert(n.to_string());
        None
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| visit(n, graph, &mut Vec::new(), &mut done))
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
fn no_import_circle_in_the_core_host_sim_or_calibrate() {
    for crate_src in ["src", "calibrate/src", "host-sim/src"] {
        let src = root().join(crate_src);
        for depth in 1..=3 {
            let graph = edges(&src, depth);
            assert!(!graph.is_empty(), "{}: no imports read", src.display());
            if let Some(c) = circle(&graph) {
                panic!("{} at depth {depth}: {}", src.display(), c.join(" -> "));
            }
        }
    }
}

/// A command (`cmd::X`) imports neither another command (`cmd::Y`) nor the library
/// module behind another command (the top-level `Y` of a `cmd::Y`, e.g. `accuracy` behind
/// `host-sim accuracy`): what two commands share lives in a module of its own.
#[test]
fn no_command_imports_another() {
    let graph = edges(&root().join("host-sim/src"), 2);
    let commands: BTreeSet<&str> = graph
        .keys()
        .chain(graph.values().flatten())
        .filter_map(|m| m.strip_prefix("cmd::"))
        .collect();
    assert!(commands.len() > 3, "commands read: {commands:?}");
    let mut bad = Vec::new();
    for (from, to) in &graph {
        let Some(own) = from.strip_prefix("cmd::") else {
            continue;
        };
        for t in to {
            // The command a target belongs to: `cmd::Y`, or the library module `Y::..`.
            let other = t.strip_prefix("cmd::").unwrap_or(t);
            let other = other.split("::").next().unwrap_or(other);
            if other != own && (t.starts_with("cmd::") || commands.contains(other)) {
                bad.push(format!("{from} imports {t}"));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("; "));
}

/// The checker itself finds a circle when there is one.
#[test]
fn the_circle_finder_finds_one() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.entry("a".into()).or_default().insert("b".into());
    g.entry("b".into()).or_default().insert("c".into());
    assert_eq!(circle(&g), None);
    g.entry("c".into()).or_default().insert("a".into());
    assert_eq!(circle(&g), Some(vec!["a".into(), "b".into(), "c".into()]));
}
