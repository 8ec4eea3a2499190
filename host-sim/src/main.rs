//! `host-sim`: the std side of softgrip (see the crate's library docs).
//!
//! Exit codes: 0 on success, 2 on a bad argument (with a one-line reason naming it), 1 on
//! any other failure.

#![forbid(unsafe_code)]

use clap::{Parser, Subcommand};
use host_sim::cmd::tables as tables_cmd;
use host_sim::cmd::{accuracy as accuracy_cmd, bench as bench_cmd};
use host_sim::cmd::{calibrate as calibrate_cmd, experiment as experiment_cmd};
use host_sim::cmd::{
    fls as fls_cmd, required_force as required_force_cmd, simulate as simulate_cmd,
};
use host_sim::CliError;
use std::process::ExitCode;

/// Host tools for the softgrip fingertip controller.
#[derive(Debug, Parser)]
#[command(name = "host-sim", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Sweep the friction limit surface of one fingertip configuration.
    Fls(fls_cmd::FlsArgs),
    /// Run grasp scenes against controllers over the serial link and report.
    Simulate(simulate_cmd::SimulateArgs),
    /// Export the controller's tables (rust, bin, csv), verify a blob, plot surfaces.
    Tables(tables_cmd::TablesArgs),
    /// The least normal force that holds a load with the safety margin (docs/model.md's rule).
    RequiredForce(required_force_cmd::RequiredForceArgs),
    /// Every controller over its knob on random trials of scene families: drops and
    /// force over the oracle, tables, bench.json and Pareto plots.
    Bench(bench_cmd::BenchArgs),
    /// Regenerate the accuracy/time report (accuracy.md, accuracy.svg).
    Accuracy(accuracy_cmd::AccuracyArgs),
    /// Lab experiments on a finger: the CSVs (and plots) a lab would record.
    Experiment(experiment_cmd::ExperimentArgs),
    // The intervals:
    // host-sim/tests/calibrate_cli.rs::json_has_every_parameter_with_value_interval_and_identification.
    // host-sim/tests/calibrate_recovery.rs checks the intervals' coverage.
    /// Fit the finger's parameters to indentation and slip-onset CSVs, with 95 % intervals.
    Calibrate(calibrate_cmd::CalibrateArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            use clap::error::ErrorKind;
            if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            // The whole error: what is wrong, the valid values or "did you mean", and the
            // usage line, as clap renders it (to stderr).
            let _ = e.print();
            return ExitCode::from(2);
        }
    };
    let result = match cli.command {
        Command::Fls(args) => fls_cmd::run(&args),
        Command::RequiredForce(args) => required_force_cmd::run(&args),
        Command::Simulate(args) => simulate_cmd::run_cmd(&args),
        Command::Accuracy(args) => accuracy_cmd::run(&args),
        Command::Tables(args) => tables_cmd::run(&args),
        Command::Bench(args) => bench_cmd::run(&args),
        Command::Experiment(args) => experiment_cmd::run(&args),
        Command::Calibrate(args) => calibrate_cmd::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Usage(msg)) => {
            eprintln!("error: {msg}");
            ExitCode::from(2)
        }
        Err(CliError::Failed(msg)) => {
            eprintln!("error: {msg}");
            ExitCode::from(1)
        }
    }
}
