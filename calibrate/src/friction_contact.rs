//! The contact that friction sees: `μ` from the slip test's pure-force onsets alone, then
//! the contact law's scale `c` (or, on a long hemicylinder, the half-length) refitted to
//! the torsion onsets at that `μ` and the joint fit's `k` and `γ` (docs/calibration.md,
//! "The contact friction sees").
//!
//! Why: the joint fit ([`crate::friction_fit`]) takes `c` from the indentation, the
//! geometric contact. On a finger whose pressure is more peaked at the centre than any
//! `k ≥ 1` allows (the bench's brush finger; a real fingertip may be one), the model at
//! that `c` overrates the torsion, and the joint fit compromises: it lowers `μ`, asking
//! a pure force for up to 10 % more than it needs, and still under-asks a pure torsion by
//! up to 6 % (the brush fingers of `host-sim/tests/calibrate_friction_contact.rs`). The
//! refit asks what each pure load needs. On a finger the model describes, it returns the
//! indentation's `c` within the lab's noise.
//!
//! On a long hemicylinder no `c` fits: its torsion is set by its length, whatever its
//! width. There the half-length is refitted instead (within a factor e of the
//! geometric one), at the indentation's `c`; it is the length friction sees, not the
//! finger's geometry.
//!
//! The refitted `c` or half-length has no interval of its own (`μ` has the slip
//! test's), so [`Calibration::conservative`] of a refitted calibration is the joint
//! fit's ([`Calibration::joint`]).
//!
//! Cost: a surface grid over the refit's reach ([`grid_for_refit`]) and 120 bisections
//! of a mean over the torsion onsets (the time it adds: docs/calibration.md).

use crate::calibration::Calibration;
use crate::error::CalibError;
use crate::estimate::{Estimate, Setup};
pub use crate::estimate::{FrictionContact, Refit};
use crate::interval::{t975, wald};
use crate::lab_csv::{OnsetKind, SlipOnset};
use crate::surface::SurfaceGrid;
use softgrip::controller::FingerShape;

/// How far the scale `c` may move from the indentation's, in `ln c`.
pub const SCALE_REACH_LN: f64 = 3.0;
/// How far the half-length may move from the geometric one, in `ln l`.
pub const LENGTH_REACH_LN: f64 = 1.0;
/// Fewest pure-force onsets (`μ` and its interval come from them alone).
pub const MIN_FORCE_ONSETS: usize = 2;
/// Aspect nodes per decade of [`grid_for_refit`]'s grid.
pub const NODES_PER_DECADE: f64 = 16.0;

/// `μ` from the pure-force onsets: the geometric mean of their `f_t/N`; `None` without
/// one. (The bench's cone baseline takes the same value.)
pub fn slip_test_mu(slip: &[SlipOnset]) -> Option<f64> {
    let (sum, n) = force_ratios(slip).fold((0.0, 0usize), |(s, n), x| (s + x.ln(), n + 1));
    (n > 0).then(|| (sum / n as f64).exp())
}

fn force_ratios(slip: &[SlipOnset]) -> impl Iterator<Item = f64> + '_ {
    slip.iter()
        .filter(|o| o.kind() == OnsetKind::Force)
        .map(|o| o.tangential_force_n / o.normal_force_n)
        .filter(|x| *x > 0.0 && x.is_finite())
}

/// The scale `c` [m/N^γ] and the half-length \[m\] that friction sees: those at which the
/// model's pure-torsion limit `μ·N·a(N)·pitch(k, l/a(N))` matches the `torsion` onsets
/// on average in `ln m` (`(μ, k, γ)` fixed). First `c`, within [`SCALE_REACH_LN`] of
/// `c0` at the geometric half-length; when no `c` there matches (a long hemicylinder),
/// the half-length, within [`LENGTH_REACH_LN`] of the geometric one, at `c0`. 60
/// bisections in the log of either.
pub fn refit(
    grid: &SurfaceGrid,
    setup: &Setup,
    (mu, k, gamma): (f64, f64, f64),
    c0: f64,
    torsion: &[&SlipOnset],
) -> (f64, f64, Refit) {
    let l0 = setup.half_length_m;
    if torsion.is_empty() {
        return (c0, l0, Refit::Neither);
    }
    let kappa = 1.0 / k;
    // Mean of ln(measured / modelled): decreasing in ln c and in ln l.
    let residual = |c: f64, l: f64| {
        let sum: f64 = torsion
            .iter()
            .map(|o| {
                let n = o.normal_force_n;
                let a = c * n.powf(gamma);
                let pitch = grid.pitch(kappa, l / a);
                (o.torsional_moment_nm / (mu * n * a * pitch)).ln()
            })
            .sum();
        sum / torsion.len() as f64
    };
    let root = |f: &dyn Fn(f64) -> f64, x0: f64, span: f64| -> Option<f64> {
        let (mut lo, mut hi) = (x0.ln() - span, x0.ln() + span);
        // A bracket that does not change sign (or a NaN) has no root.
        if !(f(lo.exp()) > 0.0 && f(hi.exp()) < 0.0) {
            return None;
        }
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if f(mid.exp()) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some((0.5 * (lo + hi)).exp())
    };
    if let Some(c) = root(&|c| residual(c, l0), c0, SCALE_REACH_LN) {
        return (c, l0, Refit::Scale);
    }
    if setup.shape == FingerShape::Rect {
        if let Some(l) = root(&|l| residual(c0, l), l0, LENGTH_REACH_LN) {
            return (c0, l, Refit::HalfLength);
        }
    }
    (c0, l0, Refit::Neither)
}

/// A grid that spans every aspect the refit can reach: `l/a(N)` at the onsets' forces
/// under `cal`'s contact law, widened by the scale's reach and the half-length's, and
/// by a fixed factor each way; [`NODES_PER_DECADE`] nodes a decade. No skew axis (a pure torsion
/// has no skew).
pub fn grid_for_refit(cal: &Calibration, slip: &[SlipOnset]) -> Result<SurfaceGrid, CalibError> {
    let shape = cal.finger_shape();
    let aspect = |n: f64| cal.half_length_m / cal.half_width_m(n);
    let (lo, hi) = slip
        .iter()
        .map(|o| aspect(o.normal_force_n))
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        });
    if !(lo <= hi) {
        return Err(CalibError::Setting(
            "friction contact: no onset with a finite contact aspect".to_string(),
        ));
    }
    let reach = (SCALE_REACH_LN + LENGTH_REACH_LN).exp() * 1.5;
    let (amin, amax) = (lo / reach, hi * reach);
    let nodes = ((amax / amin).log10() * NODES_PER_DECADE).ceil() as usize + 1;
    SurfaceGrid::build(shape, amin, amax, nodes, false)
}

/// Conservative values are refused: the refit has no interval to take an end of.
fn refuse_conservative(cal: &Calibration) -> Result<(), CalibError> {
    if cal.conservative {
        return Err(CalibError::Setting(
            "friction contact: refits a fitted calibration, not conservative values".to_string(),
        ));
    }
    Ok(())
}

impl Calibration {
    /// This (joint-fit) calibration with the contact friction sees: `μ` from the slip
    /// test's pure-force onsets (its interval a t interval of their `ln(f_t/N)`),
    /// and `c`, or on a long hemicylinder the half-length, refitted to the torsion
    /// onsets ([`refit`]) on a grid over the refit's reach ([`grid_for_refit`]). `k`, `γ`
    /// and the skew stay the joint fit's. Refused with fewer than [`MIN_FORCE_ONSETS`]
    /// pure-force onsets, and on a conservative calibration (take the conservative
    /// values of the joint fit instead).
    pub fn with_friction_contact(
        &self,
        slip_file: &str,
        slip: &[SlipOnset],
    ) -> Result<Self, CalibError> {
        let joint = self.joint();
        let grid = grid_for_refit(&joint, slip)?;
        joint.with_friction_contact_on(&grid, slip_file, slip)
    }

    /// The joint fit's values, without the friction contact (itself when it has none).
    pub fn joint(&self) -> Self {
        let mut out = self.clone();
        if let Some(fc) = out.friction_contact.take() {
            out.mu = fc.joint_mu;
            out.c = fc.joint_c;
            out.half_length_m = fc.geometric_half_length_m;
        }
        out
    }

    /// [`Calibration::with_friction_contact`] on a prebuilt grid (of the finger's shape,
    /// spanning the aspects the refit can reach: lookups clamp outside it).
    pub fn with_friction_contact_on(
        &self,
        grid: &SurfaceGrid,
        slip_file: &str,
        slip: &[SlipOnset],
    ) -> Result<Self, CalibError> {
        refuse_conservative(self)?;
        if self.friction_contact.is_some() {
            return self.joint().with_friction_contact_on(grid, slip_file, slip);
        }
        let ln: Vec<f64> = force_ratios(slip).map(f64::ln).collect();
        let (Some(mu), true) = (slip_test_mu(slip), ln.len() >= MIN_FORCE_ONSETS) else {
            return Err(CalibError::TooFew {
                file: slip_file.to_string(),
                needed: format!(
                    "the friction contact needs at least {MIN_FORCE_ONSETS} pure-force \
                     onsets (mu from the slip test alone); found {}",
                    ln.len()
                ),
            });
        };
        let n = ln.len() as f64;
        let mean = mu.ln();
        let var = ln.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        let se = (var / n).sqrt();
        let (lo, hi) = wald(
            mean,
            se,
            t975(ln.len() - 1),
            f64::NEG_INFINITY,
            f64::INFINITY,
        );
        let torsion: Vec<&SlipOnset> = slip
            .iter()
            .filter(|o| o.kind() == OnsetKind::Torsion)
            .collect();
        let setup = Setup {
            shape: self.finger_shape(),
            half_length_m: self.half_length_m,
        };
        let (c, l, how) = refit(
            grid,
            &setup,
            (mu, self.k.value, self.gamma.value),
            self.c.value,
            &torsion,
        );
        let mut out = self.clone();
        if how == Refit::Scale {
            out.c.ci95 = None;
        }
        out.mu = Estimate {
            value: mu,
            ci95: Some([lo.exp(), hi.exp()]),
            identified: true,
            reason: None,
        };
        out.c.value = c;
        out.half_length_m = l;
        out.friction_contact = Some(FrictionContact {
            refit: how,
            joint_mu: self.mu.clone(),
            joint_c: self.c.clone(),
            geometric_half_length_m: self.half_length_m,
        });
        Ok(out)
    }
}
