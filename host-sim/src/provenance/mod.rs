//! What a bench run records of the build that made it: the commit, whether the sources
//! differed from it, the full default configuration of every controller, and a digest of
//! every constant that can change its results ([`scan`]). A published run's summary
//! carries it, and `host-sim/tests/evidence_version.rs` fails when this build's digest is
//! not the one the published runs were made with.

pub mod scan;

use serde::{Deserialize, Serialize};
use std::path::Path;
use std::process::Command;

/// This build's constants, as its build script read them: `(file, name, item)`.
pub const CONSTANTS: &[(&str, &str, &str)] = include!(concat!(env!("OUT_DIR"), "/constants.rs"));

/// The digest of [`CONSTANTS`] ([`scan::digest`]).
pub const CONSTANTS_DIGEST: &str = env!("SOFTGRIP_CONSTANTS_DIGEST");

/// The build a run was made with.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// The commit of the sources (`git rev-parse HEAD` where the run was started), or
    /// `unknown` outside a git checkout.
    pub commit: String,
    /// Whether the scanned sources ([`scan::SCANNED`]) differed from that commit.
    pub dirty: bool,
    /// The digest of the constants ([`scan::digest`]).
    pub constants_digest: String,
    /// Every constant the digest covers: its name and its item text.
    pub constants: Vec<(String, String)>,
    /// The default configuration of softgrip and of the baselines.
    pub configuration: serde_json::Value,
}

/// This build's constants as `(name, item)` pairs.
pub fn this_builds_constants() -> Vec<(String, String)> {
    CONSTANTS
        .iter()
        .map(|(_, name, item)| (name.to_string(), item.to_string()))
        .collect()
}

/// The provenance of a run this build makes with `configuration`, started in `dir` (any
/// folder of the checkout).
pub fn of_this_build(dir: &Path, configuration: serde_json::Value) -> Provenance {
    let commit = git(dir, &["rev-parse", "HEAD"]).unwrap_or_else(|| "unknown".into());
    let mut status = vec!["status", "--porcelain", "--"];
    status.extend(scan::SCANNED);
    let dirty = match workspace_root(dir) {
        Some(root) => git(&root, &status).is_none_or(|s| !s.is_empty()),
        None => true,
    };
    Provenance {
        commit,
        dirty,
        constants_digest: CONSTANTS_DIGEST.to_string(),
        constants: this_builds_constants(),
        configuration,
    }
}

/// The constants of the scanned sources at `commit` of the checkout at `dir`, read
/// through git.
pub fn constants_at(dir: &Path, commit: &str) -> Result<Vec<(String, String)>, String> {
    let root = workspace_root(dir).ok_or("not inside a git checkout")?;
    let mut ls = vec!["ls-tree", "-r", "--name-only", commit, "--"];
    ls.extend(scan::SCANNED);
    let files = git(&root, &ls).ok_or_else(|| format!("git ls-tree {commit} failed"))?;
    let mut out = Vec::new();
    for f in files.lines().filter(|f| scan::is_scanned(f)) {
        let text = git(&root, &["show", &format!("{commit}:{f}")])
            .ok_or_else(|| format!("git show {commit}:{f} failed"))?;
        out.extend(scan::constants(&text));
    }
    Ok(out)
}

/// Which constants differ between `then` and `now`: one line per name, `NAME: was ->
/// is` (`-` where a side has none).
pub fn differences(then: &[(String, String)], now: &[(String, String)]) -> Vec<String> {
    use std::collections::BTreeMap;
    let group = |items: &[(String, String)]| {
        let mut m: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for (name, item) in items {
            m.entry(name.clone()).or_default().push(item.clone());
        }
        for v in m.values_mut() {
            v.sort();
        }
        m
    };
    let (a, b) = (group(then), group(now));
    let names: std::collections::BTreeSet<&String> = a.keys().chain(b.keys()).collect();
    names
        .into_iter()
        .filter(|n| a.get(*n) != b.get(*n))
        .map(|n| {
            let show = |m: &BTreeMap<String, Vec<String>>| {
                m.get(n).map_or("-".to_string(), |v| v.join(" | "))
            };
            format!("{n}: {} -> {}", show(&a), show(&b))
        })
        .collect()
}

/// The full hash of `rev` in the checkout at `dir`.
pub fn resolve(dir: &Path, rev: &str) -> Option<String> {
    git(
        dir,
        &["rev-parse", "--verify", &format!("{rev}^{{commit}}")],
    )
}

/// The root of the git checkout holding `dir`.
fn workspace_root(dir: &Path) -> Option<std::path::PathBuf> {
    git(dir, &["rev-parse", "--show-toplevel"]).map(|s| s.trim().into())
}

/// `git ARGS` in `dir`: its standard output, trimmed of the last line break, or `None`
/// when git is missing or fails.
fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .arg("-C")
        .arg(dir)
        .args(args)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim_end().to_string())
}
