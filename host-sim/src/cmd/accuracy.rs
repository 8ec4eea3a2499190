//! `host-sim accuracy`: its arguments, parsed into [`crate::accuracy::AccuracyOptions`]
//! for [`crate::accuracy::run`]; prints the summary.

use crate::accuracy::{self, report, AccuracyError, AccuracyOptions};
use crate::CliError;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `host-sim accuracy`.
#[derive(Debug, Args)]
pub struct AccuracyArgs {
    /// Fewer settings, loads and repetitions: finishes within a minute on two cores.
    #[arg(long)]
    quick: bool,
    /// Where to write accuracy.md and accuracy.svg.
    #[arg(long, default_value = "accuracy-out")]
    out: PathBuf,
    /// Also count instructions on the emulated Cortex-M4F (needs
    /// scripts/firmware-setup.sh and scripts/firmware-build.sh; slow).
    #[arg(long)]
    target: bool,
    /// No progress bar, no progress lines.
    #[arg(long)]
    quiet: bool,
}

/// Runs `host-sim accuracy`.
pub fn run(args: &AccuracyArgs) -> Result<(), CliError> {
    let opts = AccuracyOptions {
        quick: args.quick,
        target: args.target,
        quiet: args.quiet,
        out: args.out.clone(),
    };
    let done = accuracy::run(&opts).map_err(|e| match e {
        AccuracyError::Write(e) => CliError::Failed(format!("--out: {e}")),
        AccuracyError::Measure(e) => CliError::Failed(e),
    })?;
    print!("{}", report::summary(&done.results));
    println!(
        "wrote {} and {} ({:.0} s)",
        done.markdown.display(),
        done.plot.display(),
        done.results.elapsed_s
    );
    Ok(())
}
