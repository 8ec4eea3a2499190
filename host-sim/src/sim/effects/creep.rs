//! Viscoelastic creep of the contact size: a standard-linear-solid (Zener) response, the
//! Kelvin–Voigt element in series with a spring, as in the viscoelastic fingertip models
//! the paper cites (Kelvin–Voigt; Fung's quasi-linear viscoelasticity; Kao and Tiezzi).
//! When the normal force changes, a fraction `instant_fraction` of the change in contact
//! half-width happens at once and the rest relaxes with time constant `time_constant_s`:
//!
//! `a = φ·a_eq(N) + (1 − φ)·a_slow`, `τ·da_slow/dt = a_eq(N) − a_slow`,
//!
//! with `a_eq = c·N^γ`. Right after a squeeze the patch is smaller than the controller's
//! model assumes, so it resists less torsion.

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;

/// `[effect.creep]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CreepSettings {
    /// Relaxation time constant `τ` \[s\], in [1e-6, 1e6].
    pub time_constant_s: f64,
    /// The part `φ` of a change that happens at once, in [0, 1].
    pub instant_fraction: f64,
}

impl Default for CreepSettings {
    fn default() -> Self {
        Self {
            time_constant_s: 0.3,
            instant_fraction: 0.6,
        }
    }
}

impl Settings for CreepSettings {
    const NAME: &'static str = "creep";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new("time_constant_s", self.time_constant_s, 1e-6, 1e6),
            Range::new("instant_fraction", self.instant_fraction, 0.0, 1.0),
        ]
    }
    fn build(&self, _: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(Creep::new(self)))
    }
}

/// The creeping contact size.
#[derive(Debug)]
pub struct Creep {
    time_constant_s: f64,
    instant_fraction: f64,
    slow_m: Option<f64>,
}

impl Creep {
    /// From its settings: `time_constant_s`, `instant_fraction` (defaults in
    /// [`CreepSettings`]'s `Default`).
    pub fn new(s: &CreepSettings) -> Self {
        Self {
            time_constant_s: s.time_constant_s,
            instant_fraction: s.instant_fraction,
            slow_m: None,
        }
    }
}

impl Effect for Creep {
    fn name(&self) -> &'static str {
        "creep"
    }
    fn contact(&mut self, w: &mut World) {
        let eq = w.half_width_eq_m;
        let slow = self.slow_m.get_or_insert(eq);
        *slow += (eq - *slow) * (1.0 - (-w.dt_s / self.time_constant_s).exp());
        w.half_width_m = self.instant_fraction * eq + (1.0 - self.instant_fraction) * *slow;
    }
}
