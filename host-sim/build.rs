//! Whether the emulated firmware's tests can run here: QEMU unpacked by
//! `scripts/firmware-setup.sh` and the ELFs built by `scripts/firmware-build.sh`. When a
//! piece is missing the tests that need it are compiled as ignored, with the command that
//! sets it up as the reason, so `cargo test` counts them as ignored, not passed. With
//! `SOFTGRIP_REQUIRE_QEMU` set (as `.ci/run` sets it) nothing is ignored: a missing piece
//! fails those tests instead.
//!
//! It also reads the constants a bench run depends on (`src/provenance/scan.rs`, shared
//! with the library) and compiles in their list and digest, so a run records them and
//! `tests/evidence_version.rs` compares them with the published runs'.

use std::path::{Path, PathBuf};

#[path = "src/provenance/scan.rs"]
#[allow(dead_code)]
mod scan;

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    constants(&root);
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

/// Every `.rs` file under `dir` (or `dir` itself), sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    if dir.is_file() {
        return vec![dir.to_path_buf()];
    }
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// Writes `OUT_DIR/constants.rs` (the scanned constants as `(file, name, item)`) and sets
/// `SOFTGRIP_CONSTANTS_DIGEST`.
fn constants(root: &Path) {
    let mut items = Vec::new();
    let mut list = String::from("&[\n");
    for scanned in scan::SCANNED {
        let path = root.join(scanned);
        println!("cargo::rerun-if-changed={}", path.display());
        for file in rust_files(&path) {
            let rel = file.strip_prefix(root).unwrap_or(&file).to_string_lossy();
            let rel = rel.replace('\\', "/");
            let text = std::fs::read_to_string(&file).unwrap_or_default();
            for (name, item) in scan::constants(&text) {
                list.push_str(&format!("    ({rel:?}, {name:?}, {item:?}),\n"));
                items.push((name, item));
            }
        }
    }
    list.push(']');
    let out = PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    std::fs::write(out.join("constants.rs"), list).expect("OUT_DIR/constants.rs");
    println!(
        "cargo::rustc-env=SOFTGRIP_CONSTANTS_DIGEST={}",
        scan::digest(&items)
    );
}
