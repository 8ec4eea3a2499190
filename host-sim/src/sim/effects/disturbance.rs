//! External disturbances: bumps on the held object arriving as a Poisson process, each a
//! half-sine pulse of force (random direction in the contact plane) and moment (random
//! sign). A common test load for grasp stability (e.g. the impulsive disturbances of
//! slip-control experiments cited by the paper's introduction).

use super::{Effect, EffectSettings, World};
use crate::sim::scene::SceneError;
use rand::Rng;
use rand_chacha::ChaCha8Rng;

/// Random bumps.
#[derive(Debug)]
pub struct Disturbance {
    rate_hz: f64,
    force_n: f64,
    moment_nm: f64,
    duration_s: f64,
    rng: ChaCha8Rng,
    active: Vec<(f64, [f64; 2], f64)>,
}

impl Disturbance {
    /// Settings: `rate_hz` (2), `force_n` (1.0), `moment_nm` (0.01), `duration_s` (0.05).
    pub fn build(s: &EffectSettings<'_>) -> Result<Self, SceneError> {
        s.check_keys(&["rate_hz", "force_n", "moment_nm", "duration_s"])?;
        Ok(Self {
            rate_hz: s.param("rate_hz", 2.0, 0.0, 1e4)?,
            force_n: s.param("force_n", 1.0, 0.0, 1e6)?,
            moment_nm: s.param("moment_nm", 0.01, 0.0, 1e6)?,
            duration_s: s.param("duration_s", 0.05, 1e-6, 1e3)?,
            rng: s.rng(),
            active: Vec::new(),
        })
    }
}

impl Effect for Disturbance {
    fn name(&self) -> &'static str {
        "disturbance"
    }
    fn load(&mut self, w: &mut World) {
        if self.rng.random::<f64>() < self.rate_hz * w.dt_s {
            let angle = self.rng.random::<f64>() * std::f64::consts::TAU;
            let sign = if self.rng.random::<bool>() { 1.0 } else { -1.0 };
            self.active.push((
                w.t_s,
                [self.force_n * angle.cos(), self.force_n * angle.sin()],
                sign * self.moment_nm,
            ));
        }
        let d = self.duration_s;
        self.active.retain(|(t0, _, _)| w.t_s - t0 < d);
        for (t0, f, m) in &self.active {
            let s = (std::f64::consts::PI * (w.t_s - t0) / d).sin();
            w.force_n[0] += f[0] * s;
            w.force_n[1] += f[1] * s;
            w.moment_nm += m * s;
        }
    }
}
