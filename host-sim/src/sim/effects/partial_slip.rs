//! Cattaneo–Mindlin partial slip (docs/model.md, the paper's Eq. 4 and 5): below gross slip the
//! contact's edge already slides, the stick zone shrinks to `â = a(1 − T/μN)^{1/3}`, and
//! the fingertip deflects tangentially by
//! `δ = 3μN/(16a)·((2−ν)/G)·[1 − (1 − T/μN)^{2/3}]`. The plant reports `δ` (the
//! micro-displacement a tactile sensor would see before the object moves); the largest
//! value is a run metric.

use super::spec::{Range, Settings};
use rand_chacha::ChaCha8Rng;
use super::{Effect, World};
use crate::sim::finger::Finger;
use serde::Deserialize;
use softgrip::partial_slip::{deflection_m, Elasticity};

/// `[effect.partial_slip]`: none (the effect uses the finger's elasticity).
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PartialSlipSettings {}

impl Settings for PartialSlipSettings {
    const NAME: &'static str = "partial_slip";
    fn ranges(&self) -> Vec<Range> {
        Vec::new()
    }
    fn build(&self, _: ChaCha8Rng, finger: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(PartialSlip::new(self, finger)?))
    }
}

/// The micro-displacement before gross slip.
#[derive(Debug)]
pub struct PartialSlip {
    elasticity: Elasticity<f64>,
    mu: f64,
}

impl PartialSlip {
    /// From the finger's `young_modulus_pa`, `poisson` and `mu`; no settings of its own.
    pub fn new(_: &PartialSlipSettings, finger: &Finger) -> Result<Self, String> {
        let elasticity = Elasticity::new(finger.young_modulus_pa, finger.poisson)
            .map_err(|e| format!("finger.{e}"))?;
        Ok(Self {
            elasticity,
            mu: finger.mu,
        })
    }
}

impl Effect for PartialSlip {
    fn name(&self) -> &'static str {
        "partial_slip"
    }
    fn contact(&mut self, w: &mut World) {
        let [fx, fy] = w.contact_force_n();
        let t = fx.hypot(fy);
        let limit = self.mu * w.normal_n;
        let ratio = if limit > 0.0 { t / limit } else { 1.0 };
        w.micro_slip_m = deflection_m(&self.elasticity, limit, w.half_width_m, ratio);
    }
}
