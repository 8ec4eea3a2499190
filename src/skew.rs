//! Where the pressure peak sits as the centre of rotation moves: the skew law (Eq. 17) and
//! the locus of the peak (Eq. 16).
//!
//! `Δy = Δ · tanh(α · d_c / a)` and `Δx = (h/(Δ/2)) · sqrt((Δ/2)² − (Δy − Δ/2)²)`; all
//! lengths here are normalised by the contact half-width `a`. On the rectangle only `Δy`
//! matters (the profile depends on `y` alone); on the disc `Δx` moves the peak off the axis.

use crate::error::{check, ConfigError};
use crate::real::Real;

/// Validated skew parameters: the largest skew `Δ/a ∈ [0, 1)`, the rate `α > 0` and the
/// locus half-axis `h/a ≥ 0`. The paper's values are `Δ/a = 0.9`, `α = 1.1` and a circular
/// locus, `h = Δ/2`
/// (tests/fls_properties.rs::paper_cases_are_monotone_convex_and_inside_the_ellipse).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkewLaw<T> {
    delta_over_a: T,
    alpha: T,
    locus_h_over_a: T,
}

impl<T: Real> SkewLaw<T> {
    /// Validates the three parameters (names: `skew`, `alpha`, `locus`).
    pub fn new(delta_over_a: f64, alpha: f64, locus_h_over_a: f64) -> Result<Self, ConfigError> {
        check(
            "skew",
            delta_over_a,
            (0.0..1.0).contains(&delta_over_a),
            "0 <= skew < 1",
        )?;
        check(
            "alpha",
            alpha,
            alpha > 0.0 && alpha.is_finite(),
            "alpha > 0",
        )?;
        check(
            "locus",
            locus_h_over_a,
            locus_h_over_a >= 0.0 && locus_h_over_a.is_finite(),
            "locus >= 0",
        )?;
        Ok(Self {
            delta_over_a: T::of(delta_over_a),
            alpha: T::of(alpha),
            locus_h_over_a: T::of(locus_h_over_a),
        })
    }

    /// The paper's circular locus (`h = Δ/2`) for a given `Δ/a` and `α`.
    pub fn circular(delta_over_a: f64, alpha: f64) -> Result<Self, ConfigError> {
        Self::new(delta_over_a, alpha, delta_over_a / 2.0)
    }

    /// The largest distance `|(Δx, Δy)|/a` of the peak from the patch centre along the whole
    /// locus, found by sampling the path at 1024 points (start-up cost only). The disc needs
    /// it below 1.
    pub fn max_peak_radius(&self) -> f64 {
        let delta = self.delta_over_a.to_f64();
        let h = self.locus_h_over_a.to_f64();
        (0..=1024)
            .map(|i| {
                let dy = delta * i as f64 / 1024.0;
                let dx = if delta > 0.0 {
                    h / (delta / 2.0) * libm::sqrt((dy * (delta - dy)).max(0.0))
                } else {
                    0.0
                };
                libm::hypot(dx, dy)
            })
            .fold(0.0, f64::max)
    }

    /// `Δ/a`.
    pub fn delta_over_a(&self) -> T {
        self.delta_over_a
    }

    /// `α`.
    pub fn alpha(&self) -> T {
        self.alpha
    }

    /// `h/a`.
    pub fn locus_h_over_a(&self) -> T {
        self.locus_h_over_a
    }

    /// `Δy/a` at the normalised centre-of-rotation distance `d = d_c/a ≥ 0` (Eq. 17). In
    /// `[0, Δ/a]`; `d = ∞` gives `Δ/a`.
    pub fn delta_y(&self, d: T) -> T {
        self.delta_over_a * (self.alpha * d.max(T::zero())).libm_tanh()
    }

    /// `Δx/a` on the locus for a given `Δy/a` (Eq. 16): zero at both ends of the path.
    pub fn delta_x(&self, delta_y: T) -> T {
        let half = self.delta_over_a * T::of(0.5);
        if half == T::zero() {
            return T::zero();
        }
        // (Δ/2)² − (Δy − Δ/2)² = Δy (Δ − Δy), free of cancellation.
        let under = (delta_y * (self.delta_over_a - delta_y)).max(T::zero());
        self.locus_h_over_a / half * under.libm_sqrt()
    }

    /// The peak `(Δx/a, Δy/a)` at `d = d_c/a`.
    pub fn peak(&self, d: T) -> (T, T) {
        let dy = self.delta_y(d);
        (self.delta_x(dy), dy)
    }
}
