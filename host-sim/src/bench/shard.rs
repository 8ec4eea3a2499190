//! A share of a bench's work, and the merge of shares: so that a job runner (a Slurm
//! array, or any other) can spread a large sweep over machines.
//!
//! A work unit is one trial of one family under one seed, numbered in a fixed order:
//! families (in the run's order), then seeds, then the trial's index. `--shard I/N` runs
//! the units whose number is `I` modulo `N` and writes `OUT/shard-I-of-N.json`: the
//! [`Key`] (every option that changes a result) and each unit's [`TrialResult`], whole.
//! `bench merge` reads the shards of one run, checks that they share a key and cover
//! every unit exactly once, and writes the files a single run writes, from the same
//! results: bit for bit the same (`host-sim/tests/bench_shards.rs`). Floats round-trip
//! exactly through the JSON (serde_json's `float_roundtrip`).
//!
//! It also pools runs that differ in their seeds alone: a trial's result depends only on
//! its family, seed and index (each draws from a stream of its own), so the shards of a
//! run over seeds `A` and of one over seeds `B` hold every unit of the run over `A` then
//! `B` (each seed once, in the order the files first name it), and the merge writes that
//! run's files, bit for bit. A held-out set can so grow by seeds without rerunning the
//! ones it has, as long as every shard comes from the same build: the key records the
//! options, not the code (bench.md, "Outputs, shards and merge").
//!
//! Runs that differ in their controllers pool the same way: a controller's runs of a
//! trial depend only on the trial, not on which other controllers ran beside it. So after
//! a change to one controller, only that controller is rerun, and [`select`] takes the
//! others out of the shards a run already has (`bench select`). Each controller of each
//! unit must then come from exactly one file, and the files must agree on each trial's
//! own facts (its μ, sensor, holdability and oracle force), bit for bit.

use super::families::Ranges;
use super::sweep::{RunRow, Sweep, TrialResult, SWEEPS};
use super::trial_finger::{BenchPlant, FingerSource};
use super::{BenchError, BenchLink, BenchOptions};
use serde::{Deserialize, Serialize};
use softgrip::controller::FingerShape;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Shard `index` of `count` (`index < count`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard's number, from 0.
    pub index: usize,
    /// How many shards share the run.
    pub count: usize,
}

impl Shard {
    /// Parses `I/N` (`0 ≤ I < N`).
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = || format!("\"{text}\" is not I/N with 0 <= I < N (e.g. 0/4)");
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether work unit `number` is this shard's.
    pub fn takes(&self, number: usize) -> bool {
        number % self.count == self.index
    }
}

/// One work unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unit {
    /// Its number in the run's fixed order.
    pub number: usize,
    /// The family.
    pub family: &'static str,
    /// The seed.
    pub seed: u64,
    /// The trial's index.
    pub index: usize,
}

/// Every unit of a run, in order: families, then seeds, then trial index.
pub fn units(opts: &BenchOptions) -> Vec<Unit> {
    let mut out = Vec::new();
    for family in &opts.families {
        for &seed in &opts.seeds {
            for index in 0..opts.trials {
                out.push(Unit {
                    number: out.len(),
                    family,
                    seed,
                    index,
                });
            }
        }
    }
    out
}

/// One controller's sweep as a key records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepKey {
    /// The controller's name.
    pub controller: String,
    /// The knob's values.
    pub values: Vec<f64>,
    /// The default value.
    pub default: f64,
}

/// Every option that changes a bench's results, as `bench.json` and the shard files
/// record it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Key {
    /// `brush` or `fls`.
    pub plant: String,
    /// The finger of `--finger`, if one (its fields, as the limit-surface finger).
    pub finger: Option<[f64; 6]>,
    /// `--hard`.
    pub hard: bool,
    /// `--tell-actuator`.
    pub tell_actuator: bool,
    /// The seeds, pooled.
    pub seeds: Vec<u64>,
    /// Trials per family and seed.
    pub trials: usize,
    /// The families.
    pub families: Vec<String>,
    /// The controllers and their grids.
    pub sweeps: Vec<SweepKey>,
    /// softgrip's link (`direct` or `pty`).
    pub link: String,
}

impl Key {
    /// The key of `opts`.
    pub fn of(opts: &BenchOptions) -> Self {
        Self {
            plant: opts.source.plant().name().to_string(),
            finger: match opts.source {
                FingerSource::Fixed(s) => Some([
                    match s.shape {
                        FingerShape::Rect => 0.0,
                        FingerShape::Disc => 1.0,
                    },
                    s.mu,
                    s.k,
                    s.c,
                    s.gamma,
                    s.half_length_m,
                ]),
                FingerSource::Drawn(_) => None,
            },
            hard: opts.ranges.hard,
            tell_actuator: opts.ranges.tell_actuator,
            seeds: opts.seeds.clone(),
            trials: opts.trials,
            families: opts.families.iter().map(|f| f.to_string()).collect(),
            sweeps: opts
                .sweeps
                .iter()
                .map(|s| SweepKey {
                    controller: s.controller.name().to_string(),
                    values: s.values.to_vec(),
                    default: s.default,
                })
                .collect(),
            link: opts.link.name().to_string(),
        }
    }
}

/// One unit's result in a shard file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct UnitResult {
    family: String,
    seed: u64,
    index: usize,
    result: TrialResult,
}

/// A shard file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct ShardFile {
    key: Key,
    shard: [usize; 2],
    units: Vec<UnitResult>,
}

/// Writes shard `s`'s file, `OUT/shard-I-of-N.json`, with the results of `units`.
pub fn write(
    opts: &BenchOptions,
    s: Shard,
    units: &[Unit],
    results: &[TrialResult],
) -> Result<PathBuf, BenchError> {
    let file = ShardFile {
        key: Key::of(opts),
        shard: [s.index, s.count],
        units: units
            .iter()
            .zip(results)
            .map(|(u, r)| UnitResult {
                family: u.family.to_string(),
                seed: u.seed,
                index: u.index,
                result: r.clone(),
            })
            .collect(),
    };
    let path = opts
        .out
        .join(format!("shard-{}-of-{}.json", s.index, s.count));
    let text = serde_json::to_string(&file).map_err(|e| BenchError::Run(e.to_string()))?;
    std::fs::write(&path, text + "\n")
        .map_err(|e| BenchError::Write(format!("{}: {e}", path.display())))?;
    Ok(path)
}

impl Key {
    /// The options the key describes, writing to `out`: its families by name, the trials'
    /// fingers (`finger`'s, its shape 1 a disc and else a rectangle, or those drawn on its
    /// plant) and its link, with `sweeps` as the caller resolves the key's (a shard merge
    /// by grid, reverify by grid and default); or what in the key this build does not know.
    /// Shared by a shard merge and `bench reverify` ([`super::reverify`]).
    pub(super) fn options(
        &self,
        sweeps: Vec<Sweep>,
        out: &Path,
        quiet: bool,
    ) -> Result<BenchOptions, String> {
        let families = self
            .families
            .iter()
            .map(|f| {
                super::families::NAMES
                    .into_iter()
                    .find(|n| n == f)
                    .ok_or_else(|| format!("the key's family {f} is not one of this build's"))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let source = match (self.plant.as_str(), self.finger) {
            (_, Some([shape, mu, k, c, gamma, half_length_m])) => {
                FingerSource::Fixed(crate::experiment::FingerSpec {
                    shape: if shape == 1.0 {
                        FingerShape::Disc
                    } else {
                        FingerShape::Rect
                    },
                    mu,
                    k,
                    c,
                    gamma,
                    half_length_m,
                    skew: None,
                })
            }
            ("brush", None) => FingerSource::Drawn(BenchPlant::Brush),
            ("fls", None) => FingerSource::Drawn(BenchPlant::Fls),
            (p, None) => return Err(format!("the key's plant {p} is not brush or fls")),
        };
        let link = match self.link.as_str() {
            "direct" => BenchLink::Direct,
            "pty" => BenchLink::Pty,
            other => return Err(format!("the key's link {other} is not direct or pty")),
        };
        Ok(BenchOptions {
            families,
            sweeps,
            source,
            ranges: Ranges {
                hard: self.hard,
                tell_actuator: self.tell_actuator,
            },
            trials: self.trials,
            seeds: self.seeds.clone(),
            shard: None,
            link,
            out: out.to_path_buf(),
            trace: false,
            quiet,
        })
    }
}

/// The options a key describes, its sweeps found by controller and grid, writing to
/// `out`; or what in the key this build does not know.
fn options_of(key: &Key, out: &Path) -> Result<BenchOptions, String> {
    let sweeps = key
        .sweeps
        .iter()
        .map(|k| {
            SWEEPS
                .iter()
                .find(|s| s.controller.name() == k.controller && s.values == k.values.as_slice())
                .copied()
                .ok_or_else(|| format!("no sweep of {} with those values", k.controller))
        })
        .collect::<Result<Vec<Sweep>, _>>()?;
    key.options(sweeps, out, true)
}

/// The names of the options in which two keys differ.
fn differing(a: &Key, b: &Key) -> String {
    let (Ok(serde_json::Value::Object(x)), Ok(serde_json::Value::Object(y))) =
        (serde_json::to_value(a), serde_json::to_value(b))
    else {
        return "options".into();
    };
    let names: Vec<&str> = x
        .iter()
        .filter(|(k, v)| y.get(*k) != Some(*v))
        .map(|(k, _)| k.as_str())
        .collect();
    format!("options {}", names.join(", "))
}

/// The columns of each sweep of `key` in a trial's runs: `(controller, start, end)`.
fn columns(key: &Key) -> Vec<(&str, usize, usize)> {
    let mut start = 0;
    key.sweeps
        .iter()
        .map(|s| {
            let end = start + s.values.len();
            let c = (s.controller.as_str(), start, end);
            start = end;
            c
        })
        .collect()
}

fn read(path: &Path) -> Result<ShardFile, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let file: ShardFile =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
    let width: usize = file.key.sweeps.iter().map(|s| s.values.len()).sum();
    match file.units.iter().find(|u| u.result.runs.len() != width) {
        Some(u) => Err(format!(
            "{}: {} trial {} of seed {} has {} runs where its sweeps have {width}",
            path.display(),
            u.family,
            u.index,
            u.seed,
            u.result.runs.len()
        )),
        None => Ok(file),
    }
}

/// Writes the shard files `paths` again into the directory `out`, each under its own name,
/// keeping only the runs of `controllers` (in the order the file has them); returns the
/// paths written. Refuses a file that lacks one of them, and a file that would overwrite
/// itself.
pub fn select(paths: &[PathBuf], controllers: &[&str], out: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(out).map_err(|e| format!("{}: {e}", out.display()))?;
    let mut written = Vec::new();
    for path in paths {
        let mut file = read(path)?;
        let cols = columns(&file.key);
        if let Some(c) = controllers
            .iter()
            .find(|c| !cols.iter().any(|(name, ..)| name == *c))
        {
            return Err(format!("{}: has no runs of {c}", path.display()));
        }
        let keep: Vec<(usize, usize)> = cols
            .iter()
            .filter(|(name, ..)| controllers.contains(name))
            .map(|&(_, a, b)| (a, b))
            .collect();
        file.key
            .sweeps
            .retain(|s| controllers.contains(&s.controller.as_str()));
        for u in &mut file.units {
            let runs = std::mem::take(&mut u.result.runs);
            u.result.runs = keep
                .iter()
                .flat_map(|&(a, b)| runs[a..b].to_vec())
                .collect();
        }
        let name = path
            .file_name()
            .ok_or_else(|| format!("{}: not a file", path.display()))?;
        let to = out.join(name);
        if let (Ok(a), Ok(b)) = (to.canonicalize(), path.canonicalize()) {
            if a == b {
                return Err(format!(
                    "{}: --out would overwrite it; choose another directory",
                    path.display()
                ));
            }
        }
        let text = serde_json::to_string(&file).map_err(|e| e.to_string())?;
        std::fs::write(&to, text + "\n").map_err(|e| format!("{}: {e}", to.display()))?;
        written.push(to);
    }
    Ok(written)
}

/// A trial's own facts, which every file that holds it must give alike.
fn facts(r: &TrialResult) -> [u64; 5] {
    [
        r.true_mu.to_bits(),
        r.mu_ratio.to_bits(),
        u64::from(r.sensor),
        u64::from(r.holdable),
        r.oracle_mean_n.to_bits(),
    ]
}

/// One unit as the files give it: a file's trial (its facts) and each controller's runs.
struct Gathered {
    first: TrialResult,
    from: PathBuf,
    runs: BTreeMap<String, Vec<RunRow>>,
}

/// The units gathered so far, by family, seed and trial index.
type Units = BTreeMap<(String, u64, usize), Gathered>;

/// Pools the key `other` of the file `path` into `k`, the key of the files before it (the
/// first of them `first`): its new seeds and controllers join `k`'s; anything else that
/// differs, or a controller's grid, is refused.
fn pool_key(k: &mut Key, other: &Key, first: &Path, path: &Path) -> Result<(), String> {
    // A default is a label (no trial reads it, and the merge marks this build's), so
    // shards written before a default moved still pool.
    let mut rest = other.clone();
    rest.seeds.clone_from(&k.seeds);
    rest.sweeps.clone_from(&k.sweeps);
    let different = |what: String| {
        format!(
            "{} and {} are shards of different runs (their {what} differ)",
            first.display(),
            path.display()
        )
    };
    if *k != rest {
        return Err(different(differing(k, &rest)));
    }
    for s in &other.sweeps {
        match k.sweeps.iter().find(|t| t.controller == s.controller) {
            Some(t) if t.values != s.values => {
                return Err(different(format!("grids of {}", s.controller)))
            }
            Some(_) => {}
            None => k.sweeps.push(s.clone()),
        }
    }
    for seed in &other.seeds {
        if !k.seeds.contains(seed) {
            k.seeds.push(*seed);
        }
    }
    Ok(())
}

/// Adds the units of `file` (read from `path`) to `got`, each controller's runs once;
/// refuses a trial whose facts differ from another file's, and a controller's runs of a
/// unit given twice.
fn gather(got: &mut Units, file: ShardFile, path: &Path) -> Result<(), String> {
    let cols = columns(&file.key);
    for u in file.units {
        let at = format!("{} trial {} of seed {}", u.family, u.index, u.seed);
        let g = got
            .entry((u.family.clone(), u.seed, u.index))
            .or_insert_with(|| Gathered {
                first: TrialResult {
                    runs: Vec::new(),
                    ..u.result.clone()
                },
                from: path.to_path_buf(),
                runs: BTreeMap::new(),
            });
        if facts(&g.first) != facts(&u.result) {
            return Err(format!(
                "{at} differs between {} and {} (its μ, sensor, holdability or oracle \
                 force): shards of different builds",
                g.from.display(),
                path.display()
            ));
        }
        for &(name, a, b) in &cols {
            let runs = u.result.runs[a..b].to_vec();
            if g.runs.insert(name.to_string(), runs).is_some() {
                return Err(format!(
                    "{}: {at} is in more than one shard (its runs of {name})",
                    path.display()
                ));
            }
        }
    }
    Ok(())
}

/// Every unit's result in the order of the run `opts` (its controllers those of `key`),
/// from `got`; or the first unit, or controller's runs of one, that no file gave, or a
/// unit that is not the run's.
fn assemble(opts: &BenchOptions, key: &Key, mut got: Units) -> Result<Vec<TrialResult>, String> {
    let total = opts.trials * opts.seeds.len() * opts.families.len();
    let mut results = Vec::new();
    for u in units(opts) {
        let at = format!("{} trial {} of seed {}", u.family, u.index, u.seed);
        let id = (u.family.to_string(), u.seed, u.index);
        let mut g = got
            .remove(&id)
            .ok_or_else(|| format!("{at} is in no shard (unit {} of {total})", u.number))?;
        let mut r = g.first;
        for s in &key.sweeps {
            let runs = g.runs.remove(&s.controller).ok_or_else(|| {
                format!(
                    "{at} is in no shard with runs of {} (unit {})",
                    s.controller, u.number
                )
            })?;
            r.runs.extend(runs);
        }
        results.push(r);
    }
    if let Some(((f, s, i), _)) = got.into_iter().next() {
        return Err(format!(
            "{f} trial {i} of seed {s} is not a unit of this run"
        ));
    }
    Ok(results)
}

/// Reads the shard files `paths` of one run, or of runs that differ in their seeds or
/// their controllers alone, and returns the options of the run over every seed and every
/// controller they name (each once, in the order the files first name it; writing to
/// `out`) and every unit's result in that run's order; or what is wrong with them: a file
/// that cannot be read, keys that differ in more than their seeds, their controllers and
/// the controllers' defaults (labels, which the merge takes from this build), a
/// controller with different grids, a trial whose facts differ between files, a unit or a
/// controller's runs of it missing, or given twice.
pub fn merge(paths: &[PathBuf], out: &Path) -> Result<(BenchOptions, Vec<TrialResult>), String> {
    let mut key: Option<(Key, &Path)> = None;
    let mut got = Units::new();
    for path in paths {
        let file = read(path)?;
        match &mut key {
            Some((k, first)) => pool_key(k, &file.key, first, path)?,
            None => key = Some((file.key.clone(), path)),
        }
        gather(&mut got, file, path)?;
    }
    let (key, _) = key.ok_or("no shard files given")?;
    let opts = options_of(&key, out)?;
    let results = assemble(&opts, &key, got)?;
    Ok((opts, results))
}
