//! External disturbances: bumps on the held object arriving as a Poisson process, each a
//! half-sine pulse of force (random direction in the contact plane) and moment (random
//! sign). A common test load for grasp stability (e.g. the impulsive disturbances of
//! slip-control experiments cited by the paper's introduction).

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;

/// `[effect.disturbance]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DisturbanceSettings {
    /// Mean rate of bumps \[Hz\], in [0, 1e4].
    pub rate_hz: f64,
    /// Peak force of a bump \[N\], in [0, 1e6].
    pub force_n: f64,
    /// Peak moment of a bump [N·m], in [0, 1e6].
    pub moment_nm: f64,
    /// Length of a bump \[s\], in [1e-6, 1e3].
    pub duration_s: f64,
}

impl Default for DisturbanceSettings {
    fn default() -> Self {
        Self {
            rate_hz: 2.0,
            force_n: 1.0,
            moment_nm: 0.01,
            duration_s: 0.05,
        }
    }
}

impl Settings for DisturbanceSettings {
    const NAME: &'static str = "disturbance";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new("rate_hz", self.rate_hz, 0.0, 1e4),
            Range::new("force_n", self.force_n, 0.0, 1e6),
            Range::new("moment_nm", self.moment_nm, 0.0, 1e6),
            Range::new("duration_s", self.duration_s, 1e-6, 1e3),
        ]
    }
    fn build(&self, rng: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(Disturbance::new(self, rng)))
    }
}

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
    /// From its settings (`rate_hz`, `force_n`, `moment_nm`, `duration_s`; defaults in
    /// [`DisturbanceSettings`]'s `Default`) and its random stream.
    pub fn new(s: &DisturbanceSettings, rng: ChaCha8Rng) -> Self {
        Self {
            rate_hz: s.rate_hz,
            force_n: s.force_n,
            moment_nm: s.moment_nm,
            duration_s: s.duration_s,
            rng,
            active: Vec::new(),
        }
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
