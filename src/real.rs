//! The floating-point type the core computes in.
//!
//! Everything numeric in softgrip is generic over [`Real`], implemented for `f64` (the
//! default for precomputation: about 1e-12 absolute on the limit surface) and `f32` (what the
//! Cortex-M4F has in hardware: about 1e-6). The elementary functions come from
//! `num-traits` routed through `libm`, on the host and on the target alike, so a host test
//! exercises the very routines the firmware runs.

use num_traits::{Float, FloatConst};

/// A floating-point type the core can compute in: `f32` or `f64`.
pub trait Real:
    Float + FloatConst + core::fmt::Debug + core::fmt::Display + Default + 'static
{
    /// Converts an `f64` constant (rounding to nearest for `f32`).
    fn of(x: f64) -> Self;
    /// Widens to `f64` (exact for both implementations).
    fn to_f64(self) -> f64;
    /// Converts a count.
    fn of_usize(n: usize) -> Self {
        Self::of(n as f64)
    }
}

impl Real for f64 {
    #[inline(always)]
    fn of(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
}

impl Real for f32 {
    #[inline(always)]
    fn of(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
}
