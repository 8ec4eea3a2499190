//! The plain data a calibration is made of, shared by the joint fit
//! ([`crate::calibration`]) and the friction-contact refit ([`crate::friction_contact`]):
//! the finger's setup, one parameter's estimate, and what the refit moved. No fitting
//! here, so that neither of those modules needs the other's types.

use serde::Serialize;
use softgrip::controller::FingerShape;

/// What the finger is, beyond the data: its shape and half-length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setup {
    /// Rectangle (hemicylinder) or disc (hemisphere).
    pub shape: FingerShape,
    /// Half-length `l` \[m\] of the rectangle (ignored for the disc).
    pub half_length_m: f64,
}

/// One parameter's estimate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// The value (fitted, held, or moved by [`Calibration::conservative`]); `null` in
    /// JSON for `k = ∞` (uniform pressure).
    ///
    /// [`Calibration::conservative`]: crate::Calibration::conservative
    pub value: f64,
    /// The 95 % interval (docs/decisions/calibration-fit.md); `None` when the parameter was
    /// not estimated at all, or was refitted without one (the friction contact's `c`); an
    /// unbounded end is `∞` (`null` in JSON).
    pub ci95: Option<[f64; 2]>,
    /// Whether the data identify it.
    pub identified: bool,
    /// Why not, when not identified.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

impl Estimate {
    /// An identified estimate with its interval `ci`.
    pub(crate) fn fitted(value: f64, ci: (f64, f64)) -> Self {
        Self {
            value,
            ci95: Some([ci.0, ci.1]),
            identified: true,
            reason: None,
        }
    }

    /// A value held (not identified), with the interval if one was found, and why.
    pub(crate) fn held(value: f64, ci95: Option<[f64; 2]>, reason: String) -> Self {
        Self {
            value,
            ci95,
            identified: false,
            reason: Some(reason),
        }
    }

    /// The interval's lower end (the value when there is none).
    pub fn lower(&self) -> f64 {
        self.ci95.map_or(self.value, |c| c[0])
    }
}

/// What the torsion onsets moved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Refit {
    /// The scale `c` of `a = c·N^γ`.
    Scale,
    /// The half-length (a rectangle whose torsion no `c` fits).
    HalfLength,
    /// Neither: no torsion onset, or no root within reach (the joint fit's `c` and the
    /// geometric half-length stay).
    Neither,
}

/// How a calibration's friction contact was found, beside the values it moved.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrictionContact {
    /// What the torsion onsets moved.
    pub refit: Refit,
    /// The joint fit's `μ` (its value alone in JSON).
    #[serde(serialize_with = "value_only")]
    pub joint_mu: Estimate,
    /// The joint fit's `c` [m/N^γ], the indentation's contact law (its value alone in
    /// JSON).
    #[serde(serialize_with = "value_only")]
    pub joint_c: Estimate,
    /// The finger's geometric half-length \[m\].
    pub geometric_half_length_m: f64,
}

fn value_only<S: serde::Serializer>(e: &Estimate, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_f64(e.value)
}

impl FrictionContact {
    /// One line for people: what moved, to what (`half_length_m`, the calibration's), and
    /// from what (`sig` formats a number).
    pub fn describe(&self, half_length_m: f64, sig: impl Fn(f64) -> String) -> String {
        let moved = match self.refit {
            Refit::Scale => format!(
                "c refitted to the torsion onsets (joint fit: {})",
                sig(self.joint_c.value)
            ),
            Refit::HalfLength => format!(
                "no c fits the torsion onsets; half-length refitted to them: {} m (geometric: {} m)",
                sig(half_length_m),
                sig(self.geometric_half_length_m)
            ),
            Refit::Neither => {
                "neither c nor the half-length fits the torsion onsets within reach: the \
                 joint fit's c and the geometric half-length kept"
                    .to_string()
            }
        };
        format!(
            "friction contact: mu from the pure-force onsets (joint fit: {}); {moved}",
            sig(self.joint_mu.value)
        )
    }
}
