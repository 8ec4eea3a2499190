//! Skewed pressure in the true contact (the paper's Eq. 6–9, 16, 17 as docs/model.md reads
//! them): under tangential load the pressure peak moves toward the edge, which changes
//! the true limit surface. The ground truth is then built from the skewed surface;
//! the controller is not told (it models the symmetric profile).

use super::{Effect, EffectSettings};
use crate::sim::scene::SceneError;
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
    pub fn build(s: &EffectSettings<'_>) -> Result<Self, SceneError> {
        s.check_keys(&["delta_over_a", "alpha", "locus_over_a"])?;
        let delta = s.param("delta_over_a", 0.9, 0.0, 0.999_999)?;
        let default_locus = if s.finger().shape == "disc" {
            0.0
        } else {
            delta / 2.0
        };
        Ok(Self {
            skew: SkewParams {
                delta_over_a: delta,
                alpha: s.param("alpha", 1.1, 1e-9, 1e9)?,
                locus_over_a: s.param("locus_over_a", default_locus, 0.0, 1.0)?,
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
