//! Gravity and payload torque: the object's weight `m·g` on the grasp (vertical, across
//! the cylinder axis: the paper's Fig. 4 loading direction) and, with the centre of mass
//! `r` off the grasp axis, the payload torque `m·g·r` about it (statics).
//!
//! The weight comes onto the grasp as the object leaves its support: the scene's
//! `support_fraction` (0 on the table, 1 once lifted) scales both.

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;

/// `[effect.gravity]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GravitySettings {
    /// Gravitational acceleration [m/s²], in [0, 1e3].
    pub g_m_s2: f64,
}

impl Default for GravitySettings {
    fn default() -> Self {
        Self { g_m_s2: 9.81 }
    }
}

impl Settings for GravitySettings {
    const NAME: &'static str = "gravity";
    fn ranges(&self) -> Vec<Range> {
        vec![Range::new("g_m_s2", self.g_m_s2, 0.0, 1e3)]
    }
    fn build(&self, _: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(Gravity::new(self)))
    }
}

/// Weight and payload torque.
#[derive(Debug)]
pub struct Gravity {
    g_m_s2: f64,
}

impl Gravity {
    /// From its settings (`g_m_s2`; default in [`GravitySettings`]'s `Default`).
    pub fn new(s: &GravitySettings) -> Self {
        Self { g_m_s2: s.g_m_s2 }
    }
}

impl Effect for Gravity {
    fn name(&self) -> &'static str {
        "gravity"
    }
    fn load(&mut self, w: &mut World) {
        let weight = w.mass_kg * self.g_m_s2 * w.support_fraction;
        w.force_n[1] += weight;
        w.moment_nm += weight * w.com_offset_m;
    }
}
