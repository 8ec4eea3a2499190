//! `host-sim`: the std side of softgrip.
//!
//! - [`cmd`]: the commands `fls` (friction-limit-surface sweeps), `required-force` (the
//!   slip-prevention rule for one load), `simulate` (the grasp simulator, over [`sim`]),
//!   `tables` (table export and verification, limit-surface plots and sweeps), `bench` and
//!   `accuracy` (thin, over the modules of those names), `experiment` and `calibrate`,
//!   siblings that share only [`args`], [`input`] and [`plot`].
//! - [`experiment`]: lab experiments on a plant behind the [`experiment::Rig`] trait
//!   (`host-sim experiment`; `host-sim calibrate` fits their files).
//! - [`bench`](mod@bench): every controller on random trials against the oracle (`host-sim bench`),
//!   on plain options.
//! - [`accuracy`]: what accuracy costs in time (`host-sim accuracy`), on plain options.
//! - [`exact`]: the exact f64 limit surface of a configuration's finger and the least force
//!   that holds a load under it, without grids (`required-force`'s exact force, the
//!   reference of `accuracy`).
//! - [`brush`]: the brush finger, a physical fingertip plant of its own (elastic
//!   foundation, stick–slip bristles, object dynamics) that the simulator can use as its
//!   ground truth instead of softgrip's limit surface (`[finger] model = "brush"`).
//! - [`sim`]: scenes, effects, ground truth, baselines, runs and their reports.
//! - [`plot`]: limit-surface plots (`fls --plot`, `tables`).
//! - [`progress`]: the progress bar of the long commands, on stderr.
//! - [`finger_file`]: a finger TOML (`calibrate --out`'s, or a scene), as `--finger`
//!   reads it in `required-force`, `simulate`, `tables` and `experiment`.
//! - [`input`]: bounded reading of every file the user names, and the value shortening
//!   of error messages.
//! - [`link`]: the plant's side of the serial link to the device running the controller;
//!   by default the firmware loop on a thread of its own behind a pseudo-terminal.

#![forbid(unsafe_code)]

pub mod accuracy;
pub mod args;
pub mod bench;
pub mod brush;
pub mod cmd;
pub mod config;
pub mod exact;
pub mod experiment;
pub mod finger_file;
pub mod input;
pub mod link;
pub mod plot;
pub mod progress;
pub mod provenance;
pub mod sim;

/// A command-line failure with its exit code.
#[derive(Debug)]
pub enum CliError {
    /// A bad argument: exit code 2.
    Usage(String),
    /// Anything else: exit code 1.
    Failed(String),
}
