//! Skewed pressure in the true contact (the paper's Eq. 6–9, 16, 17 as docs/model.md reads
//! them): under tangential load the pressure peak moves toward the edge, which changes
//! the true limit surface. The ground truth is then built from the skewed surface;
//! the controller is not told (it models the symmetric profile).

use super::spec::{Range, Settings};
use super::Effect;
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use softgrip::controller::{FingerShape, SkewParams};

/// `[effect.skewed_pressure]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SkewedPressureSettings {
    /// Shift of the pressure peak `Δ/a`, in [0, 0.999999] (the top skew gives finite
    /// answers: `host-sim/tests/fls_cli.rs::hard_values_give_finite_answers`).
    pub delta_over_a: f64,
    /// Shape exponent `α`, in [1e-9, 1e9].
    pub alpha: f64,
    /// Locus of the skew `/a`, in [0, 1]; by default 0 on the disc (where a sideways
    /// locus folds the surface) and `Δ/2` on the rectangle (where it changes nothing).
    pub locus_over_a: Option<f64>,
}

impl Default for SkewedPressureSettings {
    fn default() -> Self {
        Self {
            delta_over_a: 0.9,
            alpha: 1.1,
            locus_over_a: None,
        }
    }
}

impl Settings for SkewedPressureSettings {
    const NAME: &'static str = "skewed_pressure";
    fn ranges(&self) -> Vec<Range> {
        let mut r = vec![
            Range::new("delta_over_a", self.delta_over_a, 0.0, 0.999_999),
            Range::new("alpha", self.alpha, 1e-9, 1e9),
        ];
        if let Some(locus) = self.locus_over_a {
            r.push(Range::new("locus_over_a", locus, 0.0, 1.0));
        }
        r
    }
    fn build(&self, _: ChaCha8Rng, finger: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(SkewedPressure::new(self, finger)))
    }
}

/// The true contact's skew.
#[derive(Debug)]
pub struct SkewedPressure {
    skew: SkewParams,
}

impl SkewedPressure {
    /// From its settings (`delta_over_a`, `alpha`, `locus_over_a`: by default 0 on the
    /// disc, where a sideways locus folds the surface, Δ/2 on the rectangle, where it
    /// changes nothing) and the finger's shape.
    pub fn new(s: &SkewedPressureSettings, finger: &Finger) -> Self {
        let delta = s.delta_over_a;
        let default_locus = if finger.shape == FingerShape::Disc {
            0.0
        } else {
            delta / 2.0
        };
        Self {
            skew: SkewParams {
                delta_over_a: delta,
                alpha: s.alpha,
                locus_over_a: s.locus_over_a.unwrap_or(default_locus),
            },
        }
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
