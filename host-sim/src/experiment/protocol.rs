//! The protocols a lab runs on a [`Rig`], and the sensors' noise on what it records.
//!
//! - indentation: each normal force, the half-width;
//! - slip: a tangential-force ramp at each normal force until gross slip (`m_n = 0`);
//! - torsion: a moment ramp at each normal force (`f_t = 0`);
//! - combined: ramps along fixed ratios `m_n/f_t` \[m\] at each normal force.
//!
//! Each measurement is repeated `repeats` times; each recorded value (the normal force
//! included) gets its own noise ([`Noise`]). Cost: one rig call per row.

use super::Rig;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use softgrip_calibrate::lab_csv::{Indentation, SlipOnset};

/// Which experiment.
#[derive(Debug, Clone, PartialEq)]
pub enum Protocol {
    /// Half-width against normal force.
    Indentation,
    /// Tangential ramps.
    Slip,
    /// Moment ramps.
    Torsion,
    /// Ramps along `m_n/f_t` ratios \[m\].
    Combined(Vec<f64>),
}

/// Sensor noise: each recorded value `x` becomes `x·(1 + relative·ε₁) + abs·ε₂`, `ε`
/// standard normal, `abs` the channel's additive noise (a zero exact value, as `m_n` of a
/// slip ramp, gets the additive part only).
#[derive(Debug, Clone)]
pub struct Noise {
    /// Relative standard deviation [-] (a fraction, not per cent).
    pub relative: f64,
    /// Additive standard deviation of the force channels \[N\].
    pub force_n: f64,
    /// Additive standard deviation of the moment channel [N·m].
    pub moment_nm: f64,
    /// Additive standard deviation of the half-width \[m\].
    pub width_m: f64,
    rng: ChaCha8Rng,
}

impl Noise {
    /// Noise with these deviations, seeded.
    pub fn new(relative: f64, force_n: f64, moment_nm: f64, width_m: f64, seed: u64) -> Self {
        Self {
            relative,
            force_n,
            moment_nm,
            width_m,
            rng: ChaCha8Rng::seed_from_u64(seed),
        }
    }

    /// No noise.
    pub fn none() -> Self {
        Self::new(0.0, 0.0, 0.0, 0.0, 0)
    }

    /// `x` as recorded, with `additive` the channel's additive deviation.
    pub(crate) fn apply(&mut self, x: f64, additive: f64) -> f64 {
        let (e1, e2): (f64, f64) = (
            self.rng.sample(StandardNormal),
            self.rng.sample(StandardNormal),
        );
        let rel = if self.relative > 0.0 {
            x * self.relative * e1
        } else {
            0.0
        };
        let abs = if additive > 0.0 { additive * e2 } else { 0.0 };
        x + rel + abs
    }
}

/// Indentation rows at each force, `repeats` each.
pub fn indentation(
    rig: &dyn Rig,
    forces: &[f64],
    repeats: usize,
    noise: &mut Noise,
) -> Vec<Indentation> {
    let mut rows = Vec::new();
    for &n in forces {
        for _ in 0..repeats {
            let a = rig.indentation_half_width_m(n);
            let (fn_, wn) = (noise.force_n, noise.width_m);
            rows.push(Indentation {
                normal_force_n: noise.apply(n, fn_),
                half_width_m: noise.apply(a, wn),
            });
        }
    }
    rows
}

/// The ramp directions `(f_t, m_n)` of a slip protocol (unit force, or unit moment, or
/// `(1 N, ratio·1 N)`).
fn directions(p: &Protocol) -> Vec<(f64, f64)> {
    match p {
        Protocol::Indentation => Vec::new(),
        Protocol::Slip => vec![(1.0, 0.0)],
        Protocol::Torsion => vec![(0.0, 1e-3)],
        Protocol::Combined(ratios) => ratios.iter().map(|&r| (1.0, r)).collect(),
    }
}

/// Slip onsets of protocol `p` (not [`Protocol::Indentation`]) at each force, `repeats`
/// each; a ramp that never slips records nothing.
pub fn onsets(
    rig: &dyn Rig,
    p: &Protocol,
    forces: &[f64],
    repeats: usize,
    noise: &mut Noise,
) -> Vec<SlipOnset> {
    let mut rows = Vec::new();
    for &n in forces {
        for (ft_unit, mn_unit) in directions(p) {
            for _ in 0..repeats {
                let Some((ft, mn)) = rig.slip_onset(n, ft_unit, mn_unit) else {
                    continue;
                };
                let (fa, ma) = (noise.force_n, noise.moment_nm);
                let normal = noise.apply(n, fa);
                rows.push(SlipOnset {
                    normal_force_n: normal,
                    tangential_force_n: noise.apply(ft, fa).abs(),
                    torsional_moment_nm: noise.apply(mn, ma).abs(),
                });
            }
        }
    }
    rows
}

/// The default combined ratios `m_n/f_t` \[m\], which put the onsets of a 1–8 mm contact
/// across the curved part of its surface.
pub const DEFAULT_RATIOS_M: [f64; 3] = [1e-3, 2.5e-3, 6e-3];

/// Everything `experiment all` records: indentation rows, and slip, torsion and combined
/// onsets in one list.
pub fn all(
    rig: &dyn Rig,
    forces: &[f64],
    repeats: usize,
    ratios_m: &[f64],
    noise: &mut Noise,
) -> (Vec<Indentation>, Vec<SlipOnset>) {
    let ind = indentation(rig, forces, repeats, noise);
    let mut slip = onsets(rig, &Protocol::Slip, forces, repeats, noise);
    slip.extend(onsets(rig, &Protocol::Torsion, forces, repeats, noise));
    slip.extend(onsets(
        rig,
        &Protocol::Combined(ratios_m.to_vec()),
        forces,
        repeats,
        noise,
    ));
    (ind, slip)
}
