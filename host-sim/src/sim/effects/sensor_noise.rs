//! Sensor noise and bias: white Gaussian noise on every channel of the fingertip
//! force/torque sensor, plus a constant bias on the tangential force and the moment (the
//! usual error model of strain-gauge F/T sensors).

use super::{Effect, EffectSettings, World};
use crate::sim::scene::SceneError;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use softgrip::protocol::SensorFrame;

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
    /// Settings: `force_sd_n` (0.02), `moment_sd_nm` (2e-4), `normal_sd_n` (0.02),
    /// `bias_force_n` (0), `bias_moment_nm` (0).
    pub fn build(s: &EffectSettings<'_>) -> Result<Self, SceneError> {
        let e = "sensor_noise";
        s.check_keys(&[
            "force_sd_n",
            "moment_sd_nm",
            "normal_sd_n",
            "bias_force_n",
            "bias_moment_nm",
        ])?;
        let normal =
            |sd: f64| Normal::new(0.0, sd).map_err(|err| SceneError(format!("effect.{e}: {err}")));
        Ok(Self {
            force: normal(s.param("force_sd_n", 0.02, 0.0, 1e6)?)?,
            moment: normal(s.param("moment_sd_nm", 2e-4, 0.0, 1e6)?)?,
            normal: normal(s.param("normal_sd_n", 0.02, 0.0, 1e6)?)?,
            bias_force_n: s.param("bias_force_n", 0.0, -1e6, 1e6)?,
            bias_moment_nm: s.param("bias_moment_nm", 0.0, -1e6, 1e6)?,
            rng: s.rng(),
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
