//! Link latency: each sensor frame reaches the controller `delay_ticks` ticks after it
//! was taken (a serial link at a fixed baud rate plus buffering), so the command answers
//! an old load. Frames keep their order.

use super::{Effect, EffectSettings, LinkFate};
use crate::sim::scene::SceneError;
use softgrip::protocol::SensorFrame;
use std::collections::VecDeque;

/// A delay line of frames.
#[derive(Debug)]
pub struct LinkLatency {
    delay_ticks: usize,
    queue: VecDeque<(SensorFrame, LinkFate)>,
}

impl LinkLatency {
    /// Setting: `delay_ticks` (2).
    pub fn build(s: &EffectSettings<'_>) -> Result<Self, SceneError> {
        s.check_keys(&["delay_ticks"])?;
        let d = s.param("delay_ticks", 2.0, 0.0, 1e5)?;
        Ok(Self {
            delay_ticks: d as usize,
            queue: VecDeque::new(),
        })
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
