//! `tables verify FILE`: a blob's tables against a fresh f64 precomputation of its
//! configuration.

use crate::CliError;
use softgrip::controller::blob::Blob;
use softgrip::controller::{Controller, Tables};
use std::path::Path;

/// Largest relative deviation between two tables.
pub fn deviation(a: &Tables<'_, f32>, b: &Tables<'_, f32>) -> Option<(f64, &'static str)> {
    let mut worst = (0.0f64, "none");
    let pairs: [(&'static str, &[f32], &[f32]); 4] = [
        ("force_n", a.force_n, b.force_n),
        ("arm_m", a.arm_m, b.arm_m),
        ("inv_arm_per_m", a.inv_arm_per_m, b.inv_arm_per_m),
        ("aspect_pos", a.aspect_pos, b.aspect_pos),
    ];
    for (name, x, y) in pairs {
        if x.len() != y.len() {
            return None;
        }
        for (p, q) in x.iter().zip(y) {
            let d = (f64::from(*p) - f64::from(*q)).abs() / f64::from(q.abs()).max(1e-12);
            if d > worst.0 {
                worst = (d, name);
            }
        }
    }
    if a.inv_radius.len() != b.inv_radius.len() {
        return None;
    }
    for (r, s) in a.inv_radius.iter().zip(b.inv_radius) {
        for (p, q) in r.iter().zip(s) {
            let d = (f64::from(*p) - f64::from(*q)).abs() / f64::from(q.abs()).max(1e-12);
            if d > worst.0 {
                worst = (d, "inv_radius");
            }
        }
    }
    Some(worst)
}

/// The largest relative deviation `verify` accepts: f32 rounding of an f32 or f64
/// precomputation.
pub const VERIFY_TOLERANCE: f64 = 1e-4;

pub(super) fn verify(file: &Path) -> Result<(), CliError> {
    let bytes = crate::input::read_capped(file, "verify", crate::input::BLOB_CAP_BYTES)
        .map_err(|e| CliError::Failed(e.to_string()))?;
    let blob =
        Blob::parse(&bytes).map_err(|e| CliError::Failed(format!("{}: {e}", file.display())))?;
    let cfg = blob.config();
    let failed = |e: &dyn std::fmt::Display| CliError::Failed(format!("{}: {e}", file.display()));
    let cfg = cfg.check().map_err(|e| failed(&e))?;
    let fresh = Controller::<f32>::from_checked_in::<f64>(&cfg).map_err(|e| failed(&e))?;
    let (dev, what) = deviation(&blob.tables(), &fresh.capacity().tables()).ok_or_else(|| {
        CliError::Failed(format!(
            "{}: the table sizes do not match a recomputation",
            file.display()
        ))
    })?;
    println!(
        "{}: valid blob; largest deviation from an f64 recomputation {dev:.2e} (in {what})",
        file.display()
    );
    if dev > VERIFY_TOLERANCE {
        return Err(CliError::Failed(format!(
            "{}: deviation {dev:.2e} in {what} exceeds {VERIFY_TOLERANCE:.0e}: mismatched tables",
            file.display()
        )));
    }
    Ok(())
}
