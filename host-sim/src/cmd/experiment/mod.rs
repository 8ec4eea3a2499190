//! `host-sim experiment`: the lab's experiments on a plant (docs/experiments.md). Writes
//! the CSV a lab would record (the formats `host-sim calibrate` reads) and an SVG plot of
//! it into `--out`.

mod finger;
mod margins;
mod plot;

use crate::args::shape_parser;
use crate::experiment::protocol::{self, DEFAULT_RATIOS_M};
use crate::experiment::{FlsRig, Noise, Protocol, Rig};
use crate::input::short_num;
use crate::CliError;
use clap::{Args, ValueEnum};
use softgrip::controller::FingerShape;
use softgrip_calibrate::lab_csv::{write_indentation_on, write_slip_on, RigRecord};
use std::path::{Path, PathBuf};

/// Which experiment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Kind {
    /// Half-width against normal force (indentation.csv).
    Indentation,
    /// Tangential-force ramps until gross slip (slip.csv).
    Slip,
    /// Moment ramps until gross slip (torsion.csv).
    Torsion,
    /// Ramps along fixed m_n/f_t ratios (combined.csv).
    Combined,
    /// indentation.csv, and slip.csv with the onsets of all three ramps.
    All,
    /// Load cycles below the onset, at one normal force: the slide and turn per cycle
    /// (cyclic.csv; not part of all).
    Cyclic,
    /// Sustained loads below the onset, at one normal force: the creep over each hold
    /// (hold.csv; not part of all).
    Hold,
}

/// The plant the experiments run on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Plant {
    /// The exact limit surface of softgrip's core with a = c·N^γ.
    Fls,
    /// The physical brush finger (elastic foundation, stick-slip bristles; docs/
    /// brush-finger.md): needs --finger with a scene whose finger table has model = "brush".
    Brush,
}

/// The finger as flags (when no `--finger` file is given).
#[derive(Debug, Clone, Args)]
pub struct FingerArgs {
    /// A scene or finger TOML whose finger table (and [effect.skewed_pressure] if its
    /// effects list it) describe the finger; excludes the flags below.
    #[arg(long, conflicts_with_all = ["shape", "k", "mu", "c", "gamma", "half_length", "skew", "alpha", "locus"])]
    pub finger: Option<PathBuf>,
    /// Patch shape.
    #[arg(long, value_parser = shape_parser())]
    pub shape: Option<FingerShape>,
    // host-sim/tests/help_figures.rs::experiments_stated_finger_defaults_are_its_defaults
    /// Pressure exponent k >= 1 [default: 2].
    #[arg(long)]
    pub k: Option<f64>,
    // host-sim/tests/help_figures.rs::experiments_stated_finger_defaults_are_its_defaults
    /// Friction coefficient [default: 0.8].
    #[arg(long)]
    pub mu: Option<f64>,
    // host-sim/tests/help_figures.rs::experiments_stated_finger_defaults_are_its_defaults
    /// c in a = c·N^γ [m/N^γ] [default: 2.5e-3].
    #[arg(long)]
    pub c: Option<f64>,
    // host-sim/tests/help_figures.rs::experiments_stated_finger_defaults_are_its_defaults
    /// γ in [0, 1/2] [default: 0.5].
    #[arg(long)]
    pub gamma: Option<f64>,
    // host-sim/tests/help_figures.rs::experiments_stated_finger_defaults_are_its_defaults
    /// Half-length l of the rectangular patch in metres [default: 0.01].
    #[arg(long)]
    pub half_length: Option<f64>,
    /// Skew of the pressure peak Δ/a in [0, 1) [default: 0, none].
    #[arg(long)]
    pub skew: Option<f64>,
    // host-sim/tests/help_figures.rs::experiments_stated_finger_defaults_are_its_defaults
    /// Rate α of the skew [default: 1.1].
    #[arg(long)]
    pub alpha: Option<f64>,
    /// Locus h/a of the skew [default: Δ/2 on the rectangle, 0 on the disc].
    #[arg(long)]
    pub locus: Option<f64>,
}

/// Arguments of `host-sim experiment`.
#[derive(Debug, Args)]
pub struct ExperimentArgs {
    /// The experiment.
    #[arg(value_enum)]
    kind: Kind,
    /// The plant.
    #[arg(long, value_enum, default_value_t = Plant::Fls)]
    plant: Plant,
    /// The finger.
    #[command(flatten)]
    finger: FingerArgs,
    /// Normal forces [N], comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "0.5,1,2,4,8")]
    forces: Vec<f64>,
    /// Measurements per force (and per ratio).
    #[arg(long, default_value_t = 2)]
    repeats: usize,
    /// Ratios m_n/f_t [m] of the combined ramps, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = DEFAULT_RATIOS_M)]
    ratios: Vec<f64>,
    // host-sim/tests/calibrate_recovery.rs records its rows with this relative noise.
    /// Relative sensor noise (standard deviation; 0.02 is 2 %) on every recorded value.
    #[arg(long, default_value_t = 0.0)]
    noise: f64,
    /// Additive noise of the force channels [N] (standard deviation).
    #[arg(long, default_value_t = 0.0)]
    noise_force: f64,
    /// Additive noise of the moment channel [N·m] (standard deviation).
    #[arg(long, default_value_t = 0.0)]
    noise_moment: f64,
    /// Additive noise of the half-width [m] (standard deviation).
    #[arg(long, default_value_t = 0.0)]
    noise_width: f64,
    /// Seed of the noise.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Output directory (created).
    #[arg(long)]
    out: PathBuf,
    /// The margin protocols' settings.
    #[command(flatten)]
    margins: margins::MarginArgs,
}

fn usage(msg: impl std::fmt::Display) -> CliError {
    CliError::Usage(msg.to_string())
}

fn check_args(args: &ExperimentArgs) -> Result<(), CliError> {
    let bad = |flag: &str, v: f64, want: &str| {
        usage(format!("--{flag}: {} must be {want}", short_num(v)))
    };
    if args.forces.is_empty() {
        return Err(usage("--forces: give at least one force"));
    }
    if let Some(&n) = args.forces.iter().find(|n| !(**n > 0.0 && n.is_finite())) {
        return Err(bad("forces", n, "a finite force > 0 [N]"));
    }
    if let Some(&r) = args.ratios.iter().find(|r| !(**r > 0.0 && r.is_finite())) {
        return Err(bad("ratios", r, "a finite ratio > 0 [m]"));
    }
    if !(1..=10_000).contains(&args.repeats) {
        return Err(usage(format!(
            "--repeats: {} must be 1 to 10000",
            args.repeats
        )));
    }
    for (flag, v) in [
        ("noise", args.noise),
        ("noise-force", args.noise_force),
        ("noise-moment", args.noise_moment),
        ("noise-width", args.noise_width),
    ] {
        if !(v >= 0.0 && v.is_finite()) {
            return Err(bad(flag, v, "a finite number >= 0"));
        }
    }
    if args.noise >= 0.5 {
        return Err(bad("noise", args.noise, "below 0.5 (a relative deviation)"));
    }
    Ok(())
}

fn write(dir: &Path, name: &str, text: &str) -> Result<PathBuf, CliError> {
    let path = dir.join(name);
    std::fs::write(&path, text)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", path.display())))?;
    Ok(path)
}

/// What every experiment does before its rows: creates `--out`, and gives the noise the
/// rows are recorded with.
fn start(args: &ExperimentArgs) -> Result<Noise, CliError> {
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", args.out.display())))?;
    Ok(Noise::new(
        args.noise,
        args.noise_force,
        args.noise_moment,
        args.noise_width,
        args.seed,
    ))
}

/// Runs the experiment.
pub fn run(args: &ExperimentArgs) -> Result<(), CliError> {
    check_args(args)?;
    let spec = finger::spec(&args.finger)?;
    if matches!(args.kind, Kind::Cyclic | Kind::Hold) {
        return margins::run(args, spec);
    }
    let (lo, hi) = args
        .forces
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &n| (l.min(n), h.max(n)));
    let rig: Box<dyn Rig> = match args.plant {
        Plant::Fls => {
            Box::new(FlsRig::new(spec, lo, hi).map_err(|e| usage(format!("finger: {e}")))?)
        }
        Plant::Brush => Box::new(finger::brush(&args.finger)?),
    };
    let mut noise = start(args)?;
    let (f, r, out) = (&args.forces, args.repeats, &args.out);
    let mut written = Vec::new();
    if matches!(args.kind, Kind::Indentation | Kind::All) {
        let rows = protocol::indentation(rig.as_ref(), f, r, &mut noise);
        let text = write_indentation_on(&RigRecord::of(spec.shape, spec.half_length_m), &rows);
        written.push(write(out, "indentation.csv", &text)?);
        written.push(plot::indentation(&out.join("indentation.svg"), &rows)?);
    }
    let kinds: &[(Protocol, &str)] = &[
        (Protocol::Slip, "slip"),
        (Protocol::Torsion, "torsion"),
        (Protocol::Combined(args.ratios.clone()), "combined"),
    ];
    let chosen: Vec<&(Protocol, &str)> = match args.kind {
        Kind::Indentation | Kind::Cyclic | Kind::Hold => vec![],
        Kind::Slip => vec![&kinds[0]],
        Kind::Torsion => vec![&kinds[1]],
        Kind::Combined => vec![&kinds[2]],
        Kind::All => kinds.iter().collect(),
    };
    if !chosen.is_empty() {
        let mut rows = Vec::new();
        for (p, _) in &chosen {
            rows.extend(protocol::onsets(rig.as_ref(), p, f, r, &mut noise));
        }
        let name = if args.kind == Kind::All {
            "slip"
        } else {
            chosen[0].1
        };
        let text = write_slip_on(&RigRecord::of(spec.shape, spec.half_length_m), &rows);
        written.push(write(out, &format!("{name}.csv"), &text)?);
        written.push(plot::onsets(&out.join(format!("{name}.svg")), &rows)?);
    }
    for p in written {
        println!("wrote {}", p.display());
    }
    Ok(())
}
