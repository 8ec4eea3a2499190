//! What the tests share: whether QEMU and the firmware they need are there, the check of
//! a generated block of a page, a run of the `host-sim` binary, a sample's command parts
//! as an array, and the brush fingers the calibration tests use. Each test binary uses
//! part of it.
#![allow(dead_code)]

use host_sim::link::qemu;
use host_sim::sim::record::Sample;
use std::path::PathBuf;
use std::process::Command;

/// Runs the `host-sim` binary with `args`: its exit code (-1 if a signal ended it),
/// stdout and stderr.
pub fn host_sim(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

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

/// The tests of one binary read the pages that others of them may rewrite.
static PAGE_LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Checks that the block of `page` (a path from the repository's root) between the
/// `markers` is `want`, generated from `source`; with `SOFTGRIP_WRITE_DOCS=1` rewrites it
/// instead. The error shows both blocks.
pub fn check_block(
    page: &str,
    markers: (&str, &str),
    want: &str,
    source: &str,
) -> Result<(), String> {
    let _page = PAGE_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(page);
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{page}: {e}"))?;
    let start = text
        .find(markers.0)
        .ok_or_else(|| format!("{page}: no `{}` marker", markers.0))?;
    let end = text[start..]
        .find(markers.1)
        .ok_or_else(|| format!("{page}: no `{}` marker", markers.1))?
        + start
        + markers.1.len();
    if &text[start..end] == want {
        return Ok(());
    }
    if std::env::var("SOFTGRIP_WRITE_DOCS").is_ok_and(|v| v == "1") {
        let new = format!("{}{want}{}", &text[..start], &text[end..]);
        std::fs::write(&path, new).map_err(|e| format!("{page}: {e}"))?;
        eprintln!("{page}: rewritten from {source}");
        return Ok(());
    }
    Err(format!(
        "{page}: the block between the `{}` markers is not what {source} gives \
         (SOFTGRIP_WRITE_DOCS=1 writes it):\n--- page\n{}\n--- {source}\n{want}",
        markers.0,
        &text[start..end]
    ))
}

/// softgrip's command parts of a sample, in the CSV's order: `[n_slip_n, required_n,
/// mu_hat, margin, slip_margin, load_factor, lead_n, n_slip_mu_n, n_safety_n, n_load_n]`.
pub fn parts(s: &Sample) -> [f32; 10] {
    let p = &s.parts;
    [
        p.n_slip_n,
        p.required_n,
        p.mu_hat,
        p.margin,
        p.slip_margin,
        p.load_factor,
        p.lead_n,
        p.n_slip_mu_n,
        p.n_safety_n,
        p.n_load_n,
    ]
}

/// The three brush fingers `brush_calibration.rs` calibrates softgrip on (a soft and a
/// stiff hemicylinder, a hemisphere) and `calibrate_contradiction.rs` fits at their shape:
/// name, finger TOML, half-length [m].
pub const BRUSH_FINGERS: [(&str, &str, f64); 3] = [
    (
        "soft hemicylinder",
        r#"
        [finger]
        model = "brush"
        shape = "rect"
        mu = 0.8
        half_length_m = 0.01
        young_modulus_pa = 3e5
        [finger.brush]
        radius_m = 0.01
        layer_thickness_m = 0.003
        mu_kinetic = 0.7
        height_m = 0.003
        "#,
        0.01,
    ),
    (
        "stiff hemicylinder",
        r#"
        [finger]
        model = "brush"
        shape = "rect"
        mu = 0.6
        half_length_m = 0.008
        young_modulus_pa = 2e6
        [finger.brush]
        radius_m = 0.008
        layer_thickness_m = 0.002
        stiffening_exponent = 1.5
        mu_kinetic = 0.55
        height_m = 0.002
        "#,
        0.008,
    ),
    (
        "hemisphere",
        r#"
        [finger]
        model = "brush"
        shape = "disc"
        mu = 1.0
        young_modulus_pa = 5e5
        [finger.brush]
        radius_m = 0.009
        layer_thickness_m = 0.003
        mu_kinetic = 0.9
        height_m = 0.003
        "#,
        0.01,
    ),
];
