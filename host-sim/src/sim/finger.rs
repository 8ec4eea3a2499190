//! The true fingertip of a scene (its `[finger]` table): which plant is the ground truth
//! (`model`), shape, pressure exponent, friction, the contact law `a = c·N^γ` and the
//! elastic constants partial slip needs. Its own module so that the scene (which reads it)
//! and the effects (which model it) both depend on it and not on each other.
//!
//! `model = "fls"` (the default) is softgrip's own limit surface: `c` and `gamma` are
//! required. `model = "brush"` is the physical plant of [`crate::brush`]: its own keys are
//! in the `[finger.brush]` subtable ([`BrushSettings`]), it shares `shape`, `mu` (its
//! static μ), `half_length_m`, `young_modulus_pa` and `poisson`; `c`, `gamma` and `k` then
//! only say what the controller believes, calibrated from the finger's lab data
//! (`host-sim experiment`, then `host-sim calibrate`): nothing is read from the plant. A
//! brush finger without `c` and `gamma` can be measured (`experiment`) but runs no
//! controller.

use crate::brush::{BrushFinger, BrushParams, BrushSettings, BrushShape, ParamError};
use serde::Deserialize;
use softgrip::controller::FingerShape;

/// Which plant is the ground truth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FingerModel {
    /// softgrip's limit surface (`crate::sim::truth`).
    #[default]
    Fls,
    /// The brush finger (`crate::brush`).
    Brush,
}

/// The fingertip and its contact.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Finger {
    /// `fls` (default) or `brush`.
    #[serde(default)]
    pub model: FingerModel,
    /// `rect` (hemicylinder) or `disc` (hemisphere).
    #[serde(default = "default_shape")]
    pub shape: FingerShape,
    /// Pressure exponent `k ≥ 1`.
    #[serde(default = "default_k")]
    pub k: f64,
    /// Friction coefficient (the brush's static μ).
    pub mu: f64,
    /// `c` in `a = c·N^γ` [m/N^γ]; required for `fls` (NaN when absent).
    #[serde(default = "absent")]
    pub c: f64,
    /// `γ` in `a = c·N^γ`; required for `fls` (NaN when absent).
    #[serde(default = "absent")]
    pub gamma: f64,
    /// Half-length `l` of the rectangular patch \[m\].
    #[serde(default = "default_half_length")]
    pub half_length_m: f64,
    /// Young's modulus of the fingertip \[Pa\] (partial slip, the brush's layer).
    #[serde(default = "default_young")]
    pub young_modulus_pa: f64,
    /// Poisson's ratio (partial slip, the brush's layer).
    #[serde(default = "default_poisson")]
    pub poisson: f64,
    /// The brush plant's own keys (`[finger.brush]`), for `model = "brush"` only.
    #[serde(default)]
    pub brush: Option<BrushSettings>,
}

fn default_shape() -> FingerShape {
    FingerShape::Rect
}
fn default_k() -> f64 {
    2.0
}
fn absent() -> f64 {
    f64::NAN
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

impl Finger {
    /// The brush plant's parameters (`None` for `model = "fls"`), unchecked.
    pub fn brush_params(&self) -> Option<BrushParams> {
        (self.model == FingerModel::Brush).then(|| {
            BrushParams::from_settings(
                match self.shape {
                    FingerShape::Rect => BrushShape::Hemicylinder,
                    FingerShape::Disc => BrushShape::Hemisphere,
                },
                self.mu,
                self.half_length_m,
                self.young_modulus_pa,
                self.poisson,
                &self.brush.clone().unwrap_or_default(),
            )
        })
    }

    /// The brush finger (`None` for `model = "fls"`); the error names the scene key.
    pub fn brush_finger(&self) -> Result<Option<BrushFinger>, BrushKeyError> {
        let Some(p) = self.brush_params() else {
            return Ok(None);
        };
        BrushFinger::new(p).map(Some).map_err(|param| {
            let shared = matches!(
                param.key,
                "mu" | "half_length_m" | "young_modulus_pa" | "poisson"
            );
            BrushKeyError {
                table: if shared { "finger" } else { "finger.brush" },
                param,
            }
        })
    }
}

/// A brush finger's parameter out of its range, named as the scene writes it: its table
/// and key, e.g. `finger.brush.radius_m: 2 must lie in (0, 1]`.
#[derive(Debug, Clone, PartialEq)]
pub struct BrushKeyError {
    /// The table holding the key: `finger` for the keys the brush shares with the limit
    /// surface (`mu`, `half_length_m`, `young_modulus_pa`, `poisson`), `finger.brush`
    /// for its own.
    pub table: &'static str,
    /// The parameter (its key within `table`) and why it is refused.
    pub param: ParamError,
}

impl std::fmt::Display for BrushKeyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}.{}", self.table, self.param)
    }
}

impl std::error::Error for BrushKeyError {}

impl From<BrushKeyError> for String {
    fn from(e: BrushKeyError) -> Self {
        e.to_string()
    }
}
