//! The progress bar of the long commands (`simulate`, `tables`, `bench`, `accuracy`): on
//! stderr, never on stdout, so what a command prints and writes is the same with or
//! without it. Hidden with `--quiet` and when stderr is not a terminal.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A bar over `len` steps, counted in `unit` (`"ticks"`, `"trials"`; empty for none):
/// `{bar} {pos}/{len} UNIT {msg} [{elapsed}<{eta}]`. Hidden if `quiet` or if stderr is
/// not a terminal.
pub fn bar(len: u64, unit: &str, quiet: bool) -> ProgressBar {
    let bar = if quiet || !std::io::stderr().is_terminal() {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(len)
    };
    let unit = if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    };
    bar.set_style(
        ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}}{unit} {{msg}} [{{elapsed}}<{{eta}}]"
        ))
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}
