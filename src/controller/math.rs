//! The math backend of the tick.
//!
//! The tick was designed so that its only elementary function is the square root: every
//! `powf`, `ln` and `exp` of the model (the contact size `a = c·N^γ`, the pitch at `l/a`)
//! is precomputed at start-up on a grid of normal forces. A tick takes one square root for
//! the magnitude of the tangential force and, in ellipse mode, one or three more for the
//! utilisation and the below-grid closed forms. The backend decides how those are
//! computed:
//!
//! - [`Libm`]: the correctly rounded `sqrt` of the `libm` crate (f32 and f64). The
//!   commanded force then carries only the table and interpolation errors documented on
//!   [`Controller`](super::Controller).
//! - [`Micromath`]: `micromath`'s bit-trick `sqrt` (f32 only), a single integer add and
//!   shift with no refinement: up to about 6 % relative error, in either direction. It
//!   enters the force demand through `|f_t|`, so the command can be off by up to that
//!   much where translation dominates; `tests/controller.rs` measures the worst case.

use crate::real::Real;

/// The elementary functions a tick needs.
pub trait TickMath<T: Real>: Copy + Default + core::fmt::Debug {
    /// The backend's name, as the command line spells it.
    const NAME: &'static str;
    /// Square root of `x ≥ 0` (NaN or any value for `x < 0`; the tick never asks).
    fn sqrt(x: T) -> T;

    /// A square root in the start-up's precision `P` for its limit-surface kernels, when
    /// the backend has one that is correctly rounded (so the grid comes out bit for bit as
    /// with `libm`'s) and cheaper, such as the firmware's `VSQRT` for `P = f32` (its gain:
    /// docs/decisions/firmware-size-levers.md; `host-sim/tests/firmware_costs.rs` measures
    /// the start-ups). `None`, the default, keeps `libm`'s. An approximate square root (such
    /// as [`Micromath`]'s) must not be offered here. `extern "C"`: it cannot unwind, which
    /// keeps the start-up's no-panic proof.
    fn startup_sqrt<P: Real>() -> Option<extern "C" fn(P) -> P> {
        None
    }
}

/// Accurate: the `libm` crate's correctly rounded square root.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Libm;

/// Fast: `micromath`'s approximate square root, f32 only.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Micromath;

impl TickMath<f32> for Libm {
    const NAME: &'static str = "libm";
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        libm::sqrtf(x)
    }
}

impl TickMath<f64> for Libm {
    const NAME: &'static str = "libm";
    #[inline(always)]
    fn sqrt(x: f64) -> f64 {
        libm::sqrt(x)
    }
}

impl TickMath<f32> for Micromath {
    const NAME: &'static str = "micromath";
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        <f32 as micromath::F32Ext>::sqrt(x)
    }
}

/// `min(a, b)` for a bound `b` that is never NaN, as `f32::min` gives it (a NaN `a`
/// yields `b`; the sign of a zero aside), by one comparison: the Cortex-M4F has no
/// `VMINNM`, so `min` is an out-of-line `fminf` call, and the tick, the slip response and
/// the utilisation clamp on every tick. Every caller's `b` is a validated bound, a
/// constant or a value already clamped.
#[inline(always)]
pub(crate) fn lesser<T: Real>(a: T, b: T) -> T {
    // A NaN `a` compares false and gives `b`.
    if a < b {
        a
    } else {
        b
    }
}

/// `max(a, b)` for a bound `b` that is never NaN (see [`lesser`]).
#[inline(always)]
pub(crate) fn greater<T: Real>(a: T, b: T) -> T {
    if a > b {
        a
    } else {
        b
    }
}
