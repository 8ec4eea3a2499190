//! Actuator lag and force limits: the gripper's drive follows the command as a first-order
//! lag with time constant `time_constant_s` (a current-controlled motor behind a
//! compliant transmission), at most `slew_n_per_s`, and within `[0, max_force_n]` (its
//! stall force).

use super::{Effect, EffectSettings, World};
use crate::sim::scene::SceneError;

/// First-order lag, slew limit and saturation.
#[derive(Debug)]
pub struct Actuator {
    time_constant_s: f64,
    slew_n_per_s: f64,
    max_force_n: f64,
}

impl Actuator {
    /// Settings: `time_constant_s` (0.02), `slew_n_per_s` (200), `max_force_n` (15).
    pub fn build(s: &EffectSettings<'_>) -> Result<Self, SceneError> {
        s.check_keys(&["time_constant_s", "slew_n_per_s", "max_force_n"])?;
        Ok(Self {
            time_constant_s: s.param("time_constant_s", 0.02, 0.0, 1e3)?,
            slew_n_per_s: s.param("slew_n_per_s", 200.0, 1e-6, 1e9)?,
            max_force_n: s.param("max_force_n", 15.0, 0.0, 1e9)?,
        })
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
