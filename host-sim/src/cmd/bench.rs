//! `host-sim bench`: its arguments, parsed into [`crate::bench::BenchOptions`] for
//! [`crate::bench::run`].

use crate::args::LinkName;
use crate::bench::families::{self, Ranges};
use crate::bench::sweep::{Sweep, SWEEPS};
use crate::bench::trial_finger::{BenchPlant, FingerSource};
use crate::bench::{self, BenchError, BenchLink, BenchOptions};
use crate::finger_file::FingerFile;
use crate::sim::controllers::{ControllerChoice, ControllerKind};
use crate::CliError;
use clap::Args;
use softgrip::controller::ControllerConfig;
use std::path::PathBuf;

/// Arguments of `host-sim bench`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct BenchArgs {
    /// `bench merge`: the files of a run's shards into the run's outputs; `bench
    /// select`: some controllers' runs out of shard files.
    #[command(subcommand)]
    pub command: Option<ShardCommand>,
    /// Families (lift-hold, shake, twist, mu-mismatch, faults), comma-separated, or all.
    #[arg(long, value_delimiter = ',', default_value = "all")]
    pub family: Vec<String>,
    /// Trials per family and seed.
    #[arg(long, default_value_t = DEFAULT_TRIALS)]
    pub trials: usize,
    /// Seeds of the trials, comma-separated: the trials of every seed are pooled, and
    /// bench.json keeps each seed's rows beside the pooled ones (alias --seed).
    #[arg(long, alias = "seed", value_delimiter = ',', default_value = "17")]
    pub seeds: Vec<u64>,
    /// Run only this share I/N of the work (a unit is one trial of one family under one
    /// seed; shard I takes the units numbered I modulo N) and write
    /// OUT/shard-I-of-N.json; `bench merge` turns the shards into the run's outputs.
    #[arg(long)]
    pub shard: Option<String>,
    /// Controllers (softgrip-ellipse, softgrip-table, constant, coulomb, box,
    /// fixed-torsion, slip-servo), comma-separated, or all; softgrip is softgrip in the
    /// default mode, which bench runs as that mode's controller.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "all")]
    pub controller: Vec<ControllerChoice>,
    /// Output directory (bench.json, trials-FAMILY.csv, pareto-FAMILY.svg/.png, trace/).
    #[arg(long, default_value = "bench-out")]
    pub out: PathBuf,
    /// softgrip's link: direct (in memory, on the calling thread) or pty (alias
    /// inprocess; then a sample of trials also runs over the pseudo-terminal and must
    /// give identical results). qemu and serial are `simulate`'s only.
    #[arg(long, value_enum, default_value = "direct")]
    pub link: LinkName,
    /// Keep and write every run's per-tick samples (CSV under OUT/trace/FAMILY/SEED/,
    /// beside each trial's scene as NNNN-scene.toml, which `simulate` replays).
    #[arg(long)]
    pub trace: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// The plant the trials run on: brush (the brush finger, a physical plant softgrip
    /// does not model, drawn per trial) or fls (softgrip's own limit surface, a finger
    /// drawn per trial).
    #[arg(long, value_enum, default_value = "brush")]
    pub plant: PlantName,
    // The shakes' and mu's ranges are checked (the twists' share is drawn in
    // bench/families.rs) by host-sim/tests/help_figures.rs::the_hard_ranges_are_the_ones_bench_help_states
    /// The harder ranges: shakes of 6-15 Hz through 20-60 ms actuators, twists of
    /// 80-100 % of the capacity, a true mu 0.5-1.0 x the measured one.
    #[arg(long)]
    pub hard: bool,
    /// Tell the controllers the shake family's actuator (lag and slew); by default they
    /// are not told.
    #[arg(long)]
    pub tell_actuator: bool,
    /// A finger file (`host-sim calibrate --out`'s, or a scene): every trial runs on this
    /// limit-surface finger instead of a drawn one (the controllers still believe only
    /// what the lab measures of it). Implies --plant fls.
    #[arg(long)]
    pub finger: Option<PathBuf>,
}

/// `bench`'s subcommands, on the shard files of `--shard` and on written runs.
#[derive(Debug, clap::Subcommand)]
pub enum ShardCommand {
    /// Merges the shard files of one run (`bench --shard I/N`) into the files the whole
    /// run writes, bit for bit: bench.json, trials-FAMILY.csv, pareto-FAMILY.svg/.png.
    /// Runs that differ in their seeds or their controllers alone are pooled into the run
    /// over all their seeds and controllers (in the order the files first name them);
    /// each controller's runs of a trial must come from one file, and every file from
    /// one build.
    Merge(MergeArgs),
    /// Writes shard files again, into --out under their own names, with only the runs
    /// of the given controllers: to pool the controllers a change left alone with a
    /// rerun of the one it changed (`bench merge`).
    Select(SelectArgs),
    /// Judges written runs again by this build's rule: rewrites each bench.json's
    /// default_choice and baseline_default_choices from its pooled rows, leaving every
    /// other byte as it was (a run judged before the rule changed).
    Rejudge(RejudgeArgs),
    /// Writes a run's summary (what it is published by: summary.json beside its
    /// bench.json, which every run also writes) from its bench.json and
    /// trials-mu-mismatch.csv. A run written before runs recorded their build needs
    /// --made-at.
    Summary(SummaryArgs),
    /// Reruns one seed of a summary's run with this build, each controller at its
    /// default only, and compares the summary's per_seed_defaults rows of that seed with
    /// the rerun's, bit for bit. If every row is equal, appends this build's provenance
    /// (with the seed and the rows compared) to the summary's provenance.reverified and
    /// rewrites it, every other byte as it was; otherwise writes nothing and names the
    /// first differing row and field. For a change meant to keep every output
    /// bit-identical: it shows that one seed reproduces, not the others.
    Reverify(ReverifyArgs),
}

/// Arguments of `host-sim bench reverify`.
#[derive(Debug, Args)]
pub struct ReverifyArgs {
    /// The run's summary.json (rewritten in place when its rows reproduce).
    pub summary: PathBuf,
    /// The seed to rerun: one of the run's.
    #[arg(long)]
    pub seed: u64,
    /// Run even when the sources differ from their commit; the entry then records
    /// dirty, which no published run accepts (for tests).
    #[arg(long)]
    pub allow_dirty: bool,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

/// Arguments of `host-sim bench summary`.
#[derive(Debug, Args)]
pub struct SummaryArgs {
    /// The run's output directory (its bench.json).
    pub dir: PathBuf,
    /// Where to write the summary (default: DIR/summary.json).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The commit an older run (one whose bench.json records no provenance) was made at,
    /// in the checkout of the current directory: refused unless that commit's constants
    /// are this build's.
    #[arg(long)]
    pub made_at: Option<String>,
}

/// Arguments of `host-sim bench rejudge`.
#[derive(Debug, Args)]
pub struct RejudgeArgs {
    /// The bench.json files.
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
}

/// Arguments of `host-sim bench select`.
#[derive(Debug, Args)]
pub struct SelectArgs {
    /// The controllers to keep, comma-separated (each must be in every file).
    #[arg(long, value_delimiter = ',', required = true)]
    pub controller: Vec<String>,
    /// Output directory (not the files' own).
    #[arg(long)]
    pub out: PathBuf,
    /// The shard files (shard-I-of-N.json).
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
}

/// Arguments of `host-sim bench merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Output directory.
    #[arg(long, default_value = "bench-out")]
    pub out: PathBuf,
    /// The shard files (shard-I-of-N.json), every shard of the run (or of each run
    /// pooled) once.
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
}

/// Trials per family and seed of the default run: sized to finish in 3 minutes on 2
/// cores (docs/bench.md gives the measured time).
pub const DEFAULT_TRIALS: usize = 12;

/// `--plant`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum PlantName {
    /// The brush finger.
    Brush,
    /// softgrip's limit surface.
    Fls,
}

/// The fingers' source: `--finger`'s, or drawn on `--plant`.
fn finger_source(args: &BenchArgs) -> Result<FingerSource, CliError> {
    let Some(path) = &args.finger else {
        return Ok(FingerSource::Drawn(match args.plant {
            PlantName::Brush => BenchPlant::Brush,
            PlantName::Fls => BenchPlant::Fls,
        }));
    };
    let file = FingerFile::load(path, "--finger")?;
    bench::finger_from_file(&file)
        .map(FingerSource::Fixed)
        .map_err(|why| CliError::Usage(format!("--finger: {}: {why}", path.display())))
}

/// `softgrip` is softgrip in the default configuration's mode, which bench runs as the
/// controller of that mode; any other kind is itself.
fn default_mode(kind: ControllerKind) -> ControllerKind {
    kind.softgrip_mode(ControllerConfig::DEFAULT.mode)
        .map_or(kind, ControllerKind::of_mode)
}

/// The families and sweeps an argument list selects.
pub fn selection(args: &BenchArgs) -> Result<(Vec<&'static str>, Vec<Sweep>), CliError> {
    let mut families: Vec<&'static str> = Vec::new();
    for name in &args.family {
        let add: Vec<&'static str> = if name == "all" {
            families::NAMES.to_vec()
        } else {
            vec![*families::NAMES.iter().find(|n| *n == name).ok_or_else(|| {
                CliError::Usage(format!(
                    "--family: unknown family \"{name}\", expected all or one of {}",
                    families::NAMES.join(", ")
                ))
            })?]
        };
        for f in add {
            if !families.contains(&f) {
                families.push(f);
            }
        }
    }
    if args.controller.contains(&ControllerChoice::All) {
        return Ok((families, SWEEPS.to_vec()));
    }
    let mut sweeps: Vec<Sweep> = Vec::new();
    for k in ControllerChoice::kinds(&args.controller)
        .into_iter()
        .map(default_mode)
    {
        let sweep = SWEEPS.iter().find(|s| s.controller == k).ok_or_else(|| {
            let names: Vec<&str> = SWEEPS.iter().map(|s| s.controller.name()).collect();
            CliError::Usage(format!(
                "--controller: bench has no sweep of \"{}\", expected all or one of {}",
                k.name(),
                names.join(", ")
            ))
        })?;
        if !sweeps.iter().any(|s| s.controller == k) {
            sweeps.push(*sweep);
        }
    }
    Ok((families, sweeps))
}

/// The options `args` ask for, or the first bad argument.
pub fn options(args: &BenchArgs) -> Result<BenchOptions, CliError> {
    let (families, sweeps) = selection(args)?;
    let source = finger_source(args)?;
    if args.trials == 0 {
        return Err(CliError::Usage("--trials: must be at least 1".into()));
    }
    let seeds = args.seeds.clone();
    let distinct: std::collections::BTreeSet<u64> = seeds.iter().copied().collect();
    if seeds.is_empty() || distinct.len() != seeds.len() {
        return Err(CliError::Usage(
            "--seeds: give one or more seeds, each once".into(),
        ));
    }
    let shard = args
        .shard
        .as_deref()
        .map(bench::shard::Shard::parse)
        .transpose()
        .map_err(|e| CliError::Usage(format!("--shard: {e}")))?;
    let link = match args.link {
        LinkName::Direct => BenchLink::Direct,
        LinkName::Pty => BenchLink::Pty,
        other @ (LinkName::Qemu | LinkName::Serial) => {
            return Err(CliError::Usage(format!(
                "--link {}: bench runs softgrip on the direct link, and over the pty as a \
                 check; expected direct or pty (the firmware's links are simulate's)",
                other.name()
            )))
        }
    };
    Ok(BenchOptions {
        families,
        sweeps,
        source,
        ranges: Ranges {
            hard: args.hard,
            tell_actuator: args.tell_actuator,
        },
        trials: args.trials,
        seeds,
        shard,
        link,
        out: args.out.clone(),
        trace: args.trace,
        quiet: args.quiet,
    })
}

fn failed(e: BenchError) -> CliError {
    match e {
        BenchError::Write(e) => CliError::Failed(format!("--out: {e}")),
        BenchError::Run(e) => CliError::Failed(e),
    }
}

/// `host-sim bench` (and `bench merge`).
pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    match &args.command {
        Some(ShardCommand::Merge(m)) => return merge(m),
        Some(ShardCommand::Select(a)) => return select(a),
        Some(ShardCommand::Rejudge(a)) => return rejudge(a),
        Some(ShardCommand::Summary(a)) => return summary(a),
        Some(ShardCommand::Reverify(a)) => return reverify(a),
        None => {}
    }
    let opts = options(args)?;
    let start = std::time::Instant::now();
    bench::run(&opts, |text| print!("{text}")).map_err(failed)?;
    println!(
        "wrote {} ({:.0} s wall)",
        args.out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

/// `host-sim bench select`.
fn select(a: &SelectArgs) -> Result<(), CliError> {
    let names: Vec<&str> = a.controller.iter().map(String::as_str).collect();
    if let Some(n) = names
        .iter()
        .find(|n| !SWEEPS.iter().any(|s| s.controller.name() == **n))
    {
        let known: Vec<&str> = SWEEPS.iter().map(|s| s.controller.name()).collect();
        return Err(CliError::Usage(format!(
            "--controller: bench has no sweep of \"{n}\", expected one of {}",
            known.join(", ")
        )));
    }
    let written = bench::shard::select(&a.shards, &names, &a.out).map_err(CliError::Failed)?;
    for p in written {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// `host-sim bench rejudge`.
fn rejudge(a: &RejudgeArgs) -> Result<(), CliError> {
    for f in &a.files {
        let lines = bench::default_choice::rejudge(f).map_err(CliError::Failed)?;
        println!("{lines}\nwrote {}", f.display());
    }
    Ok(())
}

/// `host-sim bench summary`.
fn summary(a: &SummaryArgs) -> Result<(), CliError> {
    let made_at = match &a.made_at {
        Some(commit) => {
            let here = std::env::current_dir().map_err(|e| CliError::Failed(e.to_string()))?;
            Some(bench::summary::made_at(&here, commit).map_err(CliError::Failed)?)
        }
        None => None,
    };
    let value = bench::summary::summarize(&a.dir, made_at).map_err(CliError::Failed)?;
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| bench::summary::path_in(&a.dir));
    bench::summary::write(&out, &value).map_err(CliError::Failed)?;
    println!("wrote {}", out.display());
    Ok(())
}

/// `host-sim bench reverify`.
fn reverify(a: &ReverifyArgs) -> Result<(), CliError> {
    let here = std::env::current_dir().map_err(|e| CliError::Failed(e.to_string()))?;
    let start = std::time::Instant::now();
    let done = bench::reverify::reverify(&a.summary, a.seed, a.allow_dirty, &here, a.quiet)
        .map_err(CliError::Failed)?;
    println!(
        "seed {}: {} rows of per_seed_defaults equal, bit for bit ({:.0} s wall); appended \
         to provenance.reverified (commit {}, constants digest {})\nwrote {}",
        a.seed,
        done.rows_compared,
        start.elapsed().as_secs_f64(),
        done.entry["commit"].as_str().unwrap_or("?"),
        done.entry["constants_digest"].as_str().unwrap_or("?"),
        a.summary.display()
    );
    Ok(())
}

/// `host-sim bench merge`.
fn merge(m: &MergeArgs) -> Result<(), CliError> {
    let (opts, results) = bench::shard::merge(&m.shards, &m.out).map_err(CliError::Failed)?;
    std::fs::create_dir_all(&m.out)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", m.out.display())))?;
    let units = bench::shard::units(&opts);
    let groups = bench::group(&opts, &units, results);
    bench::write_outputs(&opts, &groups, |text| print!("{text}")).map_err(failed)?;
    println!("wrote {}", m.out.display());
    Ok(())
}
