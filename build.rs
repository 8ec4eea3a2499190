//! Puts `memory.x` on the linker's search path for the firmware (cortex-m-rt's `link.x`
//! includes it). Host builds ignore it.

use std::path::PathBuf;

fn main() {
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    let target = std::env::var("TARGET").unwrap_or_default();
    if target.starts_with("thumb") {
        let out = PathBuf::from(std::env::var("OUT_DIR").unwrap_or_default());
        let _ = std::fs::copy("memory.x", out.join("memory.x"));
        println!("cargo:rustc-link-search={}", out.display());
    }
}
