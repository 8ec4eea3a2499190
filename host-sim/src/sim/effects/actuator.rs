//! Actuator lag and force limits: the gripper's drive follows the command as a first-order
//! lag with time constant `time_constant_s` (a current-controlled motor behind a
//! compliant transmission), at most `slew_n_per_s`, and within `[0, max_force_n]` (its
//! stall force).

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;

/// `[effect.actuator]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ActuatorSettings {
    /// Time constant of the lag \[s\], in [0, 1e3] (0: none).
    pub time_constant_s: f64,
    /// Slew limit [N/s], in [1e-6, 1e9].
    pub slew_n_per_s: f64,
    /// Stall force \[N\], in [0, 1e9].
    pub max_force_n: f64,
}

impl Default for ActuatorSettings {
    fn default() -> Self {
        Self {
            time_constant_s: 0.02,
            slew_n_per_s: 200.0,
            max_force_n: 15.0,
        }
    }
}

impl Settings for ActuatorSettings {
    const NAME: &'static str = "actuator";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new("time_constant_s", self.time_constant_s, 0.0, 1e3),
            Range::new("slew_n_per_s", self.slew_n_per_s, 1e-6, 1e9),
            Range::new("max_force_n", self.max_force_n, 0.0, 1e9),
        ]
    }
    fn build(&self, _: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(Actuator::new(self)))
    }
}

/// First-order lag, slew limit and saturation.
#[derive(Debug)]
pub struct Actuator {
    time_constant_s: f64,
    slew_n_per_s: f64,
    max_force_n: f64,
}

impl Actuator {
    /// From its settings: `time_constant_s`, `slew_n_per_s`, `max_force_n` (defaults in
    /// [`ActuatorSettings`]'s `Default`).
    pub fn new(s: &ActuatorSettings) -> Self {
        Self {
            time_constant_s: s.time_constant_s,
            slew_n_per_s: s.slew_n_per_s,
            max_force_n: s.max_force_n,
        }
    }
}

impl Effect for Actuator {
    fn name(&self) -> &'static str {
        "actuator"
    }
    fn actuate(&mut self, w: &mut World) {
        let target = w.command_n.clamp(0.0, self.max_force_n);
        // Exact discretisation of the lag over one step.
        let alpha = if self.time_constant_s > 0.0 {
            1.0 - (-w.dt_s / self.time_constant_s).exp()
        } else {
            1.0
        };
        let step = (alpha * (target - w.normal_n))
            .clamp(-self.slew_n_per_s * w.dt_s, self.slew_n_per_s * w.dt_s);
        w.normal_n = (w.normal_n + step).clamp(0.0, self.max_force_n);
    }
}
