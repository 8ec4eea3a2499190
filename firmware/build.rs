//! Puts the repository's `memory.x` on the linker's search path and links with
//! cortex-m-rt's `link.x` (which includes it), for the firmware on the target. With the
//! feature `prebuilt-tables`, copies the tables file named by `SOFTGRIP_TABLES_RS` into
//! `OUT_DIR`. Host builds do neither.

use std::path::PathBuf;

fn main() {
    let manifest = PathBuf::from(std::env::var("CARGO_MANIFEST_DIR").unwrap_or_default());
    // The memory map stays at the repository root (the layout requires it there).
    let memory_x = manifest.join("../memory.x");
    println!("cargo:rerun-if-changed={}", memory_x.display());
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=SOFTGRIP_TABLES_RS");
    // Variants that pick the same thing are refused together, rather than one silently
    // winning.
    let on = |f: &str| std::env::var_os(format!("CARGO_FEATURE_{f}")).is_some();
    for (a, b, what) in [
        ("FAST_MATH", "SOFT_SQRT", "the tick's square root"),
        (
            "PRECOMPUTE_F64",
            "PREBUILT_TABLES",
            "how the tables are made",
        ),
        (
            "BOARD",
            "SQRT_CHECK",
            "what the firmware runs on (a board that resets, or the emulator's semihosting)",
        ),
    ] {
        if on(a) && on(b) {
            let name = |f: &str| f.to_lowercase().replace('_', "-");
            eprintln!(
                "features `{}` and `{}` each pick {what}: enable one",
                name(a),
                name(b)
            );
            std::process::exit(1);
        }
    }
    let out = PathBuf::from(std::env::var("OUT_DIR").unwrap_or_default());
    if std::env::var_os("CARGO_FEATURE_PREBUILT_TABLES").is_some() {
        // The firmware's prebuilt tables: the file `host-sim tables --format rust` wrote.
        let Some(src) = std::env::var_os("SOFTGRIP_TABLES_RS") else {
            eprintln!(
                "feature prebuilt-tables needs SOFTGRIP_TABLES_RS=path/to/softgrip_tables.rs"
            );
            std::process::exit(1);
        };
        println!("cargo:rerun-if-changed={}", PathBuf::from(&src).display());
        if let Err(e) = std::fs::copy(&src, out.join("prebuilt_tables.rs")) {
            eprintln!("SOFTGRIP_TABLES_RS: {e}");
            std::process::exit(1);
        }
    }
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumb") {
        if let Err(e) = std::fs::copy(&memory_x, out.join("memory.x")) {
            eprintln!("{}: {e}", memory_x.display());
            std::process::exit(1);
        }
        // cortex-m-rt's `device` feature includes `device.x` for the interrupt handlers'
        // names; the firmware handles no interrupt, so it names none (src/interrupts.rs).
        if let Err(e) = std::fs::write(out.join("device.x"), "/* no interrupt handlers */\n") {
            eprintln!("device.x: {e}");
            std::process::exit(1);
        }
        println!("cargo:rustc-link-search={}", out.display());
        println!("cargo:rustc-link-arg-bins=-Tlink.x");
        if std::env::var_os("CARGO_FEATURE_DEFMT").is_some() {
            // defmt's string table (the defmt crate puts defmt.x on the search path).
            println!("cargo:rustc-link-arg-bins=-Tdefmt.x");
        }
    }
}
