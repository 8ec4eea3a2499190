//! `host-sim`: the std side of softgrip.
//!
//! - [`fls_cmd`]: friction-limit-surface sweeps (`host-sim fls`).
//! - [`required_force_cmd`]: the slip-prevention rule for one load (`host-sim
//!   required-force`).
//! - [`sim`] and [`simulate_cmd`]: the grasp simulator (`host-sim simulate`).
//! - [`tables_cmd`] and [`fls_plot`]: table export and verification, limit-surface
//!   plots and parameter sweeps (`host-sim tables`).
//! - [`input`]: bounded reading of every file the user names, and the value shortening
//!   of error messages.
//! - [`link`]: the plant's side of the serial link to the device running the controller;
//!   by default the firmware loop on a thread of its own behind a pseudo-terminal.

#![forbid(unsafe_code)]

pub mod accuracy;
pub mod bench;
pub mod fls_cmd;
pub mod fls_plot;
pub mod input;
pub mod link;
pub mod required_force_cmd;
pub mod sim;
pub mod simulate_cmd;
pub mod tables_cmd;

/// A command-line failure with its exit code.
#[derive(Debug)]
pub enum CliError {
    /// A bad argument: exit code 2.
    Usage(String),
    /// Anything else: exit code 1.
    Failed(String),
}
