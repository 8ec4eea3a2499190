//! Skewed pressure in the true contact (the paper's Eq. 6–9, 16, 17 as docs/model.md reads
//! them): under tangential load the pressure peak moves toward the edge, which changes
//! the true limit surface. The ground truth is then built from the skewed surface;
//! the controller is not told (it models the symmetric profile).

use super::{check_keys, Effect};
use crate::sim::scene::{Scene, SceneError};
use softgrip::controller::SkewParams;

/// The true contact's skew.
#[derive(Debug)]
pub struct SkewedPressure {
    skew: SkewParams,
}

impl SkewedPressure {
    /// Settings: `delta_over_a` (0.9), `alpha` (1.1), `locus_over_a` (0 on the disc,
    /// where a sideways locus folds the surface; Δ/2 on the rectangle, where it changes
    /// nothing).
    pub fn build(scene: &Scene, text: Option<&str>) -> Result<Self, SceneError> {
        let e = "skewed_pressure";
        check_keys(scene, e, &["delta_over_a", "alpha", "locus_over_a"])?;
        let delta = scene.effect_param(text, e, "delta_over_a", 0.9, 0.0, 0.999_999)?;
        let default_locus = if scene.finger.shape == "disc" {
            0.0
        } else {
            delta / 2.0
        };
        Ok(Self {
            skew: SkewParams {
                delta_over_a: delta,
                alpha: scene.effect_param(text, e, "alpha", 1.1, 1e-9, 1e9)?,
                locus_over_a: scene.effect_param(
                    text,
                    e,
                    "locus_over_a",
                    default_locus,
                    0.0,
                    1.0,
                )?,
            },
        })
    }
}

impl Effect for SkewedPressure {
    fn name(&self) -> &'static str {
        "skewed_pressure"
    }
    fn true_skew(&self) -> Option<SkewParams> {
        Some(self.skew)
    }
}
