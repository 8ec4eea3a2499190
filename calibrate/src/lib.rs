//! softgrip-calibrate: fits softgrip's finger parameters to a lab's measurements
//! (docs/experiments.md, docs/calibration.md), so that `host-sim calibrate` and the
//! Python package run the same code.
//!
//! - [`lab_csv`]: the two lab files (indentation, slip onsets) and the rig they record,
//!   read with errors naming file, line and column, and written;
//! - [`contact_fit`]: `c` and `γ` of `a = c·N^γ` in closed form (log-log least squares);
//! - [`surface`]: the exact limit surface tabulated over `1/k`, `l/a` and the skew;
//! - [`friction_fit`]: the joint fit of `c`, `γ`, `μ`, `k` and the skew to both files;
//! - [`calibration`]: identifiability, 95 % intervals (docs/decisions/calibration-fit.md),
//!   conservative values: [`calibrate`];
//! - [`lack_of_fit`]: whether the onsets contradict the fit, beyond their noise;
//! - [`friction_contact`]: optionally after it, `μ` from the slip test and the contact
//!   scale (or a long hemicylinder's half-length) refitted to the torsion onsets;
//! - [`estimate`]: the plain data both make ([`Setup`] and where it came from,
//!   [`Estimate`], the refit's record);
//! - [`interval`] and [`lsq`]: t quantiles, Wald intervals, the least-squares solver;
//! - [`margin_csv`]: the margin protocols' files (cyclic loads, sustained loads), and
//!   [`margins`]: the controller's margins fitted to them;
//! - [`finger_toml`]: the finger TOML and the text report;
//! - [`error`]: the errors, [`CalibError`].
//!
//! Accuracy: exact data give the exact `c` and `γ` (to rounding), `μ` within 2e-4 and `k`
//! within 2 % (the tabulated surface's interpolation;
//! calibrate/tests/exact_fit.rs::exact_data_give_the_exact_parameters). Cost: most of
//! [`calibrate`]'s time is tabulating the surface; [`calibrate_on`] with a prebuilt grid a
//! few milliseconds.

#![forbid(unsafe_code)]
// A negated comparison (`!(x > lo)`) is how the crate rejects NaN with the bad values, as
// the core does.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod calibration;
pub mod contact_fit;
pub mod error;
pub mod estimate;
pub mod finger_toml;
pub mod friction_contact;
pub mod friction_fit;
pub mod interval;
pub mod lab_csv;
pub mod lack_of_fit;
pub mod lsq;
pub mod margin_csv;
pub mod margins;
pub mod surface;

pub use calibration::{calibrate, calibrate_on, grid_for, Calibration};
pub use error::CalibError;
pub use estimate::{Estimate, ResolvedSetup, Setup, SetupSource};
