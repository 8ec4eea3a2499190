//! A seeded normal variate for the closed-loop suites (`tests/actuator_id.rs`,
//! `tests/load_margin.rs`): Box–Muller over a 64-bit LCG, so every run draws the same
//! sensor noise.
//!
//! Included with `#[path = "common/noise.rs"] mod noise;`.

/// A seeded normal variate (Box–Muller over a 64-bit LCG); the field is the seed.
pub struct Noise(pub u64);

impl Noise {
    /// A uniform variate in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// A standard normal variate.
    pub fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}
