//! Whether the emulated firmware's tests can run here: QEMU unpacked by
//! `scripts/firmware-setup.sh` and the ELFs built by `scripts/firmware-build.sh`. When a
//! piece is missing the tests that need it are compiled as ignored, with the command that
//! sets it up as the reason, so `cargo test` counts them as ignored, not passed. With
//! `SOFTGRIP_REQUIRE_QEMU` set (as `.ci/run` sets it) nothing is ignored: a missing piece
//! fails those tests instead.

use std::path::Path;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let qemu = root.join(".firmware/qemu/usr/bin/qemu-system-arm");
    let elf = |variant: &str| root.join(format!("target/firmware/{variant}/softgrip-firmware.elf"));
    println!("cargo::rerun-if-env-changed=SOFTGRIP_REQUIRE_QEMU");
    // The folders as well as the files: unpacked and copied files may keep old
    // modification times, but the folders the scripts create or write into change.
    for path in [
        root.join(".firmware"),
        root.join("target/firmware/default"),
        root.join("target/firmware/prebuilt-tables"),
        root.join("target/firmware/sqrt-check"),
        root.join("target/firmware/board"),
        root.join("target/firmware/solve-to-cap"),
        qemu.clone(),
        elf("default"),
        elf("prebuilt-tables"),
        elf("sqrt-check"),
        elf("board"),
        elf("solve-to-cap"),
    ] {
        println!("cargo::rerun-if-changed={}", path.display());
    }
    let required = std::env::var_os("SOFTGRIP_REQUIRE_QEMU").is_some();
    let have = |variant: &str| required || (qemu.exists() && elf(variant).exists());
    for (cfg, ok) in [
        ("no_qemu", have("default")),
        (
            "no_qemu_prebuilt",
            have("default") && have("prebuilt-tables") && have("solve-to-cap"),
        ),
        ("no_qemu_sqrt", have("sqrt-check")),
        ("no_qemu_board", have("board")),
    ] {
        println!("cargo::rustc-check-cfg=cfg({cfg})");
        if !ok {
            println!("cargo::rustc-cfg={cfg}");
        }
    }
}
