//! The finger of `experiment`: from a scene or finger TOML (`--finger`: its `[finger]`
//! table, and `[effect.skewed_pressure]` when its `effects` list the skew, read as the
//! simulator reads them) or from the flags.

use super::FingerArgs;
use crate::brush::BrushFinger;
use crate::experiment::FingerSpec;
use crate::finger_file::FingerFile;
use crate::sim::effects::skewed_pressure::{SkewedPressure, SkewedPressureSettings};
use crate::sim::effects::Effect;
use crate::CliError;
use softgrip::controller::{FingerShape, SkewParams};
use std::path::Path;

/// The brush finger of `--finger` (a scene or finger file whose `[finger]` has
/// `model = "brush"`).
pub fn brush(args: &FingerArgs) -> Result<BrushFinger, CliError> {
    let Some(path) = &args.finger else {
        return Err(CliError::Usage(
            "--plant brush needs --finger FILE: a scene or finger file with \
             [finger] model = \"brush\" (e.g. host-sim/scenes/brush_lift_hold.toml)"
                .into(),
        ));
    };
    let usage = |m: String| CliError::Usage(format!("--finger: {}: {m}", path.display()));
    let f = FingerFile::load(path, "--finger")?;
    f.finger
        .brush_finger()
        .map_err(|e| usage(e.to_string()))?
        .ok_or_else(|| usage("--plant brush: [finger] has no model = \"brush\"".into()))
}

fn from_file(path: &Path) -> Result<FingerSpec, CliError> {
    let usage = |m: String| CliError::Usage(format!("--finger: {}: {m}", path.display()));
    let f = FingerFile::load(path, "--finger")?;
    let skew = if f.effects.iter().any(|e| e == "skewed_pressure") {
        let table = f.effect.get("skewed_pressure").cloned().unwrap_or_default();
        let settings: SkewedPressureSettings =
            toml::Value::Table(table)
                .try_into()
                .map_err(|e: toml::de::Error| {
                    usage(format!("effect.skewed_pressure: {}", e.message().trim()))
                })?;
        SkewedPressure::new(&settings, &f.finger).true_skew()
    } else {
        None
    };
    let g = &f.finger;
    Ok(FingerSpec {
        shape: g.shape,
        mu: g.mu,
        k: g.k,
        c: g.c,
        gamma: g.gamma,
        half_length_m: g.half_length_m,
        skew,
    })
}

/// The finger the arguments describe.
pub fn spec(args: &FingerArgs) -> Result<FingerSpec, CliError> {
    if let Some(path) = &args.finger {
        return from_file(path);
    }
    let shape = args.shape.unwrap_or(FingerShape::Rect);
    let delta = args.skew.unwrap_or(0.0);
    let default_locus = if shape == FingerShape::Disc {
        0.0
    } else {
        delta / 2.0
    };
    Ok(FingerSpec {
        shape,
        mu: args.mu.unwrap_or(0.8),
        k: args.k.unwrap_or(2.0),
        c: args.c.unwrap_or(2.5e-3),
        gamma: args.gamma.unwrap_or(0.5),
        half_length_m: args.half_length.unwrap_or(0.01),
        skew: (delta != 0.0).then_some(SkewParams {
            delta_over_a: delta,
            alpha: args.alpha.unwrap_or(1.1),
            locus_over_a: args.locus.unwrap_or(default_locus),
        }),
    })
}
