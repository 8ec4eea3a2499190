//! Sensor noise and bias: white Gaussian noise on every channel of the fingertip
//! force/torque sensor, plus a constant bias on the tangential force and the moment (the
//! usual error model of strain-gauge F/T sensors).

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use serde::Deserialize;
use softgrip::protocol::SensorFrame;

/// `[effect.sensor_noise]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorNoiseSettings {
    /// Standard deviation of the tangential force's noise \[N\], in [0, 1e6].
    pub force_sd_n: f64,
    /// Standard deviation of the moment's noise [N·m], in [0, 1e6].
    pub moment_sd_nm: f64,
    /// Standard deviation of the normal force's noise \[N\], in [0, 1e6].
    pub normal_sd_n: f64,
    /// Bias of the tangential force \[N\], in [-1e6, 1e6].
    pub bias_force_n: f64,
    /// Bias of the moment [N·m], in [-1e6, 1e6].
    pub bias_moment_nm: f64,
}

impl Default for SensorNoiseSettings {
    fn default() -> Self {
        Self {
            force_sd_n: 0.02,
            moment_sd_nm: 2e-4,
            normal_sd_n: 0.02,
            bias_force_n: 0.0,
            bias_moment_nm: 0.0,
        }
    }
}

impl Settings for SensorNoiseSettings {
    const NAME: &'static str = "sensor_noise";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new("force_sd_n", self.force_sd_n, 0.0, 1e6),
            Range::new("moment_sd_nm", self.moment_sd_nm, 0.0, 1e6),
            Range::new("normal_sd_n", self.normal_sd_n, 0.0, 1e6),
            Range::new("bias_force_n", self.bias_force_n, -1e6, 1e6),
            Range::new("bias_moment_nm", self.bias_moment_nm, -1e6, 1e6),
        ]
    }
    fn build(&self, rng: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(SensorNoise::new(self, rng)?))
    }
}

/// Gaussian noise and bias.
#[derive(Debug)]
pub struct SensorNoise {
    force: Normal<f64>,
    moment: Normal<f64>,
    normal: Normal<f64>,
    bias_force_n: f64,
    bias_moment_nm: f64,
    rng: ChaCha8Rng,
}

impl SensorNoise {
    /// From its settings (`force_sd_n`, `moment_sd_nm`, `normal_sd_n`, `bias_force_n`,
    /// `bias_moment_nm`; defaults in [`SensorNoiseSettings`]'s `Default`) and its random
    /// stream.
    pub fn new(s: &SensorNoiseSettings, rng: ChaCha8Rng) -> Result<Self, String> {
        let normal = |key: &str, sd: f64| {
            Normal::new(0.0, sd).map_err(|err| format!("effect.sensor_noise.{key}: {err}"))
        };
        Ok(Self {
            force: normal("force_sd_n", s.force_sd_n)?,
            moment: normal("moment_sd_nm", s.moment_sd_nm)?,
            normal: normal("normal_sd_n", s.normal_sd_n)?,
            bias_force_n: s.bias_force_n,
            bias_moment_nm: s.bias_moment_nm,
            rng,
        })
    }
}

impl Effect for SensorNoise {
    fn name(&self) -> &'static str {
        "sensor_noise"
    }
    fn sense(&mut self, _w: &World, frame: &mut SensorFrame) {
        let r = &mut self.rng;
        for f in &mut frame.tangential_force_n {
            *f += (self.force.sample(r) + self.bias_force_n / std::f64::consts::SQRT_2) as f32;
        }
        frame.torsional_moment_nm += (self.moment.sample(r) + self.bias_moment_nm) as f32;
        frame.normal_force_n += self.normal.sample(r) as f32;
    }
}
