//! `host-sim bench`: every controller, swept over its knob, on random trials of scene
//! families, against the oracle force; drop rates with Wilson intervals, force over the
//! oracle, Pareto plots.
//!
//! - [`families`]: the trial generators and their ranges;
//! - [`oracle`]: the least force that holds each tick's true load;
//! - [`sweep`]: the controllers' knobs, one trial's runs, the summary rows;
//! - [`report`]: text tables and `bench.json`; [`plot`]: the Pareto plots.
//!
//! Trials run in parallel (rayon), each run without per-tick samples (unless asked for
//! traces), softgrip on the direct in-memory link. [`run`] is the whole bench on plain
//! options ([`BenchOptions`]); the command `host-sim bench` (`cmd::bench`) parses its
//! arguments into them.

pub mod families;
pub mod lab;
pub mod onset_table;
pub mod oracle;
pub mod plot;
pub mod report;
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
use std::fmt;
use std::path::{Path, PathBuf};
use sweep::{Row, Sweep, TrialResult};
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
    /// Trials per family (at least 1).
    pub trials: usize,
    /// Seed of the trials.
    pub seed: u64,
    /// softgrip's link.
    pub link: BenchLink,
    /// Output directory: `bench.json`, `trials-FAMILY.csv`, `pareto-FAMILY.svg/.png`,
    /// `trace/`.
    pub out: PathBuf,
    /// Keep and write every run's per-tick samples (CSV under `OUT/trace/FAMILY/`).
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

/// Runs the bench `opts` describes and writes its files. `show` gets what the terminal
/// shows, as it comes, the progress bar out of the way: each family's table and
/// dominance line as the family finishes, and the pty check's outcome.
pub fn run(opts: &BenchOptions, mut show: impl FnMut(&str)) -> Result<(), BenchError> {
    let write_err =
        |p: &Path, e: std::io::Error| BenchError::Write(format!("{}: {e}", p.display()));
    std::fs::create_dir_all(&opts.out).map_err(|e| write_err(&opts.out, e))?;
    let total = (opts.trials * opts.families.len()) as u64;
    let bar = crate::progress::bar(total, "trials", opts.quiet);
    let mut all: Vec<Row> = Vec::new();
    let mut dominance = Vec::new();
    for family in &opts.families {
        bar.set_message(family.to_string());
        let rows = bench_family(opts, family, &bar)?;
        let check = report::dominance(family, &rows);
        let text = format!(
            "{}\n{}\n\n",
            report::family_table(family, &rows),
            report::dominance_line(&check)
        );
        bar.suspend(|| show(&text));
        dominance.push(check);
        plot::write_pareto(&opts.out, family, &rows).map_err(BenchError::Run)?;
        all.extend(rows);
    }
    bar.finish_and_clear();
    if opts.link == BenchLink::Pty {
        show(&format!(
            "pty check: the first {PTY_SAMPLE} trials of each family gave identical results \
             over the pty and the direct link (softgrip, both modes)\n"
        ));
    }
    report::write_json(
        &opts.out.join("bench.json"),
        opts.seed,
        opts.trials,
        opts.link.name(),
        &all,
        &dominance,
    )
    .map_err(|e| BenchError::Write(e.to_string()))
}

/// The trials of one family: run (and traced, and checked over the pty, as `opts` asks),
/// written to `trials-FAMILY.csv`, and summed up in the summary rows.
fn bench_family(
    opts: &BenchOptions,
    family: &str,
    bar: &ProgressBar,
) -> Result<Vec<Row>, BenchError> {
    let trace = if opts.trace {
        let dir = opts.out.join("trace").join(family);
        std::fs::create_dir_all(&dir)
            .map_err(|e| BenchError::Write(format!("{}: {e}", dir.display())))?;
        Some(dir)
    } else {
        None
    };
    let results = run_family(
        &opts.source,
        &opts.ranges,
        family,
        opts.seed,
        opts.trials,
        &opts.sweeps,
        &LinkKind::Direct,
        trace.as_deref(),
        bar,
    )
    .map_err(BenchError::Run)?;
    if opts.link == BenchLink::Pty {
        check_pty(&opts.source, &opts.ranges, family, opts.seed).map_err(BenchError::Run)?;
    }
    report::write_trials_csv(
        &opts.out.join(format!("trials-{family}.csv")),
        &opts.sweeps,
        &results,
    )
    .map_err(|e| BenchError::Write(e.to_string()))?;
    Ok(sweep::rows(family, &opts.sweeps, &results))
}

/// Runs the trials `0..trials` of `family`, in parallel, in index order: each is drawn
/// (its finger measured and every controller calibrated) and run against every sweep.
#[allow(clippy::too_many_arguments)]
pub fn run_family(
    source: &FingerSource,
    ranges: &Ranges,
    family: &str,
    seed: u64,
    trials: usize,
    sweeps: &[Sweep],
    link: &LinkKind,
    trace: Option<&Path>,
    bar: &ProgressBar,
) -> Result<Vec<TrialResult>, String> {
    (0..trials)
        .into_par_iter()
        .map(|i| {
            let t = families::trial_on(source, ranges, family, seed, i)?;
            let r = sweep::run_trial(&t, sweeps, link, trace);
            bar.inc(1);
            r
        })
        .collect()
}

/// Runs the first [`PTY_SAMPLE`] trials of `family` with softgrip (both modes, default
/// knob) over the pty and over the direct link, and checks that the summaries agree.
fn check_pty(
    source: &FingerSource,
    ranges: &Ranges,
    family: &str,
    seed: u64,
) -> Result<(), String> {
    for i in 0..PTY_SAMPLE {
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
