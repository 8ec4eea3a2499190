//! The `sqrt-check` build: the tick's square root (the backend `Math` the firmware is
//! built with) against `libm::sqrtf`, over a sweep of inputs, on the target. It prints one
//! line through semihosting and exits with 0 when every result matched, 1 otherwise;
//! host-sim/tests/qemu_sqrt.rs computes the same digest on the host and compares.
//!
//! The sweep: every f32 in `[1, 4)` (2²⁴ values: every significand at both exponent
//! parities, which is all the rounding cases of a square root, since `√(4ᵏx) = 2ᵏ√x`
//! exactly for normal numbers), then 65 536 bit patterns spread over the whole 32-bit
//! range (`k · 65 537`: every exponent and sign, subnormals, infinities, NaNs), then
//! `±0`, `±∞`, the smallest subnormal and the largest finite value. A NaN result counts
//! as the canonical quiet NaN: NaN bits are not portable (the tick never takes the root
//! of a negative or a NaN).

use softgrip::controller::TickMath;

const CANONICAL_NAN: u32 = 0x7FC0_0000;
const SPECIALS: [u32; 6] = [0, 0x8000_0000, 0x7F80_0000, 0xFF80_0000, 1, 0x7F7F_FFFF];

fn bits_of(root: f32) -> u32 {
    if root.is_nan() {
        CANONICAL_NAN
    } else {
        root.to_bits()
    }
}

/// FNV-1a over the result bits, four bytes at a time.
fn mix(hash: u64, word: u32) -> u64 {
    (hash ^ u64::from(word)).wrapping_mul(0x0000_0100_0000_01B3)
}

fn hex(out: &mut [u8], mut value: u64) {
    for slot in out.iter_mut().rev() {
        *slot = b"0123456789abcdef"[(value & 0xF) as usize];
        value >>= 4;
    }
}

fn decimal(out: &mut [u8], mut value: u32) {
    for slot in out.iter_mut().rev() {
        *slot = b'0' + (value % 10) as u8;
        value /= 10;
    }
}

/// Runs the sweep, prints `sqrt-check N=<count> digest=<hex> mismatches=<count>` and
/// exits the emulator (it does not return; its type says `()` so that the device loop
/// after the call in `main` does not read as unreachable).
pub fn run_and_exit<M: TickMath<f32>>() {
    let mut hash = 0xCBF2_9CE4_8422_2325_u64;
    let mut count = 0u32;
    let mut mismatches = 0u32;
    let mut check = |bits: u32| {
        let x = f32::from_bits(bits);
        let got = bits_of(M::sqrt(x));
        if got != bits_of(libm::sqrtf(x)) {
            mismatches += 1;
        }
        hash = mix(hash, got);
        count += 1;
    };
    for bits in 0x3F80_0000..0x4080_0000u32 {
        check(bits);
    }
    for k in 0..=u16::MAX {
        check(u32::from(k).wrapping_mul(65_537));
    }
    for bits in SPECIALS {
        check(bits);
    }
    let mut line = *b"sqrt-check N=0000000000 digest=0000000000000000 mismatches=0000000000\n";
    decimal(&mut line[13..23], count);
    hex(&mut line[31..47], hash);
    decimal(&mut line[59..69], mismatches);
    if let Ok(mut out) = cortex_m_semihosting::hio::hstdout() {
        let _ = out.write_all(&line);
    }
    crate::exit::exit(u8::from(mismatches != 0));
}
