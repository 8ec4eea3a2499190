//! Link faults: on the serial line a frame may lose a byte's worth of bits (a bit flip),
//! be cut short (truncation: the receiver sees the delimiter early), or vanish (a dropped
//! frame). The damaged bytes really cross the link to the device, whose CRC and COBS
//! checks must catch them; the device counts them, and the plant counts what it dropped,
//! so every frame is accounted for.

use super::spec::{Range, Settings};
use super::{Effect, LinkFate};
use crate::sim::finger::Finger;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use softgrip::protocol::{encode, Request, SensorFrame, MAX_FRAME_LEN};

/// `[effect.link_faults]`: probabilities per frame, each in [0, 1].
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LinkFaultsSettings {
    /// A bit flip.
    pub bit_flip_prob: f64,
    /// A truncation.
    pub truncate_prob: f64,
    /// A drop.
    pub drop_prob: f64,
}

impl Default for LinkFaultsSettings {
    fn default() -> Self {
        Self {
            bit_flip_prob: 0.01,
            truncate_prob: 0.005,
            drop_prob: 0.005,
        }
    }
}

impl Settings for LinkFaultsSettings {
    const NAME: &'static str = "link_faults";
    fn ranges(&self) -> Vec<Range> {
        vec![
            Range::new("bit_flip_prob", self.bit_flip_prob, 0.0, 1.0),
            Range::new("truncate_prob", self.truncate_prob, 0.0, 1.0),
            Range::new("drop_prob", self.drop_prob, 0.0, 1.0),
        ]
    }
    fn build(&self, rng: ChaCha8Rng, _: &Finger) -> Result<Box<dyn Effect>, String> {
        Ok(Box::new(LinkFaults::new(self, rng)))
    }
}

/// Bit flips, truncation and drops.
#[derive(Debug)]
pub struct LinkFaults {
    bit_flip_prob: f64,
    truncate_prob: f64,
    drop_prob: f64,
    rng: ChaCha8Rng,
}

impl LinkFaults {
    /// From its settings (probabilities per frame: `bit_flip_prob`, `truncate_prob`,
    /// `drop_prob`; defaults in [`LinkFaultsSettings`]'s `Default`) and its random stream.
    pub fn new(s: &LinkFaultsSettings, rng: ChaCha8Rng) -> Self {
        Self {
            bit_flip_prob: s.bit_flip_prob,
            truncate_prob: s.truncate_prob,
            drop_prob: s.drop_prob,
            rng,
        }
    }
}

impl Effect for LinkFaults {
    fn name(&self) -> &'static str {
        "link_faults"
    }
    fn link(&mut self, frames: &mut Vec<(SensorFrame, LinkFate)>) {
        for (frame, fate) in frames.iter_mut() {
            if *fate != LinkFate::Deliver {
                continue;
            }
            let roll = self.rng.random::<f64>();
            if roll < self.drop_prob {
                *fate = LinkFate::Drop;
                continue;
            }
            let mut buf = [0u8; MAX_FRAME_LEN];
            let Ok(len) = encode(&Request::Sensor(*frame), &mut buf) else {
                continue;
            };
            let mut bytes = buf[..len].to_vec();
            if roll < self.drop_prob + self.truncate_prob {
                // Cut somewhere inside the frame and end it there.
                let cut = self.rng.random_range(1..len - 1);
                bytes.truncate(cut);
                bytes.push(0);
                *fate = LinkFate::Corrupt(bytes);
            } else if roll < self.drop_prob + self.truncate_prob + self.bit_flip_prob {
                // Flip one bit of the block (not the delimiter). A flip that would make a
                // byte 0x00 flips the next bit instead: a new delimiter would split the
                // frame in two, and the accounting counts frames, not pieces.
                let i = self.rng.random_range(0..len - 1);
                let mut bit = self.rng.random_range(0..8u32);
                if bytes[i] ^ (1 << bit) == 0 {
                    bit = (bit + 1) % 8;
                }
                bytes[i] ^= 1 << bit;
                *fate = LinkFate::Corrupt(bytes);
            }
        }
    }
}
