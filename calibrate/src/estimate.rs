//! The plain data a calibration is made of, shared by the joint fit
//! ([`crate::calibration`]) and the friction-contact refit ([`crate::friction_contact`]):
//! the finger's setup (and where it came from: [`Setup::resolve`]), one parameter's
//! estimate, and what the refit moved. No fitting here, so that neither of those modules
//! needs the other's types.

use crate::error::CalibError;
use crate::lab_csv::RigRecord;
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

/// Where a setting of the [`Setup`] came from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SetupSource {
    /// The caller gave it (a flag, a keyword).
    Given,
    /// A lab file recorded it (the file's name).
    File(String),
    /// Neither: [`Setup::DEFAULT`]'s.
    Default,
}

/// A [`Setup`] and where each of its settings came from.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedSetup {
    /// The setup.
    pub setup: Setup,
    /// Where the shape came from.
    pub shape_from: SetupSource,
    /// Where the half-length came from.
    pub half_length_from: SetupSource,
}

/// One setting: the given value, else the files' (which must agree with it and with each
/// other), else `default`.
fn pick<T: PartialEq + Copy>(
    setting: &'static str,
    given: Option<T>,
    recorded: &[(&str, Option<T>)],
    default: T,
    show: impl Fn(T) -> String,
) -> Result<(T, SetupSource), CalibError> {
    let mut found: Option<(&str, T)> = None;
    for &(file, value) in recorded {
        let Some(v) = value else { continue };
        let against = match (given, found) {
            (Some(g), _) => (g != v).then_some((None, g)),
            (None, Some((f0, v0))) => (v0 != v).then_some((Some(f0.to_string()), v0)),
            (None, None) => None,
        };
        if let Some((given_in, g)) = against {
            return Err(CalibError::Contradiction {
                setting,
                given: show(g),
                given_in,
                file: file.to_string(),
                recorded: show(v),
            });
        }
        found.get_or_insert((file, v));
    }
    Ok(match (given, found) {
        (Some(g), _) => (g, SetupSource::Given),
        (None, Some((f, v))) => (v, SetupSource::File(f.to_string())),
        (None, None) => (default, SetupSource::Default),
    })
}

impl Setup {
    /// The setup when neither the caller nor a file says otherwise: a rectangle of
    /// half-length 10 mm.
    pub const DEFAULT: Setup = Setup {
        shape: FingerShape::Rect,
        half_length_m: 0.01,
    };

    /// The setup from the caller's settings (`None`: not given) and what the lab `files`
    /// (name, record) record of the rig: each setting given, else recorded, else
    /// [`Setup::DEFAULT`]'s. A given value that differs from a recorded one, or two files
    /// that record different values, is refused ([`CalibError::Contradiction`], naming
    /// both).
    pub fn resolve(
        shape: Option<FingerShape>,
        half_length_m: Option<f64>,
        files: &[(&str, RigRecord)],
    ) -> Result<ResolvedSetup, CalibError> {
        let shapes: Vec<(&str, Option<FingerShape>)> =
            files.iter().map(|(f, r)| (*f, r.shape)).collect();
        let lengths: Vec<(&str, Option<f64>)> =
            files.iter().map(|(f, r)| (*f, r.half_length_m)).collect();
        let name = |s: FingerShape| s.name().to_string();
        let (shape, shape_from) = pick("shape", shape, &shapes, Self::DEFAULT.shape, name)?;
        let (half_length_m, half_length_from) = pick(
            "half_length_m",
            half_length_m,
            &lengths,
            Self::DEFAULT.half_length_m,
            |l| l.to_string(),
        )?;
        Ok(ResolvedSetup {
            setup: Setup {
                shape,
                half_length_m,
            },
            shape_from,
            half_length_from,
        })
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(shape: Option<FingerShape>, l: Option<f64>) -> RigRecord {
        RigRecord {
            shape,
            half_length_m: l,
        }
    }

    #[test]
    fn each_setting_is_the_given_else_the_recorded_else_the_default() {
        let (rect, disc) = (Some(FingerShape::Rect), Some(FingerShape::Disc));
        let none = Setup::resolve(None, None, &[("i", rec(None, None))]).unwrap();
        assert_eq!(none.setup, Setup::DEFAULT);
        assert_eq!(none.shape_from, SetupSource::Default);
        let files = [("i", rec(disc, None)), ("s", rec(disc, Some(0.02)))];
        let r = Setup::resolve(None, None, &files).unwrap();
        assert_eq!(r.setup.shape, FingerShape::Disc);
        assert_eq!(r.setup.half_length_m, 0.02);
        assert_eq!(r.shape_from, SetupSource::File("i".into()));
        assert_eq!(r.half_length_from, SetupSource::File("s".into()));
        let r = Setup::resolve(disc, Some(0.02), &files).unwrap();
        assert_eq!(r.shape_from, SetupSource::Given);
        // A given value against a recorded one, and two files against each other.
        let e = Setup::resolve(rect, None, &files).unwrap_err();
        assert_eq!(
            e,
            CalibError::Contradiction {
                setting: "shape",
                given: "rect".into(),
                given_in: None,
                file: "i".into(),
                recorded: "disc".into(),
            }
        );
        assert!(e
            .to_string()
            .starts_with("shape: rect was given, but i records the rig's shape = disc"));
        let e = Setup::resolve(None, Some(0.01), &files).unwrap_err();
        assert!(
            e.to_string().contains("0.01 was given, but s records"),
            "{e}"
        );
        let e = Setup::resolve(
            None,
            None,
            &[("i", rec(rect, None)), ("s", rec(disc, None))],
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "shape: i records rect, but s records disc: the files are of different rigs"
        );
    }
}
