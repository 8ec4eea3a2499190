//! Link latency: each sensor frame reaches the controller `delay_ticks` ticks after it
//! was taken (a serial link at a fixed baud rate plus buffering), so the command answers
//! an old load. Frames keep their order.

use super::spec::{Range, Settings};
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use super::{Effect, LinkFate};
use serde::Deserialize;
use softgrip::protocol::SensorFrame;
use std::collections::VecDeque;

/// `[effect.link_latency]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LinkLatencySettings {
    /// The delay \[ticks\], in [0, 1e5]; a fraction is dropped.
    pub delay_ticks: f64,
}

impl Default for LinkLatencySettings {
    fn default() -> Self {
        Self { delay_ticks: 2.0 }
    }
}

impl Settings for LinkLatencySettings {
    const NAME: &'static str = "link_latency";
    fn ranges(&self) -> Vec<Range> {
        vec![Range::new("delay_ticks", self.delay_ticks, 0.0, 1e5)]
    }
    fn build(&self, _: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(LinkLatency::new(self)))
    }
}

/// A delay line of frames.
#[derive(Debug)]
pub struct LinkLatency {
    delay_ticks: usize,
    queue: VecDeque<(SensorFrame, LinkFate)>,
}

impl LinkLatency {
    /// From its settings (`delay_ticks`, default 2).
    pub fn new(s: &LinkLatencySettings) -> Self {
        Self {
            delay_ticks: s.delay_ticks as usize,
            queue: VecDeque::new(),
        }
    }
}

impl Effect for LinkLatency {
    fn name(&self) -> &'static str {
        "link_latency"
    }
    fn link(&mut self, frames: &mut Vec<(SensorFrame, LinkFate)>) {
        self.queue.extend(frames.drain(..));
        while self.queue.len() > self.delay_ticks {
            if let Some(f) = self.queue.pop_front() {
                frames.push(f);
            }
        }
    }
}
