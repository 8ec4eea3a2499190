//! The tick's square root on the FPU: `VSQRT.F32`, one instruction where `libm::sqrtf` is
//! a software routine of about 78 (docs/firmware.md). Both are correctly rounded (IEEE 754), so
//! the results are bit-identical to the `Libm` backend on the host; the `sqrt-check`
//! build checks that over a sweep of inputs (host-sim/tests/qemu_sqrt.rs).
//!
//! Written with `core::arch::asm!`, stable on ARM: no compiler intrinsic, no unstable
//! feature.

#![allow(unsafe_code)]

use softgrip::controller::TickMath;
use softgrip::real::Real;

/// The FPU's square root.
#[derive(Debug, Clone, Copy, Default)]
pub struct FpuSqrt;

/// `VSQRT.F32` of `x`.
///
/// Rust 1.95's `asm!` offers no floating-point register class on this target (`sreg`
/// asks for the `vfp2` feature, which includes double precision the M4F lacks; fixed in
/// later compilers, rust-lang/rust#159988), so the operand travels in a core register and
/// `s0` is borrowed and given back.
#[inline(always)]
pub fn vsqrt(x: f32) -> f32 {
    let bits: u32;
    // SAFETY: floating-point moves and one square root: no memory, no stack, no flags
    // (VSQRT may set the FPSCR's cumulative exception bits, which nothing here reads);
    // `s0` holds its old value again on exit, as `asm!` requires of undeclared registers.
    unsafe {
        core::arch::asm!(
            "vmov {saved}, s0",
            "vmov s0, {x}",
            "vsqrt.f32 s0, s0",
            "vmov {x}, s0",
            "vmov s0, {saved}",
            x = inout(reg) x.to_bits() => bits,
            saved = out(reg) _,
            options(pure, nomem, nostack, preserves_flags),
        );
    }
    f32::from_bits(bits)
}

/// [`vsqrt`] behind a pointer the start-up can call (`extern "C"`: it cannot unwind).
extern "C" fn vsqrt_c(x: f32) -> f32 {
    vsqrt(x)
}

impl TickMath<f32> for FpuSqrt {
    const NAME: &'static str = "fpu";
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        vsqrt(x)
    }

    /// `VSQRT` for an f32 start-up too (the limit-surface kernels take two square roots
    /// per quadrature node); an f64 start-up (`precompute-f64`) keeps libm's, as the M4F
    /// has no double-precision FPU.
    fn startup_sqrt<P: Real>() -> Option<extern "C" fn(P) -> P> {
        let f: extern "C" fn(f32) -> f32 = vsqrt_c;
        (&f as &dyn core::any::Any)
            .downcast_ref::<extern "C" fn(P) -> P>()
            .copied()
    }
}
