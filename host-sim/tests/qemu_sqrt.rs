//! The firmware's square root (the FPU's `VSQRT.F32`, through `asm!`) is bit-identical to
//! `libm::sqrtf` on the host, over the sweep of firmware/src/sqrt_check.rs: the
//! `sqrt-check` firmware runs the sweep in QEMU and prints a digest of its results, and
//! this test computes the same digest with the host's `Libm` backend.
//!
//! Needs `scripts/firmware-setup.sh` and `scripts/firmware-build.sh sqrt-check`; without
//! them the test is compiled as ignored (`host-sim/build.rs`), unless
//! `SOFTGRIP_REQUIRE_QEMU=1` (as `.ci/run` sets).

use host_sim::link::qemu;
use softgrip::controller::{Libm, TickMath};

mod common;

const CANONICAL_NAN: u32 = 0x7FC0_0000;
const SPECIALS: [u32; 6] = [0, 0x8000_0000, 0x7F80_0000, 0xFF80_0000, 1, 0x7F7F_FFFF];

/// The sweep and digest of firmware/src/sqrt_check.rs, on the host.
fn host_digest() -> (u32, u64) {
    let mut hash = 0xCBF2_9CE4_8422_2325_u64;
    let mut count = 0u32;
    let mut check = |bits: u32| {
        let root = <Libm as TickMath<f32>>::sqrt(f32::from_bits(bits));
        let word = if root.is_nan() {
            CANONICAL_NAN
        } else {
            root.to_bits()
        };
        hash = (hash ^ u64::from(word)).wrapping_mul(0x0000_0100_0000_01B3);
        count += 1;
    };
    (0x3F80_0000..0x4080_0000u32).for_each(&mut check);
    (0..=u16::MAX).for_each(|k| check(u32::from(k).wrapping_mul(65_537)));
    SPECIALS.into_iter().for_each(&mut check);
    (count, hash)
}

#[test]
#[cfg_attr(
    no_qemu_sqrt,
    ignore = "needs QEMU and the sqrt-check firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh sqrt-check"
)]
fn the_firmware_square_root_is_bit_identical_to_the_hosts() {
    let Some((qemu, elf)) = common::qemu_and_firmware("sqrt-check") else {
        return;
    };
    let out = qemu::command(&qemu, &elf, "null", false).output().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("sqrt-check "))
        .unwrap_or_else(|| panic!("no result line: {stdout} {:?}", out.status));
    let field = |name: &str| {
        line.split_whitespace()
            .find_map(|w| w.strip_prefix(name))
            .unwrap_or_else(|| panic!("{name} missing in {line}"))
            .to_owned()
    };
    let (count, digest) = host_digest();
    eprintln!("{line}");
    assert_eq!(field("N=").parse::<u32>().unwrap(), count, "{line}");
    assert_eq!(field("mismatches=").parse::<u32>().unwrap(), 0, "{line}");
    assert_eq!(field("digest="), format!("{digest:016x}"), "{line}");
    assert_eq!(out.status.code(), Some(0), "{line}");
}
