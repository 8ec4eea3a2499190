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
use softgrip::controller::{ControllerConfig, Mode};
use std::path::PathBuf;

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
    /// A controller (softgrip-ellipse, softgrip-table, constant, coulomb, box,
    /// fixed-torsion, slip-servo) or all; softgrip is softgrip in the default mode, which
    /// bench runs as that mode's controller.
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
    /// The plant the trials run on: brush (the brush finger, a physical plant softgrip
    /// does not model, drawn per trial) or fls (softgrip's own limit surface, a finger
    /// drawn per trial).
    #[arg(long, value_enum, default_value = "brush")]
    pub plant: PlantName,
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
    match kind.softgrip_mode(ControllerConfig::DEFAULT.mode) {
        Some(Mode::Ellipse) => ControllerKind::SoftgripEllipse,
        Some(Mode::Table) => ControllerKind::SoftgripTable,
        None => kind,
    }
}

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
            .find(|s| s.controller == default_mode(kind))
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

/// The options `args` ask for, or the first bad argument.
pub fn options(args: &BenchArgs) -> Result<BenchOptions, CliError> {
    let (families, sweeps) = selection(args)?;
    let source = finger_source(args)?;
    if args.trials == 0 {
        return Err(CliError::Usage("--trials: must be at least 1".into()));
    }
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
        seed: args.seed,
        link,
        out: args.out.clone(),
        trace: args.trace,
        quiet: args.quiet,
    })
}

/// `host-sim bench`.
pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    let opts = options(args)?;
    bench::run(&opts, |text| print!("{text}")).map_err(|e| match e {
        BenchError::Write(e) => CliError::Failed(format!("--out: {e}")),
        BenchError::Run(e) => CliError::Failed(e),
    })?;
    println!("wrote {}", args.out.display());
    Ok(())
}
