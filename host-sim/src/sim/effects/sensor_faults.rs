//! Sensor faults: dropouts (the sensor repeats its last frame, timestamp included: the
//! controller sees stale input), NaN readings (a broken channel or a bus glitch), and
//! saturation (every channel clipped at the sensor's range, silently, as an overloaded
//! strain gauge does).

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use softgrip::protocol::SensorFrame;

/// `[effect.sensor_faults]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorFaultsSettings {
    /// Probability of a dropout per frame, in [0, 1].
    pub dropout_prob: f64,
    /// Probability of a NaN reading per frame, in [0, 1].
    pub nan_prob: f64,
    /// Saturation of the force channels \[N\], at least 0 (infinite: off).
    pub saturation_n: f64,
    /// Saturation of the moment channel [N·m], at least 0 (infinite: off).
    pub saturation_nm: f64,
}

impl Default for SensorFaultsSettings {
    fn default() -> Self {
        Self {
            dropout_prob: 0.01,
            nan_prob: 0.005,
            saturation_n: f64::INFINITY,
            saturation_nm: f64::INFINITY,
        }
    }
}

impl Settings for SensorFaultsSettings {
    const NAME: &'static str = "sensor_faults";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new("dropout_prob", self.dropout_prob, 0.0, 1.0),
            Range::new("nan_prob", self.nan_prob, 0.0, 1.0),
            Range::new("saturation_n", self.saturation_n, 0.0, f64::INFINITY),
            Range::new("saturation_nm", self.saturation_nm, 0.0, f64::INFINITY),
        ]
    }
    fn build(&self, rng: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(SensorFaults::new(self, rng)))
    }
}

/// Dropouts, NaN and saturation.
#[derive(Debug)]
pub struct SensorFaults {
    dropout_prob: f64,
    nan_prob: f64,
    saturation_n: f64,
    saturation_nm: f64,
    last: Option<SensorFrame>,
    rng: ChaCha8Rng,
}

impl SensorFaults {
    /// From its settings (`dropout_prob` and `nan_prob` per frame, `saturation_n` and
    /// `saturation_nm`, infinite for off; defaults in [`SensorFaultsSettings`]'s `Default`)
    /// and its random stream.
    pub fn new(s: &SensorFaultsSettings, rng: ChaCha8Rng) -> Self {
        Self {
            dropout_prob: s.dropout_prob,
            nan_prob: s.nan_prob,
            saturation_n: s.saturation_n,
            saturation_nm: s.saturation_nm,
            last: None,
            rng,
        }
    }
}

impl Effect for SensorFaults {
    fn name(&self) -> &'static str {
        "sensor_faults"
    }
    fn sense(&mut self, _w: &World, frame: &mut SensorFrame) {
        let sat_f = self.saturation_n as f32;
        let sat_m = self.saturation_nm as f32;
        for f in &mut frame.tangential_force_n {
            *f = f.clamp(-sat_f, sat_f);
        }
        frame.normal_force_n = frame.normal_force_n.clamp(-sat_f, sat_f);
        frame.torsional_moment_nm = frame.torsional_moment_nm.clamp(-sat_m, sat_m);
        let seq = frame.seq;
        if let Some(last) = self
            .last
            .filter(|_| self.rng.random::<f64>() < self.dropout_prob)
        {
            // The sensor repeats its previous reading; only the link's sequence number is
            // new.
            *frame = SensorFrame { seq, ..last };
        } else if self.rng.random::<f64>() < self.nan_prob {
            match self.rng.random_range(0..4) {
                0 => frame.tangential_force_n[0] = f32::NAN,
                1 => frame.tangential_force_n[1] = f32::NAN,
                2 => frame.torsional_moment_nm = f32::NAN,
                _ => frame.normal_force_n = f32::NAN,
            }
        }
        self.last = Some(*frame);
    }
}
