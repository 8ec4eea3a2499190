//! `host-sim bench`: every controller, swept over its knob, on random trials of scene
//! families, against the oracle force; drop rates with Wilson intervals, force over the
//! oracle, Pareto plots.
//!
//! - [`families`]: the trial generators and their ranges; [`trial_finger`]: each trial's
//!   fingertip; [`lab`]: what every controller is told, from the lab's rows;
//! - [`oracle`]: the least force that holds each tick's true load ([`onset_table`] on
//!   the brush finger);
//! - [`sweep`]: the controllers' knobs and one trial's runs; [`stats`]: the summary rows
//!   (per seed and pooled);
//! - [`report`]: text tables, the dominance checks and `bench.json`; [`plot`]: the Pareto
//!   plots; [`shard`]: a share of the work units, and the merge of shards;
//! - [`summary`]: what a run is published by; [`reverify`]: one seed of a published run
//!   rerun on this build and compared with it.
//!
//! Trials run in parallel (rayon), each run without per-tick samples (unless asked for
//! traces), softgrip on the direct in-memory link. [`run`] is the whole bench on plain
//! options ([`BenchOptions`]); the command `host-sim bench` (`cmd::bench`) parses its
//! arguments into them. A run computes every work unit's [`TrialResult`] (a unit is one
//! trial of one family under one seed), then writes its files from those alone
//! ([`write_outputs`]): so a merge of shards, which has the same results, writes the same
//! bytes.

pub mod default_choice;
pub mod families;
pub mod lab;
pub mod onset_table;
pub mod oracle;
pub mod plot;
pub mod report;
pub mod reverify;
pub mod shard;
pub mod stats;
pub mod summary;
pub mod sweep;
pub mod trial_finger;

use crate::experiment::FingerSpec;
use crate::finger_file::FingerFile;
use crate::sim::controllers::{ControllerKind, LinkKind};
use crate::sim::finger::FingerModel;
use crate::sim::run::{self as sim_run, RunOptions};
use families::Ranges;
use indicatif::ProgressBar;
use rayon::prelude::*;
use stats::Row;
use std::fmt;
use std::path::{Path, PathBuf};
use sweep::{Sweep, TrialResult};
use trial_finger::FingerSource;

/// Trials per family that a pty check ([`BenchLink::Pty`]) also runs over the pty and
/// compares.
pub const PTY_SAMPLE: usize = 3;

/// softgrip's link in a bench run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BenchLink {
    /// In memory, on the calling thread.
    Direct,
    /// Direct, and a sample of trials ([`PTY_SAMPLE`] per family) also over the
    /// pseudo-terminal, which must give identical results.
    Pty,
}

impl BenchLink {
    /// The name `bench.json` records.
    pub fn name(self) -> &'static str {
        match self {
            BenchLink::Direct => "direct",
            BenchLink::Pty => "pty",
        }
    }
}

/// What a bench run does and where it writes.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// The families, in order (of [`families::NAMES`]).
    pub families: Vec<&'static str>,
    /// The controllers, each swept over its knob.
    pub sweeps: Vec<Sweep>,
    /// Where the trials' fingers come from (and so the plant).
    pub source: FingerSource,
    /// The families' ranges and what the controllers are told.
    pub ranges: Ranges,
    /// Trials per family and seed (at least 1).
    pub trials: usize,
    /// The seeds of the trials, pooled (at least one, each once).
    pub seeds: Vec<u64>,
    /// Run only this share of the work units and write it as a shard file.
    pub shard: Option<shard::Shard>,
    /// softgrip's link.
    pub link: BenchLink,
    /// Output directory: `bench.json`, `trials-FAMILY.csv`, `pareto-FAMILY.svg/.png`,
    /// `trace/`.
    pub out: PathBuf,
    /// Keep and write every run's per-tick samples (CSV under `OUT/trace/FAMILY/SEED/`,
    /// beside each trial's scene, which `simulate` replays).
    pub trace: bool,
    /// No progress bar.
    pub quiet: bool,
}

/// Why a bench run failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BenchError {
    /// A file or directory under the output directory could not be written (the path
    /// and the reason).
    Write(String),
    /// A trial could not be built or run, the pty check failed, or a plot failed.
    Run(String),
}

impl fmt::Display for BenchError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BenchError::Write(e) | BenchError::Run(e) => f.write_str(e),
        }
    }
}

impl std::error::Error for BenchError {}

/// The bench's finger from a finger file (`calibrate --out`'s, or a scene): the
/// limit-surface finger every trial then runs on (its shape, pressure exponent, μ and
/// contact law; the controllers still believe only what the lab measures of it); or why
/// no trial can run on it (the limit-surface finger only; a value out of range names its
/// key).
pub fn finger_from_file(file: &FingerFile) -> Result<FingerSpec, String> {
    let g = &file.finger;
    if g.model != FingerModel::Fls {
        return Err("bench runs the limit-surface finger (model = \"fls\")".into());
    }
    let spec = FingerSpec {
        shape: g.shape,
        k: g.k,
        mu: file.believed_mu(),
        c: g.c,
        gamma: g.gamma,
        half_length_m: g.half_length_m,
        skew: None,
    };
    // A finger no scene accepts is refused here, naming its key, not as a failed trial.
    families::trial_on(
        &FingerSource::Fixed(spec),
        &Ranges::default(),
        families::NAMES[0],
        0,
        0,
    )
    .map(|_| spec)
}

/// The trials of one family under one seed, in index order.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyResults {
    /// The family.
    pub family: &'static str,
    /// The seed.
    pub seed: u64,
    /// Trial `i`'s result at index `i`.
    pub results: Vec<TrialResult>,
}

/// Runs the bench `opts` describes and writes its files (or, with a shard, its shard
/// file). `show` gets what the terminal shows: each family's table and dominance lines,
/// and the pty check's outcome.
pub fn run(opts: &BenchOptions, mut show: impl FnMut(&str)) -> Result<(), BenchError> {
    std::fs::create_dir_all(&opts.out)
        .map_err(|e| BenchError::Write(format!("{}: {e}", opts.out.display())))?;
    let units = shard::units(opts);
    let mine: Vec<shard::Unit> = match opts.shard {
        Some(s) => units.into_iter().filter(|u| s.takes(u.number)).collect(),
        None => units,
    };
    let bar = crate::progress::bar(mine.len() as u64, "trials", opts.quiet);
    let done = run_units(opts, &mine, &bar)?;
    bar.finish_and_clear();
    if opts.link == BenchLink::Pty {
        show(&format!(
            "pty check: the first {PTY_SAMPLE} trials of each family and seed gave identical \
             results over the pty and the direct link (softgrip, both modes)\n"
        ));
    }
    match opts.shard {
        Some(s) => {
            let path = shard::write(opts, s, &mine, &done)?;
            show(&format!(
                "wrote shard {} ({} trials)\n",
                path.display(),
                mine.len()
            ));
            Ok(())
        }
        None => write_outputs(opts, &group(opts, &mine, done), show),
    }
}

/// The trace directory of each family of `opts` (`None`s without `--trace`).
fn trace_dirs(opts: &BenchOptions) -> Result<Vec<Option<PathBuf>>, BenchError> {
    opts.families
        .iter()
        .map(|family| {
            if !opts.trace {
                return Ok(None);
            }
            let dir = opts.out.join("trace").join(family);
            std::fs::create_dir_all(&dir)
                .map_err(|e| BenchError::Write(format!("{}: {e}", dir.display())))?;
            Ok(Some(dir))
        })
        .collect()
}

/// The trace folder of `seed` under its family's, made if need be: a trial's index is
/// unique only within its seed.
fn seed_trace_dir(family_dir: &Path, seed: u64) -> Result<PathBuf, String> {
    let dir = family_dir.join(seed.to_string());
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    Ok(dir)
}

/// Runs `units` (in parallel) and returns their results in the same order; with a pty
/// link, also checks the first [`PTY_SAMPLE`] trials of each family and seed among them.
fn run_units(
    opts: &BenchOptions,
    units: &[shard::Unit],
    bar: &ProgressBar,
) -> Result<Vec<TrialResult>, BenchError> {
    let dirs = trace_dirs(opts)?;
    let results = units
        .par_iter()
        .map(|u| {
            let fam = opts.families.iter().position(|f| *f == u.family);
            let dir = match fam.and_then(|i| dirs[i].as_deref()) {
                Some(d) => Some(seed_trace_dir(d, u.seed)?),
                None => None,
            };
            let t = families::trial_on(&opts.source, &opts.ranges, u.family, u.seed, u.index)?;
            let r = sweep::run_trial(&t, &opts.sweeps, &LinkKind::Direct, dir.as_deref());
            bar.inc(1);
            r
        })
        .collect::<Result<Vec<_>, String>>()
        .map_err(BenchError::Run)?;
    if opts.link == BenchLink::Pty {
        for u in units.iter().filter(|u| u.index < PTY_SAMPLE) {
            check_pty(&opts.source, &opts.ranges, u.family, u.seed, u.index)
                .map_err(BenchError::Run)?;
        }
    }
    Ok(results)
}

/// The results of `units` grouped by family and seed, in `opts`' order of both.
pub fn group(
    opts: &BenchOptions,
    units: &[shard::Unit],
    results: Vec<TrialResult>,
) -> Vec<FamilyResults> {
    let mut out: Vec<FamilyResults> = Vec::new();
    for (u, r) in units.iter().zip(results) {
        match out
            .iter_mut()
            .find(|g| g.family == u.family && g.seed == u.seed)
        {
            Some(g) => g.results.push(r),
            None => out.push(FamilyResults {
                family: u.family,
                seed: u.seed,
                results: vec![r],
            }),
        }
    }
    out.sort_by_key(|g| {
        let f = opts.families.iter().position(|x| *x == g.family);
        let s = opts.seeds.iter().position(|x| *x == g.seed);
        (f, s)
    });
    out
}

/// Writes a bench's files from its results: per family the pooled table and the
/// dominance lines (shown), `trials-FAMILY.csv` and the Pareto plots; then `bench.json`
/// with the pooled and the per-seed rows, and its `summary.json`
/// ([`summary`]).
pub fn write_outputs(
    opts: &BenchOptions,
    groups: &[FamilyResults],
    mut show: impl FnMut(&str),
) -> Result<(), BenchError> {
    let (mut pooled, mut per_seed, mut checks) = (Vec::new(), Vec::new(), Vec::new());
    let mut clairvoyant = Vec::new();
    for family in &opts.families {
        let mine: Vec<&FamilyResults> = groups.iter().filter(|g| g.family == *family).collect();
        let all: Vec<&TrialResult> = mine.iter().flat_map(|g| g.results.iter()).collect();
        let rows: Vec<Row> = stats::rows(family, None, &opts.sweeps, &all);
        for g in &mine {
            let results: Vec<&TrialResult> = g.results.iter().collect();
            per_seed.extend(stats::rows(family, Some(g.seed), &opts.sweeps, &results));
        }
        let check = report::dominance(family, &rows, report::DOMINANCE_MAX_DROP_RATE);
        let reference = stats::clairvoyant_constant(family, &opts.sweeps, &all);
        show(&format!(
            "{}\n{}\n{}{}",
            report::family_table(family, &rows),
            report::dominance_lines(&check),
            report::turn_line(family, &rows),
            reference.as_ref().map_or(String::new(), |c| format!(
                "{family}: a constant grip chosen per trial in advance (the least of the grid \
                 that holds it; a reference, not a controller) needs {:.3} x the oracle's force \
                 (median {:.3}) over the {} holdable trials\n",
                c.mean_force_over_oracle, c.median_force_over_oracle, c.trials
            ))
        ));
        clairvoyant.extend(reference);
        let by_seed: Vec<(u64, &[TrialResult])> = mine
            .iter()
            .map(|g| (g.seed, g.results.as_slice()))
            .collect();
        let csv = opts.out.join(format!("trials-{family}.csv"));
        report::write_trials_csv(&csv, &opts.sweeps, &by_seed)
            .map_err(|e| BenchError::Write(format!("{}: {e}", csv.display())))?;
        plot::write_pareto(&opts.out, family, &rows).map_err(BenchError::Run)?;
        checks.push(check);
        pooled.extend(rows);
    }
    let choice = default_choice::choose_on_rows(&pooled);
    if let Some(c) = &choice {
        show(&format!("{}\n", default_choice::lines(c)));
    }
    let baseline_choices = default_choice::baseline_choices_on_rows(&pooled);
    for c in &baseline_choices {
        show(&format!("{}\n", default_choice::baseline_line(c)));
    }
    let json = opts.out.join("bench.json");
    let here = std::env::current_dir().unwrap_or_else(|_| opts.out.clone());
    let parts = report::JsonParts {
        provenance: &crate::provenance::of_this_build(&here, summary::configuration()),
        key: &shard::Key::of(opts),
        rows: &pooled,
        per_seed: &per_seed,
        dominance: &checks,
        default_choice: choice.as_ref(),
        baseline_default_choices: &baseline_choices,
        clairvoyant_constant: &clairvoyant,
    };
    report::write_json(&json, &parts)
        .map_err(|e| BenchError::Write(format!("{}: {e}", json.display())))?;
    let summary = summary::summarize(&opts.out, None)
        .and_then(|v| summary::write(&summary::path_in(&opts.out), &v));
    summary.map_err(BenchError::Write)
}

/// Runs trial `i` of `family` under `seed` with softgrip (both modes, default knob) over
/// the pty and over the direct link, and checks that the summaries agree.
fn check_pty(
    source: &FingerSource,
    ranges: &Ranges,
    family: &str,
    seed: u64,
    i: usize,
) -> Result<(), String> {
    {
        let t = families::trial_on(source, ranges, family, seed, i)?;
        for c in [
            ControllerKind::SoftgripEllipse,
            ControllerKind::SoftgripTable,
        ] {
            let c = c.name();
            let opts = RunOptions {
                skip_samples: true,
                truth: Some(t.truth.as_ref()),
                untimed: true,
            };
            let d = sim_run::run_with(&t.scene, c, &LinkKind::Direct, None, opts)?.summary;
            let p = sim_run::run_with(&t.scene, c, &LinkKind::InProcess, None, opts)?.summary;
            let same = d.dropped == p.dropped
                && d.slip_events == p.slip_events
                && d.slip_distance_m.to_bits() == p.slip_distance_m.to_bits()
                && d.mean_normal_force_n.to_bits() == p.mean_normal_force_n.to_bits()
                && d.peak_normal_force_n.to_bits() == p.peak_normal_force_n.to_bits();
            if !same {
                return Err(format!(
                    "{family} trial {i}, {c}: the pty link and the direct link disagree \
                     (mean force {} against {})",
                    p.mean_normal_force_n, d.mean_normal_force_n
                ));
            }
        }
    }
    Ok(())
}

/// Runs the trials `0..trials` of `family` under `seed`, in parallel, in index order:
/// each is drawn (its finger measured and every controller calibrated) and run against
/// every sweep.
#[allow(clippy::too_many_arguments)]
pub fn run_family(
    source: &FingerSource,
    ranges: &Ranges,
    family: &str,
    seed: u64,
    trials: usize,
    sweeps: &[Sweep],
    link: &LinkKind,
    bar: &ProgressBar,
) -> Result<Vec<TrialResult>, String> {
    (0..trials)
        .into_par_iter()
        .map(|i| {
            let t = families::trial_on(source, ranges, family, seed, i)?;
            let r = sweep::run_trial(&t, sweeps, link, None);
            bar.inc(1);
            r
        })
        .collect()
}
