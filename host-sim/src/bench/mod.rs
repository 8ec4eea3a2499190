//! `host-sim bench`: every controller, swept over its knob, on random trials of scene
//! families, against the oracle force; drop rates with Wilson intervals, force over the
//! oracle, Pareto plots.
//!
//! - [`families`]: the trial generators and their ranges;
//! - [`oracle`]: the least force that holds each tick's true load;
//! - [`sweep`]: the controllers' knobs, one trial's runs, the summary rows;
//! - [`report`]: text tables and `bench.json`; [`plot`]: the Pareto plots.
//!
//! Trials run in parallel (rayon), each run without per-tick samples (unless `--trace`),
//! softgrip on the direct in-memory link by default.

pub mod families;
pub mod oracle;
pub mod plot;
pub mod report;
pub mod sweep;

use crate::args::LinkName;
use crate::sim::controllers::{ControllerChoice, LinkKind};
use crate::sim::run::{self, RunOptions};
use crate::CliError;
use clap::Args;
use indicatif::ProgressBar;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use sweep::{Row, Sweep, TrialResult, SWEEPS};

/// Arguments of `host-sim bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// A family (lift-hold, shake, twist, mu-mismatch, faults) or all.
    #[arg(long, default_value = "all")]
    pub family: String,
    /// Trials per family.
    #[arg(long, default_value_t = 200)]
    pub trials: usize,
    /// Seed of the trials.
    #[arg(long, default_value_t = 17)]
    pub seed: u64,
    /// A controller (softgrip, softgrip-table, constant, coulomb, box, fixed-torsion,
    /// slip-servo) or all; softgrip-ellipse is softgrip in the default mode, which bench
    /// runs as `softgrip`.
    #[arg(long, value_enum, default_value = "all")]
    pub controller: ControllerChoice,
    /// Output directory (bench.json, trials-FAMILY.csv, pareto-FAMILY.svg/.png, trace/).
    #[arg(long, default_value = "bench-out")]
    pub out: PathBuf,
    /// softgrip's link: direct (in memory, on the calling thread) or pty (alias
    /// inprocess; then a sample of trials also runs over the pseudo-terminal and must
    /// give identical results). qemu and serial are `simulate`'s only.
    #[arg(long, value_enum, default_value = "direct")]
    pub link: LinkName,
    /// Keep and write every run's per-tick samples (CSV under OUT/trace/FAMILY/).
    #[arg(long)]
    pub trace: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// A finger file (`host-sim calibrate --out`'s, or a scene): every trial's finger and
    /// the μ every controller believes (a scene's [controller] mu if set); default the
    /// shipped scenes' finger. The limit-surface finger only.
    #[arg(long)]
    pub finger: Option<PathBuf>,
}

/// The finger of `--finger`, or the default.
fn bench_finger(args: &BenchArgs) -> Result<families::BenchFinger, CliError> {
    let Some(path) = &args.finger else {
        return Ok(families::BenchFinger::default());
    };
    let file = crate::finger_file::FingerFile::load(path, "--finger")?;
    let g = &file.finger;
    if g.model != crate::sim::finger::FingerModel::Fls {
        return Err(CliError::Usage(format!(
            "--finger: {}: bench runs the limit-surface finger (model = \"fls\")",
            path.display()
        )));
    }
    let finger = families::BenchFinger {
        shape: g.shape,
        k: g.k,
        mu: file.believed_mu(),
        c: g.c,
        gamma: g.gamma,
        half_length_m: g.half_length_m,
    };
    // A finger no scene accepts is refused here, naming its key, not as a failed trial.
    let text = families::trial_on(&finger, families::NAMES[0], 0, 0).map(|t| t.text);
    if text.is_none() {
        let why = match families::probe(&finger) {
            Err(e) => e,
            Ok(()) => "no trial can be built on it".into(),
        };
        return Err(CliError::Usage(format!(
            "--finger: {}: {why}",
            path.display()
        )));
    }
    Ok(finger)
}

/// Trials per family that `--link pty` also runs over the pty and compares.
pub const PTY_SAMPLE: usize = 3;

/// The families and sweeps an argument list selects.
pub fn selection(args: &BenchArgs) -> Result<(Vec<&'static str>, Vec<Sweep>), CliError> {
    let families: Vec<&'static str> = if args.family == "all" {
        families::NAMES.to_vec()
    } else {
        vec![*families::NAMES
            .iter()
            .find(|n| **n == args.family)
            .ok_or_else(|| {
                CliError::Usage(format!(
                    "--family: unknown family \"{}\", expected all or one of {}",
                    args.family,
                    families::NAMES.join(", ")
                ))
            })?]
    };
    let sweeps: Vec<Sweep> = match args.controller {
        ControllerChoice::All => SWEEPS.to_vec(),
        ControllerChoice::One(kind) => vec![*SWEEPS
            .iter()
            .find(|s| s.controller == kind)
            .ok_or_else(|| {
                let names: Vec<&str> = SWEEPS.iter().map(|s| s.controller.name()).collect();
                CliError::Usage(format!(
                    "--controller: bench has no sweep of \"{}\", expected all or one of {}",
                    kind.name(),
                    names.join(", ")
                ))
            })?],
    };
    Ok((families, sweeps))
}

/// Runs the trials `0..trials` of `family`, in parallel, in index order.
#[allow(clippy::too_many_arguments)]
pub fn run_family(
    finger: &families::BenchFinger,
    family: &str,
    seed: u64,
    trials: usize,
    sweeps: &[Sweep],
    link: &LinkKind,
    trace: Option<&Path>,
    bar: &ProgressBar,
) -> Result<Vec<TrialResult>, String> {
    let first = families::trial_on(finger, family, seed, 0).ok_or("no such family")?;
    // Every trial of a family has the same finger and force range, so one ground truth
    // serves them all (each trial sets its own true μ).
    let truth = run::build_truth(&first.scene)?;
    (0..trials)
        .into_par_iter()
        .map(|i| {
            let t = families::trial_on(finger, family, seed, i)
                .ok_or_else(|| format!("{family}: trial {i} could not be built"))?;
            let r = sweep::run_trial(&t, &truth, sweeps, link, trace);
            bar.inc(1);
            r
        })
        .collect()
}

/// Runs the first [`PTY_SAMPLE`] trials of `family` with softgrip (both modes, default
/// knob) over the pty and over the direct link, and checks that the summaries agree.
fn check_pty(finger: &families::BenchFinger, family: &str, seed: u64) -> Result<(), String> {
    for i in 0..PTY_SAMPLE {
        let t = families::trial_on(finger, family, seed, i).ok_or("no such family")?;
        for c in ["softgrip", "softgrip-table"] {
            let opts = RunOptions {
                skip_samples: true,
                truth: None,
                untimed: true,
            };
            let d = run::run_with(&t.scene, c, &LinkKind::Direct, None, opts)?.summary;
            let p = run::run_with(&t.scene, c, &LinkKind::InProcess, None, opts)?.summary;
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

/// `host-sim bench`.
pub fn run_cmd(args: &BenchArgs) -> Result<(), CliError> {
    let (families, sweeps) = selection(args)?;
    let finger = bench_finger(args)?;
    if args.trials == 0 {
        return Err(CliError::Usage("--trials: must be at least 1".into()));
    }
    let pty = match args.link {
        LinkName::Direct => false,
        LinkName::Pty => true,
        other @ (LinkName::Qemu | LinkName::Serial) => {
            return Err(CliError::Usage(format!(
                "--link {}: bench runs softgrip on the direct link, and over the pty as a \
                 check; expected direct or pty (the firmware's links are simulate's)",
                other.name()
            )))
        }
    };
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", args.out.display())))?;
    let bar = crate::progress::bar((args.trials * families.len()) as u64, "trials", args.quiet);
    let mut all: Vec<Row> = Vec::new();
    let mut dominance = Vec::new();
    for family in &families {
        bar.set_message(family.to_string());
        let trace = if args.trace {
            let dir = args.out.join("trace").join(family);
            std::fs::create_dir_all(&dir)
                .map_err(|e| CliError::Failed(format!("--out: {}: {e}", dir.display())))?;
            Some(dir)
        } else {
            None
        };
        let results = run_family(
            &finger,
            family,
            args.seed,
            args.trials,
            &sweeps,
            &LinkKind::Direct,
            trace.as_deref(),
            &bar,
        )
        .map_err(CliError::Failed)?;
        if pty {
            check_pty(&finger, family, args.seed).map_err(CliError::Failed)?;
        }
        report::write_trials_csv(
            &finger,
            &args.out.join(format!("trials-{family}.csv")),
            family,
            args.seed,
            &sweeps,
            &results,
        )
        .map_err(|e| CliError::Failed(format!("--out: {e}")))?;
        let rows = sweep::rows(family, &sweeps, &results);
        let check = report::dominance(family, &rows);
        bar.suspend(|| {
            println!("{}", report::family_table(family, &rows));
            println!("{}\n", report::dominance_line(&check));
        });
        dominance.push(check);
        plot::write_pareto(&args.out, family, &rows).map_err(CliError::Failed)?;
        all.extend(rows);
    }
    bar.finish_and_clear();
    if pty {
        println!(
            "pty check: the first {PTY_SAMPLE} trials of each family gave identical results \
             over the pty and the direct link (softgrip, both modes)"
        );
    }
    report::write_json(
        &args.out.join("bench.json"),
        args.seed,
        args.trials,
        args.link.name(),
        &all,
        &dominance,
    )
    .map_err(|e| CliError::Failed(format!("--out: {e}")))?;
    println!("wrote {}", args.out.display());
    Ok(())
}
