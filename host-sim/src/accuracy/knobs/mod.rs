//! The knobs, the configurations that vary them, and what each configuration leaves in
//! error and costs in time.
//!
//! Every configuration is measured the same way, on two fingers (the default
//! [`ControllerConfig`], a rectangle whose contact grows with the force, and a Hertzian
//! disc), against the exact f64 answers of [`crate::exact`]:
//!
//! - **pitch error**: the moment arm `a·pitch` the configuration stores at its grid forces
//!   against `a·pitch` with the converged pitch, worst relative error over both fingers;
//! - **surface error**: the largest radial error of the surface the tick tests the load
//!   against (arm interpolation, Eq. 10 ellipse or stored table, aspect interpolation)
//!   against the exact surface, `|u_exact/u − 1|` over a grid of forces and directions;
//! - **force error**: `N_req(s)` from a real tick against the exact rule's answer, over a
//!   fixed set of loads spread over directions and magnitudes; against the exact surface
//!   (both fingers), against the configuration's own rule (the ellipse rule with the exact
//!   pitch for ellipse mode), and the largest under-ask (the unsafe side);
//! - **costs**: host time of the start-up precomputation and of one tick, medians of
//!   repeated runs on the rectangle.

use crate::exact::{exact_tick, ExactSurface, Finger, Rule};
use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, Libm, Measurement, Micromath, Mode, TickMath,
};
use softgrip::Real;
use std::hint::black_box;
use std::time::Instant;

mod fingers;
mod measure;
mod variant;

pub use fingers::*;
pub use measure::*;
pub use variant::*;
