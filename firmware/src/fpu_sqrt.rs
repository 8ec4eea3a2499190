//! The tick's square root on the FPU: `VSQRT.F32`, one instruction where `libm::sqrtf` is
//! a software routine of about 78 (docs/firmware.md). Both are correctly rounded (IEEE 754), so
//! the results are bit-identical to the `Libm` backend on the host.

#![allow(unsafe_code)]

use softgrip::controller::TickMath;

/// The FPU's square root.
#[derive(Debug, Clone, Copy, Default)]
pub struct FpuSqrt;

impl TickMath<f32> for FpuSqrt {
    const NAME: &'static str = "fpu";
    #[inline(always)]
    fn sqrt(x: f32) -> f32 {
        // LLVM's `llvm.sqrt.f32`, which is `VSQRT.F32` on this FPU. The firmware is built
        // with build-std (RUSTC_BOOTSTRAP), so the intrinsic is available.
        #[allow(unused_unsafe)]
        // SAFETY: a pure floating-point operation.
        unsafe {
            core::intrinsics::sqrtf32(x)
        }
    }
}
