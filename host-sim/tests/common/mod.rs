//! What the QEMU tests share: whether QEMU and the firmware they need are there. Each test
//! binary uses part of it.
#![allow(dead_code)]

use host_sim::link::qemu;
use std::path::PathBuf;

/// QEMU's directory if QEMU and the firmware of every variant in `variants` are there
/// ([`qemu::available`]). Otherwise `None`, after printing the scripts that set them up;
/// with `SOFTGRIP_REQUIRE_QEMU` set (as `.ci/run` sets it), a failure instead.
pub fn qemu_for(variants: &[&str]) -> Option<PathBuf> {
    if qemu::available(variants) {
        return Some(qemu::default_paths().0);
    }
    let variants = variants.join(" ");
    assert!(
        std::env::var("SOFTGRIP_REQUIRE_QEMU").is_err(),
        "SOFTGRIP_REQUIRE_QEMU is set but QEMU or the firmware ({variants}) is missing"
    );
    eprintln!("skipped: run scripts/firmware-setup.sh and scripts/firmware-build.sh {variants}");
    None
}

/// QEMU's directory and the firmware of `variant`, if both are there (see [`qemu_for`]).
pub fn qemu_and_firmware(variant: &str) -> Option<(PathBuf, PathBuf)> {
    qemu_for(&[variant]).map(|q| (q, qemu::firmware(variant)))
}
