//! The report: `accuracy.md` (tables, the Pareto front, the defaults, the brute-force
//! ratio, the target's figures) and `accuracy.svg` (error against time, log-log, the
//! Pareto points highlighted). The plot uses `plotters`' SVG backend without any font
//! feature: text is written as SVG `<text>` elements.

use super::knobs::{Engine, Knob, Measured, Variant};
use super::{brute, knobs, target, Results};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

mod defaults;
mod format;
mod fronts;
mod plot;
mod sections;
mod summary;
mod tables;

use defaults::*;
pub use format::*;
pub use fronts::*;
pub use plot::*;
pub use sections::*;
pub use summary::*;
use tables::*;
