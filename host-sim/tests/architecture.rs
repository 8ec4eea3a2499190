//! The layout stays a picture of the architecture: no import circle between the modules of
//! the core or of host-sim (at every depth of the module tree), and no command importing
//! another. Read from the sources' `crate::` paths (the code's own imports, doc links and
//! comments left out), so a new circle fails here before it is built upon.

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

/// The module paths each module refers to through `crate::`, cut to `depth` segments.
fn edges(src: &Path, depth: usize) -> BTreeMap<String, BTreeSet<String>> {
    let mods = modules(src);
    let cut = |m: &str| m.split("::").take(depth).collect::<Vec<_>>().join("::");
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (m, file) in &mods {
        let text = std::fs::read_to_string(file).unwrap();
        for line in text.lines() {
            let code = line.split("//").next().unwrap_or("");
            let mut rest = code;
            while let Some(i) = rest.find("crate::") {
                rest = &rest[i + "crate::".len()..];
                let path: String = rest
                    .chars()
                    .take_while(|c| {
                        c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '_' || *c == ':'
                    })
                    .collect();
                let segs: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
                // The longest prefix that is a module.
                let Some(target) = (1..=segs.len())
                    .rev()
                    .map(|k| segs[..k].join("::"))
                    .find(|p| mods.contains_key(p))
                else {
                    continue;
                };
                let (a, b) = (cut(m), cut(&target));
                if !a.is_empty() && !b.is_empty() && a != b {
                    out.entry(a).or_default().insert(b);
                }
            }
        }
    }
    out
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
fn no_import_circle_in_the_core_or_host_sim() {
    for src in [root().join("src"), root().join("host-sim/src")] {
        for depth in 1..=3 {
            let graph = edges(&src, depth);
            assert!(!graph.is_empty(), "{}: no imports read", src.display());
            if let Some(c) = circle(&graph) {
                panic!("{} at depth {depth}: {}", src.display(), c.join(" -> "));
            }
        }
    }
}

#[test]
fn no_command_imports_another() {
    let graph = edges(&root().join("host-sim/src"), 2);
    for (from, to) in &graph {
        if from.starts_with("cmd::") {
            let other: Vec<&String> = to.iter().filter(|t| t.starts_with("cmd::")).collect();
            assert!(other.is_empty(), "{from} imports {other:?}");
        }
    }
    assert!(
        graph.keys().any(|k| k.starts_with("cmd::")),
        "no command read"
    );
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
