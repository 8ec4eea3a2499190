//! What every controller believes about a trial's finger: calibrated from the same lab
//! data of that finger, never read from the plant.
//!
//! The lab ([`crate::experiment`]) measures the finger at [`LAB_FORCES_N`], once each,
//! with relative noise on every recorded value ([`LAB_NOISE`]): an indentation test
//! (contact half-width), a slip test (tangential ramps) and a torsion test (moment
//! ramps). From those rows:
//! - **softgrip** is calibrated as `host-sim calibrate --friction-contact` calibrates
//!   a finger (the same code, `softgrip_calibrate`, on a surface grid shared by every
//!   trial of a shape): `k` and `γ` from the joint fit, `μ` from the slip test (as the
//!   cone), and the scale `c` of its contact law refitted to the torsion test at that
//!   `μ`, `k` and `γ` ([`softgrip_calibrate::friction_contact`]): the contact size that
//!   friction sees. On a finger softgrip models this is the indentation's `c`; on the
//!   brush finger, whose pressure is more peaked at the centre than any `k ≥ 1` allows,
//!   the joint fit would otherwise lower `μ` to fit the torsion onsets and ask every
//!   tangential load for more force than it needs, while still overrating the finger's
//!   torsion. On a long hemicylinder no `c` fits (its torsion is set by its length):
//!   there the half-length friction sees is refitted instead, at the indentation's `c`,
//!   and softgrip is told it in place of the geometric one;
//! - **the cone** (`coulomb`) gets `μ` from the slip test: the geometric mean of the
//!   onsets' `f_t/N`;
//! - **`fixed-torsion` and `box`** get that `μ` and their fixed patch from the torsion
//!   test: the torsion arm `m_n/(μ·N)`, geometric mean over the test's forces (a patch
//!   of one size, fitted in the least-squares sense on the log scale, as a lab would fit
//!   a model that has one).
//!
//! Cost: 6 indentations and 12 slip onsets on the rig, and a fit.

use crate::experiment::protocol::{self, Noise, Protocol};
use crate::experiment::Rig;
use softgrip::controller::FingerShape;
use softgrip_calibrate::friction_contact::slip_test_mu;
use softgrip_calibrate::lab_csv::{Indentation, OnsetKind, SlipOnset};
use softgrip_calibrate::surface::SurfaceGrid;
use softgrip_calibrate::Setup;
use std::sync::OnceLock;

/// The lab's normal forces \[N\].
pub const LAB_FORCES_N: [f64; 6] = [0.5, 1.0, 2.0, 4.0, 8.0, 16.0];
/// Relative noise (standard deviation) on every recorded value.
pub const LAB_NOISE: f64 = 0.02;
/// Aspect range `l/a` and nodes of the shared surface grids: every finger the bench
/// draws, at every lab force, lies inside it (`lab_aspects_lie_inside_the_shared_grid`);
/// one that does not gets a grid of its own ([`calibrate`]).
pub const GRID_ASPECTS: (f64, f64, usize) = (0.15, 400.0, 53);

/// What the controllers believe about one finger.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beliefs {
    /// softgrip's `μ` (the slip test's, as the friction contact takes it).
    pub mu: f64,
    /// softgrip's pressure exponent `k`.
    pub k: f64,
    /// softgrip's `c` in `a = c·N^γ` [m/N^γ].
    pub c: f64,
    /// softgrip's `γ`.
    pub gamma: f64,
    /// softgrip's half-length \[m\]: the geometric one, or the one friction sees when the
    /// torsion onsets call for it ([`softgrip_calibrate::friction_contact`]).
    pub half_length_m: f64,
    /// The cone's, the box's and fixed-torsion's `μ` (slip test).
    pub cone_mu: f64,
    /// The box's and fixed-torsion's torsion arm \[m\] (torsion test).
    pub torsion_arm_m: f64,
}

/// The lab's rows for one finger.
#[derive(Debug, Clone)]
pub struct LabData {
    /// Indentation rows.
    pub indentation: Vec<Indentation>,
    /// Slip and torsion onsets.
    pub onsets: Vec<SlipOnset>,
}

/// Runs the lab's tests on `rig`, the noise seeded by `seed`.
pub fn measure(rig: &dyn Rig, seed: u64) -> LabData {
    let mut noise = Noise::new(LAB_NOISE, 0.0, 0.0, 0.0, seed);
    let f = &LAB_FORCES_N;
    let indentation = protocol::indentation(rig, f, 1, &mut noise);
    let mut onsets = protocol::onsets(rig, &Protocol::Slip, f, 1, &mut noise);
    onsets.extend(protocol::onsets(rig, &Protocol::Torsion, f, 1, &mut noise));
    LabData {
        indentation,
        onsets,
    }
}

fn grid(shape: FingerShape) -> Result<&'static SurfaceGrid, String> {
    static RECT: OnceLock<Result<SurfaceGrid, String>> = OnceLock::new();
    static DISC: OnceLock<Result<SurfaceGrid, String>> = OnceLock::new();
    let cell = match shape {
        FingerShape::Rect => &RECT,
        FingerShape::Disc => &DISC,
    };
    let (lo, hi, n) = GRID_ASPECTS;
    cell.get_or_init(|| SurfaceGrid::build(shape, lo, hi, n, false).map_err(|e| e.to_string()))
        .as_ref()
        .map_err(Clone::clone)
}

fn geometric_mean(xs: impl Iterator<Item = f64>) -> Option<f64> {
    let (mut sum, mut n) = (0.0, 0usize);
    for x in xs.filter(|x| *x > 0.0 && x.is_finite()) {
        sum += x.ln();
        n += 1;
    }
    (n > 0).then(|| (sum / n as f64).exp())
}

/// Every controller's beliefs from `lab`, for a finger of `shape` and half-length
/// `half_length_m` \[m\] (its geometry, which a lab knows); or why the data do not fit.
pub fn calibrate(lab: &LabData, shape: FingerShape, half_length_m: f64) -> Result<Beliefs, String> {
    let setup = Setup {
        shape,
        half_length_m,
    };
    let fit = |g: &SurfaceGrid| {
        softgrip_calibrate::calibrate_on(
            g,
            &setup,
            "indentation",
            &lab.indentation,
            "slip",
            &lab.onsets,
        )
        .map_err(|e| format!("calibration: {e}"))
    };
    let shared = grid(shape)?;
    let cal = fit(shared)?;
    // A grid clamps the aspect at its ends, which would bias the fit (and the friction
    // contact's refit) for a finger beyond them: such a finger is calibrated as
    // `host-sim calibrate --friction-contact` calibrates it, on the grids its data need.
    let cal = if inside_shared_grid(shape, half_length_m, cal.c.value, cal.gamma.value) {
        cal.with_friction_contact_on(shared, "slip", &lab.onsets)
    } else {
        let own = softgrip_calibrate::grid_for(&setup, &lab.indentation, &lab.onsets)
            .map_err(|e| format!("calibration: {e}"))?;
        fit(&own)?.with_friction_contact("slip", &lab.onsets)
    }
    .map_err(|e| format!("calibration: {e}"))?;
    let cone_mu = slip_test_mu(&lab.onsets).ok_or("calibration: no slip onset")?;
    let torsion_arm_m = geometric_mean(
        lab.onsets
            .iter()
            .filter(|o| o.kind() == OnsetKind::Torsion)
            .map(|o| o.torsional_moment_nm / (cone_mu * o.normal_force_n)),
    )
    .ok_or("calibration: no torsion onset")?;
    Ok(Beliefs {
        mu: cal.mu.value,
        k: cal.k.value,
        c: cal.c.value,
        gamma: cal.gamma.value,
        half_length_m: cal.half_length_m,
        cone_mu,
        torsion_arm_m,
    })
}

/// Whether the aspects `l/a(N)` of a finger of `shape` and half-length `half_length_m`
/// \[m\] with the contact law `a = c·N^γ` lie inside the shared grid at every lab force
/// (always for a disc, whose surface has no aspect).
pub fn inside_shared_grid(shape: FingerShape, half_length_m: f64, c: f64, gamma: f64) -> bool {
    if shape == FingerShape::Disc {
        return true;
    }
    let (lo, hi, _) = GRID_ASPECTS;
    LAB_FORCES_N.iter().all(|&n| {
        let aspect = half_length_m / (c * n.powf(gamma));
        (lo..=hi).contains(&aspect)
    })
}
