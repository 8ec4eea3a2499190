//! The floating-point type the core computes in.
//!
//! Everything numeric in softgrip is generic over [`Real`], implemented for `f64` (the
//! default for precomputation: about 1e-12 absolute on the limit surface) and `f32` (what the
//! Cortex-M4F has in hardware: about 1e-6).
//!
//! The elementary functions are [`Real`]'s own `libm_*` methods, which call the `libm`
//! crate directly, on the host and on the target alike: a host computation then rounds
//! exactly as the firmware does, so the firmware in QEMU and the in-process link give
//! bit-identical results. `num-traits`' `Float::ln` and friends must not be used for this:
//! when any crate in a host build enables `num-traits/std` (plotting libraries do), they
//! switch to the C library's routines, which round differently in the last place.
//! `clippy.toml` forbids them.

use num_traits::{Float, FloatConst};

/// A floating-point type the core can compute in: `f32` or `f64`.
pub trait Real:
    Float + FloatConst + core::fmt::Debug + core::fmt::Display + Default + 'static
{
    /// Converts an `f64` constant (rounding to nearest for `f32`).
    fn of(x: f64) -> Self;
    /// `true` for `f32`, the firmware's precision: what the precision-dependent constants
    /// (the quadrature's truncation, the solve's iteration cap) are chosen by.
    const SINGLE: bool;
    /// Widens to `f64` (exact for both implementations).
    fn to_f64(self) -> f64;
    /// Converts a count.
    fn of_usize(n: usize) -> Self {
        Self::of(n as f64)
    }
    /// Converts a tick count (rounding to nearest for `f32`). `f32` overrides it with a
    /// direct conversion: on the M4F one `VCVT`, where going through `f64` is a software
    /// routine.
    fn of_u32(n: u32) -> Self {
        Self::of(f64::from(n))
    }
    /// Natural logarithm (libm).
    fn libm_ln(self) -> Self;
    /// `e^x` (libm).
    fn libm_exp(self) -> Self;
    /// `x^y` (libm).
    fn libm_powf(self, y: Self) -> Self;
    /// Square root (libm; correctly rounded).
    fn libm_sqrt(self) -> Self;
    /// `sqrt(x² + y²)` without overflow (libm).
    fn libm_hypot(self, y: Self) -> Self;
    /// Four-quadrant arctangent of `self/x` (libm).
    fn libm_atan2(self, x: Self) -> Self;
    /// Cube root (libm).
    fn libm_cbrt(self) -> Self;
    /// `e^x − 1` (libm).
    fn libm_exp_m1(self) -> Self;
    /// `ln(1 + x)` (libm).
    fn libm_ln_1p(self) -> Self;
    /// Hyperbolic tangent (libm).
    fn libm_tanh(self) -> Self;
    /// `(sin x, cos x)` (libm).
    fn libm_sin_cos(self) -> (Self, Self);
}

macro_rules! libm_methods {
    ($ln:ident, $exp:ident, $pow:ident, $sqrt:ident, $hypot:ident, $atan2:ident, $cbrt:ident,
     $expm1:ident, $log1p:ident, $tanh:ident, $sincos:ident) => {
        #[inline(always)]
        fn libm_ln(self) -> Self {
            libm::$ln(self)
        }
        #[inline(always)]
        fn libm_exp(self) -> Self {
            libm::$exp(self)
        }
        #[inline(always)]
        fn libm_powf(self, y: Self) -> Self {
            libm::$pow(self, y)
        }
        #[inline(always)]
        fn libm_sqrt(self) -> Self {
            libm::$sqrt(self)
        }
        #[inline(always)]
        fn libm_hypot(self, y: Self) -> Self {
            libm::$hypot(self, y)
        }
        #[inline(always)]
        fn libm_atan2(self, x: Self) -> Self {
            libm::$atan2(self, x)
        }
        #[inline(always)]
        fn libm_cbrt(self) -> Self {
            libm::$cbrt(self)
        }
        #[inline(always)]
        fn libm_exp_m1(self) -> Self {
            libm::$expm1(self)
        }
        #[inline(always)]
        fn libm_ln_1p(self) -> Self {
            libm::$log1p(self)
        }
        #[inline(always)]
        fn libm_tanh(self) -> Self {
            libm::$tanh(self)
        }
        #[inline(always)]
        fn libm_sin_cos(self) -> (Self, Self) {
            libm::$sincos(self)
        }
    };
}

impl Real for f64 {
    libm_methods!(log, exp, pow, sqrt, hypot, atan2, cbrt, expm1, log1p, tanh, sincos);
    const SINGLE: bool = false;
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
    libm_methods!(logf, expf, powf, sqrtf, hypotf, atan2f, cbrtf, expm1f, log1pf, tanhf, sincosf);
    const SINGLE: bool = true;
    #[inline(always)]
    fn of(x: f64) -> Self {
        x as f32
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self as f64
    }
    #[inline(always)]
    fn of_u32(n: u32) -> Self {
        n as f32
    }
}

/// The square root of the start-up's hot loops (the limit-surface kernels): `libm`'s, or
/// one that a [`TickMath`](crate::controller::TickMath) backend offers
/// ([`TickMath::startup_sqrt`](crate::controller::TickMath::startup_sqrt): the firmware's
/// `VSQRT`). Both are correctly rounded, so the precomputed grid is the same bit for bit;
/// only the cost differs (on the M4F, one instruction instead of libm's software routine).
/// An `extern "C"` function cannot unwind, so the call through the pointer keeps the
/// start-up's no-panic proof (`scripts/no-panic.sh`, `controller_new`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SqrtFn<T>(Option<extern "C" fn(T) -> T>);

impl<T: Real> SqrtFn<T> {
    /// `libm`'s.
    pub(crate) const LIBM: Self = Self(None);

    /// `f` where given, else `libm`'s.
    pub(crate) fn new(f: Option<extern "C" fn(T) -> T>) -> Self {
        Self(f)
    }

    /// `sqrt(x)`.
    #[inline(always)]
    pub(crate) fn sqrt(self, x: T) -> T {
        match self.0 {
            Some(f) => f(x),
            None => x.libm_sqrt(),
        }
    }
}
