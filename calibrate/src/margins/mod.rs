//! The controller's margins from the margin protocols (docs/calibration.md, "The
//! margins"; the protocols and their thresholds: docs/decisions/margin-protocols.md):
//!
//! - cyclic (`cyclic.csv`): a fraction of the onset *ratchets* when the median slide per
//!   cycle over the last half of its cycles exceeds [`RATCHET_SLIDE_M`] or the median turn
//!   exceeds [`RATCHET_TURN_RAD`], or when it stopped before the others (the plate slid
//!   off). The cyclic share `r` of an axis is the largest fraction below the first that
//!   ratchets; `r` is the lesser of the two axes'; `cyclic_factor = 1/r`;
//! - hold (`hold.csv`): a fraction *creeps* when the slide's rate at the end of the hold
//!   exceeds [`CREEP_SLIDE_M_S`] or the turn's exceeds [`CREEP_TURN_RAD_S`]. The hold
//!   shares `h_t` (force) and `h_m` (torsion) are the largest fractions below the first
//!   that creeps; a round patch's `disc_torsion_factor = max(1, h_t/h_m)`; the least
//!   `safety·steady_factor` the hold allows is `1/h_t` on the disc (its moment carries
//!   the torsion factor) and `1/min(h_t, h_m)` on the rectangle.
//!
//! The 95 % interval of a share (the level: docs/decisions/calibration-fit.md) runs from
//! the last fraction that held to the first that did not (1 when none failed), each widened by the onset's own uncertainty: the
//! fractions are of the *measured* onset, whose relative standard error is the onset
//! rows' pooled relative standard deviation over `√n`, times `t_{0.975}` of the pooled
//! degrees of freedom (none with one onset per axis: the bracket alone). A share is at
//! most 1. The factors' intervals map the shares' through the same formulas. Rows are
//! grouped into tests by axis: onset rows begin a test, the rows after them at each
//! fraction belong to it (a lab may repeat the protocol, at another normal force too:
//! each axis's share is the least over its tests). Cost: linear in the rows.
//!
//! The fit (`fit.rs`: the rows judged, the shares, the factors) and the report
//! (`report.rs`: the margins in the finger TOML, the text report and the JSON report) are
//! re-exported here.

mod fit;
mod report;

pub use fit::{
    fit_cyclic, fit_hold, not_measured, CyclicMargins, HoldMargins, Margins, Measured,
    CREEP_SLIDE_M_S, CREEP_TURN_RAD_S, RATCHET_SLIDE_M, RATCHET_TURN_RAD,
};
pub use report::{margins_text, margins_toml, Report};
