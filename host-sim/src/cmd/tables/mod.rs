//! `host-sim tables`: export the controller's start-up tables for the firmware (Rust
//! source, a versioned binary blob, or CSV), verify a blob, plot limit surfaces as the
//! paper's Figures 9–12 do, and sweep parameter sets in parallel.
//!
//! - `export`: the tables as Rust source, a blob or CSV.
//! - `verify`: a blob against a fresh precomputation.
//! - `figures`: the limit-surface plots (`--plot`).
//! - `sweep`: the parameter sweep (`--sweep`).

mod export;
mod figures;
mod sweep;
mod verify;

pub use export::{flash_bytes, rust_source};
pub use verify::{deviation, VERIFY_TOLERANCE};

use crate::args::Precision;
use crate::config::names::flag;
use crate::input::config_reason;
use crate::CliError;
use clap::{Args, Subcommand, ValueEnum};
use indicatif::ProgressBar;
use softgrip::controller::{Checked, Controller, ControllerConfig, Mode};
use std::path::{Path, PathBuf};

/// Output format of `tables`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TableFormat {
    /// Rust source of const tables (`softgrip_tables.rs`), for the firmware's
    /// `prebuilt-tables` feature.
    Rust,
    /// A versioned, CRC-checked binary blob (`softgrip_tables.bin`).
    Bin,
    /// CSV for analysis (`tables_nodes.csv`, `tables_directions.csv`).
    Csv,
}

/// `tables verify`.
#[derive(Debug, Subcommand)]
pub enum TablesAction {
    /// Recompute the tables of a blob and report the largest deviation; exit 1 on a
    /// corrupted or mismatched file.
    Verify {
        /// The blob (`.bin`).
        file: PathBuf,
    },
}

/// Arguments of `host-sim tables`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct TablesArgs {
    /// `verify FILE`.
    #[command(subcommand)]
    action: Option<TablesAction>,
    /// A TOML file with a `[finger]` table (and optionally `[controller]`), e.g. a scene;
    /// default: the controller's default finger.
    #[arg(long)]
    finger: Option<PathBuf>,
    /// Export format.
    #[arg(long, value_enum, default_value_t = TableFormat::Bin)]
    format: TableFormat,
    /// The configuration over the finger's (or the defaults, in table mode): `--config FILE`
    /// and one flag per field, among them `--mode` (the mode the tables serve).
    #[command(flatten)]
    config: crate::config::ConfigArgs,
    /// Arithmetic of the precomputation.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    precision: Precision,
    /// Output directory.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Also draw the limit surfaces as the paper's Figures 9–12 (SVG).
    #[arg(long)]
    plot: bool,
    /// Also sweep k × skew × aspect × μ in parallel and write `sweep.csv`.
    #[arg(long)]
    sweep: bool,
    /// No progress bar (there is none either when stderr is not a terminal).
    #[arg(long)]
    quiet: bool,
}

fn usage(msg: impl std::fmt::Display) -> CliError {
    CliError::Usage(msg.to_string())
}

/// The configuration the arguments describe, checked once: the finger file's (or the
/// defaults), in table mode, with `--config` and the flags over it.
pub fn config(args: &TablesArgs) -> Result<Checked, CliError> {
    let (base, finger) = match &args.finger {
        None => (ControllerConfig::default(), None),
        Some(p) => {
            let f = crate::finger_file::FingerFile::load(p, "--finger")?;
            let cfg = crate::sim::run::scene_config(&f.finger, &f.controller_settings(), f.tick_hz)
                .map_err(|e| usage(format!("--finger: {}: {e}", p.display())))?;
            (cfg, Some((p, f)))
        }
    };
    let cfg = args.config.apply(&ControllerConfig {
        mode: Mode::Table,
        ..base
    })?;
    cfg.check().map_err(|e| {
        let field = e.field();
        match &finger {
            _ if args.config.sets(field) => {
                usage(format!("--{}: {}", flag(field), config_reason(&e)))
            }
            Some((p, f)) => usage(format!(
                "--finger: {}: {}",
                p.display(),
                crate::sim::run::config_error(&e, &f.controller, &cfg)
            )),
            None => usage(format!("--config: {e}")),
        }
    })
}

fn build(cfg: Checked, precision: Precision) -> Result<Controller<f32>, CliError> {
    match precision {
        Precision::F64 => Controller::<f32>::from_checked_in::<f64>(&cfg),
        Precision::F32 => Controller::<f32>::from_checked(&cfg),
    }
    .map_err(|e| usage(format!("--finger: {e}")))
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    std::fs::write(path, bytes)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", path.display())))
}

fn bar(len: u64, what: &str, quiet: bool) -> ProgressBar {
    let b = crate::progress::bar(len, "", quiet);
    b.set_message(what.to_string());
    b
}

/// Runs `host-sim tables`.
pub fn run(args: &TablesArgs) -> Result<(), CliError> {
    if let Some(TablesAction::Verify { file }) = &args.action {
        return verify::verify(file);
    }
    let out = args
        .out
        .as_ref()
        .ok_or_else(|| usage("--out: required (the directory to write into)"))?;
    export::export(args, out)?;
    if args.plot {
        figures::plot(out, args.quiet)?;
    }
    if args.sweep {
        sweep::sweep(out, args.quiet)?;
    }
    Ok(())
}
