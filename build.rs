//! Puts `memory.x` on the linker's search path for the firmware (cortex-m-rt's `link.x`
//! includes it). Host builds ignore it.

use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-env-changed=SOFTGRIP_TABLES_RS");
    if std::env::var_os("CARGO_FEATURE_PREBUILT_TABLES").is_some() {
        // The firmware's prebuilt tables: the file `host-sim tables --format rust` wrote.
        let Some(src) = std::env::var_os("SOFTGRIP_TABLES_RS") else {
            eprintln!(
                "feature prebuilt-tables needs SOFTGRIP_TABLES_RS=path/to/softgrip_tables.rs"
            );
            std::process::exit(1);
        };
        println!("cargo:rerun-if-changed={}", PathBuf::from(&src).display());
        let out = PathBuf::from(std::env::var("OUT_DIR").unwrap_or_default());
        if let Err(e) = std::fs::copy(&src, out.join("prebuilt_tables.rs")) {
            eprintln!("SOFTGRIP_TABLES_RS: {e}");
            std::process::exit(1);
        }
    }
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumb") {
        let out = PathBuf::from(std::env::var("OUT_DIR").unwrap_or_default());
        let _ = std::fs::copy("memory.x", out.join("memory.x"));
        println!("cargo:rustc-link-search={}", out.display());
    }
}
