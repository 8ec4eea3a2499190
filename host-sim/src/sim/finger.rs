//! The true fingertip of a scene (its `[finger]` table): shape, pressure exponent,
//! friction, the contact law `a = c·N^γ` and the elastic constants partial slip needs. Its
//! own module so that the scene (which reads it) and the effects (which model it) both
//! depend on it and not on each other.

use serde::Deserialize;
use softgrip::controller::FingerShape;

/// The fingertip and its contact.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Finger {
    /// `rect` (hemicylinder) or `disc` (hemisphere).
    #[serde(default = "default_shape")]
    pub shape: FingerShape,
    /// Pressure exponent `k ≥ 1`.
    #[serde(default = "default_k")]
    pub k: f64,
    /// Friction coefficient.
    pub mu: f64,
    /// `c` in `a = c·N^γ` [m/N^γ].
    pub c: f64,
    /// `γ` in `a = c·N^γ`.
    pub gamma: f64,
    /// Half-length `l` of the rectangular patch [m].
    #[serde(default = "default_half_length")]
    pub half_length_m: f64,
    /// Young's modulus of the fingertip [Pa] (partial slip).
    #[serde(default = "default_young")]
    pub young_modulus_pa: f64,
    /// Poisson's ratio (partial slip).
    #[serde(default = "default_poisson")]
    pub poisson: f64,
}

fn default_shape() -> FingerShape {
    FingerShape::Rect
}
fn default_k() -> f64 {
    2.0
}
fn default_half_length() -> f64 {
    0.01
}
fn default_young() -> f64 {
    3e5
}
fn default_poisson() -> f64 {
    0.45
}
