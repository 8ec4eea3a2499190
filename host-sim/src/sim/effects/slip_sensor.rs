//! A tactile slip sensor: the frame's slip signal ([`SlipSignal`]) from the true state of
//! the contact, as the incipient-slip detectors of tactile fingertips report it: the
//! vibration and micro-vibration signatures of the stick–slip transition seen by
//! piezoelectric or MEMS skins (Howe & Cutkosky, "Sensing skin acceleration for slip and
//! texture perception", ICRA 1989; Romano et al., "Human-inspired robotic grasp control
//! with tactile sensing", IEEE T-RO 27(6), 2011), and the incipient slip found from the
//! shrinking stick region of the patch before gross slip (Dong, Yuan & Adelson, "Maintaining
//! grasps with a GelSight tactile sensor", IROS 2018).
//!
//! - `Gross` while the object slides relative to the fingertips (true utilisation > 1);
//! - `Incipient` while the true utilisation exceeds `incipient_utilisation` without
//!   sliding;
//! - `None` otherwise.
//!
//! Imperfections, each a scene setting:
//! - `latency_s` \[s\]: the signal reports the contact as it was this long before
//!   (rounded to whole ticks, at least one tick: the sensor sees the previous step's
//!   contact);
//! - `miss_probability`, **per episode**: when the true signal turns on (from `None` to
//!   `Incipient` or `Gross`), with this probability the whole episode, until the true
//!   signal is `None` again, goes unreported;
//! - `false_alarm_rate_hz` \[Hz\]: a Poisson process of false `Incipient` reports, each
//!   one tick long, while the true signal is `None`.
//!
//! The defaults are [`SlipSensorSettings`]'s `Default`.
//!
//! It draws from its own random stream (seeded from the scene seed and its name), so
//! listing it changes no other effect's random numbers.

use super::spec::{Range, Settings};
use super::{Effect, World};
use crate::sim::finger::Finger;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use softgrip::protocol::{SensorFrame, SlipSignal};
use std::collections::VecDeque;

/// `[effect.slip_sensor]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SlipSensorSettings {
    /// The true utilisation above which it reports `Incipient`, in [0, 1].
    pub incipient_utilisation: f64,
    /// How late it reports \[s\], in [0, 10].
    pub latency_s: f64,
    /// Probability of missing a whole episode, in [0, 1].
    pub miss_probability: f64,
    /// Rate of false `Incipient` reports \[Hz\], in [0, 1e4].
    pub false_alarm_rate_hz: f64,
}

impl Default for SlipSensorSettings {
    fn default() -> Self {
        Self {
            incipient_utilisation: 0.9,
            latency_s: 0.005,
            miss_probability: 0.05,
            false_alarm_rate_hz: 0.2,
        }
    }
}

impl Settings for SlipSensorSettings {
    const NAME: &'static str = "slip_sensor";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new(
                "incipient_utilisation",
                self.incipient_utilisation,
                0.0,
                1.0,
            ),
            Range::new("latency_s", self.latency_s, 0.0, 10.0),
            Range::new("miss_probability", self.miss_probability, 0.0, 1.0),
            Range::new("false_alarm_rate_hz", self.false_alarm_rate_hz, 0.0, 1e4),
        ]
    }
    fn build(&self, rng: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(SlipSensor::new(self, rng)))
    }
}

/// The slip sensor.
#[derive(Debug)]
pub struct SlipSensor {
    incipient_utilisation: f64,
    latency_s: f64,
    miss_probability: f64,
    false_alarm_rate_hz: f64,
    rng: ChaCha8Rng,
    /// Whether the current true episode is being missed.
    missing: bool,
    /// The previous tick's true signal (episode starts).
    last_true: SlipSignal,
    /// Signals waiting out the latency, oldest first.
    pending: VecDeque<SlipSignal>,
}

impl SlipSensor {
    /// From its settings (`incipient_utilisation`, `latency_s`, `miss_probability` per
    /// episode, `false_alarm_rate_hz`; defaults in [`SlipSensorSettings`]'s `Default`) and
    /// its random stream.
    pub fn new(s: &SlipSensorSettings, rng: ChaCha8Rng) -> Self {
        Self {
            incipient_utilisation: s.incipient_utilisation,
            latency_s: s.latency_s,
            miss_probability: s.miss_probability,
            false_alarm_rate_hz: s.false_alarm_rate_hz,
            rng,
            missing: false,
            last_true: SlipSignal::None,
            pending: VecDeque::with_capacity(16),
        }
    }

    /// The true signal for a contact at utilisation `u` [-], sliding or not.
    pub fn true_signal(&self, u: f64, sliding: bool) -> SlipSignal {
        if sliding {
            SlipSignal::Gross
        } else if u > self.incipient_utilisation {
            SlipSignal::Incipient
        } else {
            SlipSignal::None
        }
    }
}

impl Effect for SlipSensor {
    fn name(&self) -> &'static str {
        "slip_sensor"
    }
    fn sense(&mut self, w: &World, frame: &mut SensorFrame) {
        let truth = self.true_signal(w.true_utilisation, w.sliding);
        if truth != SlipSignal::None && self.last_true == SlipSignal::None {
            self.missing = self.rng.random::<f64>() < self.miss_probability;
        }
        self.last_true = truth;
        let reported = if truth == SlipSignal::None {
            let p = self.false_alarm_rate_hz * w.dt_s;
            if p > 0.0 && self.rng.random::<f64>() < p {
                SlipSignal::Incipient
            } else {
                SlipSignal::None
            }
        } else if self.missing {
            SlipSignal::None
        } else {
            truth
        };
        // The world holds the previous step's contact: one tick of the latency is spent.
        let delay = ((self.latency_s / w.dt_s).round() as usize).saturating_sub(1);
        self.pending.push_back(reported);
        frame.slip = if self.pending.len() > delay {
            self.pending.pop_front().unwrap_or_default()
        } else {
            SlipSignal::None
        };
    }
}
