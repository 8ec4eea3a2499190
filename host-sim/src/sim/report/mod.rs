//! What `host-sim simulate` writes: the per-tick time series as CSV, two SVG plots, a
//! JSON summary of the runs, and text tables for the terminal.
//!
//! - [`write_csv`]: one row per [`Sample`], header = the field names of [`Sample`] (those
//!   of its [`Sample::parts`] in its place).
//! - [`plot_surface`]: the load in normalised coordinates against the limit surface.
//! - [`plot_force`]: the applied normal force over time, slip intervals as bars below, and
//!   under softgrip's line the force each part of its command asks (`bands.rs`).
//! - [`write_summary_json`]: `{"runs": [...]}` of [`RunSummary`].
//! - [`summary_table`] and [`comparison_table`]: fixed-width tables for the terminal.
//!
//! The plots are drawn with `plotters`' SVG backend without any font feature: text (title,
//! axis labels, legend) is written as SVG `<text>` elements with a generic `font-family`
//! that the viewer renders; plotters only estimates text extents for the layout.

use super::record::{RunSummary, Sample};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::Serialize;
use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

mod bands;
mod draw;
mod files;
mod force_plot;
mod surface_plot;
mod tables;

use draw::*;
pub use files::*;
pub use force_plot::*;
pub use surface_plot::*;
pub use tables::*;

/// The CSV header [`write_csv`] writes: the field names of [`Sample`], in declaration order,
/// those of its [`Sample::parts`] in its place.
pub const SAMPLE_CSV_FIELDS: [&str; 26] = [
    "t_s",
    "ft_n",
    "mn_nm",
    "ft_meas_n",
    "mn_meas_nm",
    "n_cmd_n",
    "n_true_n",
    "a_true_m",
    "f_norm",
    "m_norm",
    "pitch",
    "utilisation",
    "slipping",
    "slip_distance_m",
    "slip_rotation_rad",
    "status",
    "n_slip_n",
    "required_n",
    "mu_hat",
    "margin",
    "slip_margin",
    "load_factor",
    "lead_n",
    "n_slip_mu_n",
    "n_safety_n",
    "n_load_n",
];

/// Most line vertices drawn per run and curve (longer series are decimated for the plot
/// only; the CSV keeps every sample).
pub(super) const MAX_LINE_POINTS: usize = 4000;
/// Most slip markers drawn per run in the surface plot.
pub(super) const MAX_SLIP_MARKERS: usize = 2000;
/// Upper bound of the surface plot's axes, whatever the data.
pub(super) const MAX_SURFACE_AXIS: f64 = 1.0e6;

/// Run colours (the "tab10" palette without its red and grey, which mark slip and the
/// tangential load).
pub(crate) const RUN_COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
pub(super) const SLIP_COLOUR: RGBColor = RGBColor(214, 39, 40);
pub(super) const LOAD_GREY: RGBColor = RGBColor(127, 127, 127);

pub(super) fn run_colour(i: usize) -> RGBColor {
    RUN_COLOURS[i % RUN_COLOURS.len()]
}

/// A failure to write a report file.
#[derive(Debug)]
pub enum ReportError {
    /// Creating or writing a file failed.
    Io(io::Error),
    /// `plotters` failed to draw (its `DrawingAreaErrorKind`, as text).
    Plot(String),
}

impl fmt::Display for ReportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::Io(e) => write!(f, "report I/O error: {e}"),
            ReportError::Plot(e) => write!(f, "plotting error: {e}"),
        }
    }
}

impl std::error::Error for ReportError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReportError::Io(e) => Some(e),
            ReportError::Plot(_) => None,
        }
    }
}

impl From<io::Error> for ReportError {
    fn from(e: io::Error) -> Self {
        ReportError::Io(e)
    }
}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for ReportError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        ReportError::Plot(e.to_string())
    }
}
