//! Whether the onsets contradict the fit: a lack-of-fit test of the slip residuals
//! against the noise the rows themselves show (docs/calibration.md, "A fit the rows
//! contradict").
//!
//! The residual of an onset is `ln u`, its relative distance from the fitted surface. The
//! noise is measured without the model, in the first of these that has at least
//! [`MIN_NOISE_DF`] degrees of freedom:
//!
//! - **repeats**: onsets of one kind at the same normal force and, for mixed ones, the
//!   same ratio `m_n/f_t`, each within a span of [`REPEAT_SPAN_LN`] in `ln`. Their
//!   residuals' scatter about their own mean is pure error: no parameter can reduce it.
//!   The test is the classical one, `F = (SS_res − SS_pe)/(g − p) ÷ SS_pe/(n − g)` for
//!   `n` onsets in `g` groups and `p` fitted slip parameters;
//! - **the pure-force onsets**: the scatter of their `ln(f_t/N)` about its mean, which
//!   every shape, half-length, `k` and `c` fit alike; `F = s²/σ_f²`, `s` the fit's
//!   residual scale (`n − p` degrees of freedom).
//!
//! The fit is contradicted when `P(F > f) <` [`LEVEL`] and the residuals' RMS is over
//! [`MATERIAL_RMS`]: beyond the noise, and large enough to matter (the brush fingers, which
//! the model describes only nearly, leave up to 2.1 % without noise). The likely cause
//! is named from the sign of the torsion onsets' mean residual against the pure-force
//! ones': on the rectangle a patch shorter than the half-length given or a hemisphere
//! (`shape = disc`) slips at less torsion than the fit allows, a longer patch at more; on
//! the disc, a hemicylinder. Figures: host-sim/tests/calibrate_contradiction.rs. Cost: a
//! sort of the onsets.

use crate::interval::f_tail;
use crate::lab_csv::{OnsetKind, SlipOnset};
use serde::Serialize;
use softgrip::controller::FingerShape;

/// The widest span in `ln N` (and in `ln(m_n/f_t)`) of one group of repeated onsets: a
/// tenth, so that repeats recorded with a few per cent of noise fall into one group and the
/// forces of a lab's protocol (a factor of 2 apart) do not
/// (host-sim/tests/calibrate_contradiction.rs).
pub const REPEAT_SPAN_LN: f64 = 0.1;
/// Fewest degrees of freedom of the noise for the test to be made.
pub const MIN_NOISE_DF: usize = 4;
/// The test's level: the chance that rows the fit describes are said to contradict it
/// (host-sim/tests/calibrate_contradiction.rs).
pub const LEVEL: f64 = 1e-3;
/// The least RMS of the onsets' `ln u` that is reported: over twice the brush fingers'
/// misfit without noise
/// (host-sim/tests/calibrate_contradiction.rs::brush_fingers_fitted_at_their_shape_do_not_warn).
pub const MATERIAL_RMS: f64 = 0.05;

/// Where the noise was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum NoiseSource {
    /// Repeated onsets at one condition.
    Repeats,
    /// The pure-force onsets' scatter of `ln(f_t/N)`.
    PureForceOnsets,
    /// Neither has [`MIN_NOISE_DF`] degrees of freedom: not tested.
    None,
}

/// The test's figures.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LackOfFit {
    /// RMS of the onsets' `ln u` at the fit.
    pub rms_ln_utilisation: f64,
    /// Where the noise was measured.
    pub noise_from: NoiseSource,
    /// The noise's standard deviation in `ln u` (`null` when not measured).
    pub noise_sd: Option<f64>,
    /// `F`, the residual variance the noise does not explain over the noise's (`null`
    /// when not measured or infinite: noise-free repeats).
    pub f_ratio: Option<f64>,
    /// `F`'s degrees of freedom.
    pub f_df: [usize; 2],
    /// `P(F > f_ratio)` for rows the fit describes (`null` when not measured).
    pub p_value: Option<f64>,
    /// Whether the rows contradict the fit: `p_value <` [`LEVEL`] and
    /// `rms_ln_utilisation >` [`MATERIAL_RMS`].
    pub contradicted: bool,
}

/// Groups of repeated onsets: indices, by kind, then `ln N`, then (mixed) `ln(m_n/f_t)`,
/// each group spanning at most [`REPEAT_SPAN_LN`] in each.
fn repeat_groups(slip: &[SlipOnset]) -> Vec<Vec<usize>> {
    let key = |o: &SlipOnset| {
        let kind = match o.kind() {
            OnsetKind::Force => 0u8,
            OnsetKind::Torsion => 1,
            OnsetKind::Mixed => 2,
        };
        let ratio = if kind == 2 {
            (o.torsional_moment_nm / o.tangential_force_n).ln()
        } else {
            0.0
        };
        (kind, o.normal_force_n.ln(), ratio)
    };
    let keys: Vec<(u8, f64, f64)> = slip.iter().map(key).collect();
    // Split a sorted run wherever a member is more than the span from the run's first.
    let split = |idx: Vec<usize>, coord: &dyn Fn(usize) -> f64| {
        let mut out: Vec<Vec<usize>> = Vec::new();
        for i in idx {
            match out.last_mut() {
                Some(g) if coord(i) - coord(g[0]) <= REPEAT_SPAN_LN => g.push(i),
                _ => out.push(vec![i]),
            }
        }
        out
    };
    let mut order: Vec<usize> = (0..slip.len()).collect();
    order.sort_by(|&a, &b| {
        (keys[a].0, keys[a].1)
            .partial_cmp(&(keys[b].0, keys[b].1))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut by_force: Vec<Vec<usize>> = Vec::new();
    for kind in 0..3u8 {
        let of_kind: Vec<usize> = order
            .iter()
            .copied()
            .filter(|&i| keys[i].0 == kind)
            .collect();
        by_force.extend(split(of_kind, &|i| keys[i].1));
    }
    by_force
        .into_iter()
        .flat_map(|mut g| {
            g.sort_by(|&a, &b| keys[a].2.total_cmp(&keys[b].2));
            split(g, &|i| keys[i].2)
        })
        .collect()
}

/// Pure error of `residuals` over `groups`: its sum of squares and degrees of freedom.
fn pure_error(residuals: &[f64], groups: &[Vec<usize>]) -> (f64, usize) {
    groups.iter().fold((0.0, 0), |(ss, df), g| {
        let mean = g.iter().map(|&i| residuals[i]).sum::<f64>() / g.len() as f64;
        let s: f64 = g.iter().map(|&i| (residuals[i] - mean).powi(2)).sum();
        (ss + s, df + g.len() - 1)
    })
}

/// The scatter of the pure-force onsets' `ln(f_t/N)`: sum of squares and degrees of
/// freedom.
fn force_scatter(slip: &[SlipOnset]) -> (f64, usize) {
    let ln: Vec<f64> = slip
        .iter()
        .filter(|o| o.kind() == OnsetKind::Force)
        .map(|o| (o.tangential_force_n / o.normal_force_n).ln())
        .collect();
    let mean = ln.iter().sum::<f64>() / ln.len().max(1) as f64;
    let ss = ln.iter().map(|x| (x - mean).powi(2)).sum();
    (ss, ln.len().saturating_sub(1))
}

/// The test of the onsets' `residuals` (`ln u` at the fit, one per onset of `slip`) from
/// a fit of `p` slip parameters.
pub fn assess(slip: &[SlipOnset], residuals: &[f64], p: usize) -> LackOfFit {
    let n = residuals.len();
    let ss: f64 = residuals.iter().map(|r| r * r).sum();
    let rms = (ss / n.max(1) as f64).sqrt();
    let groups = repeat_groups(slip);
    let (ss_pe, df_pe) = pure_error(residuals, &groups);
    let df_lof = groups.len().saturating_sub(p);
    let (ss_f, df_f) = force_scatter(slip);
    let df_res = n.saturating_sub(p);
    let (from, noise_var, misfit_var, f_df) = if df_pe >= MIN_NOISE_DF && df_lof >= 1 {
        let lof = (ss - ss_pe).max(0.0) / df_lof as f64;
        (
            NoiseSource::Repeats,
            ss_pe / df_pe as f64,
            lof,
            [df_lof, df_pe],
        )
    } else if df_f >= MIN_NOISE_DF && df_res >= 1 {
        let s2 = ss / df_res as f64;
        (
            NoiseSource::PureForceOnsets,
            ss_f / df_f as f64,
            s2,
            [df_res, df_f],
        )
    } else {
        return LackOfFit {
            rms_ln_utilisation: rms,
            noise_from: NoiseSource::None,
            noise_sd: None,
            f_ratio: None,
            f_df: [0, 0],
            p_value: None,
            contradicted: false,
        };
    };
    let f = if noise_var > 0.0 {
        misfit_var / noise_var
    } else if misfit_var > 0.0 {
        f64::INFINITY
    } else {
        0.0
    };
    let p_value = f_tail(f, f_df[0], f_df[1]);
    LackOfFit {
        rms_ln_utilisation: rms,
        noise_from: from,
        noise_sd: Some(noise_var.sqrt()),
        f_ratio: f.is_finite().then_some(f),
        f_df,
        p_value: Some(p_value),
        contradicted: p_value < LEVEL && rms > MATERIAL_RMS,
    }
}

/// The mean residual of the torsion onsets (else the mixed ones) less that of the
/// pure-force ones: negative when onsets with a moment slip at less torsion than the fit
/// allows. `None` without both.
fn torsion_lean(slip: &[SlipOnset], residuals: &[f64]) -> Option<f64> {
    let mean = |kind: OnsetKind| {
        let (s, n) = slip
            .iter()
            .zip(residuals)
            .filter(|(o, _)| o.kind() == kind)
            .fold((0.0, 0usize), |(s, n), (_, r)| (s + r, n + 1));
        (n > 0).then(|| s / n as f64)
    };
    let force = mean(OnsetKind::Force)?;
    let moment = mean(OnsetKind::Torsion).or_else(|| mean(OnsetKind::Mixed))?;
    Some(moment - force)
}

/// The warning of a contradicted fit: the figures and the likely cause, for a finger of
/// `shape` and half-length `half_length_m` \[m\]; `None` when not contradicted.
pub fn warning(
    lof: &LackOfFit,
    shape: FingerShape,
    half_length_m: f64,
    slip: &[SlipOnset],
    residuals: &[f64],
) -> Option<String> {
    if !lof.contradicted {
        return None;
    }
    let noise = lof.noise_sd.unwrap_or(0.0);
    let from = match lof.noise_from {
        NoiseSource::Repeats => "their repeats",
        _ => "the pure-force onsets' scatter",
    };
    let f = lof.f_ratio.map_or("inf".to_string(), |f| format!("{f:.1}"));
    let head = format!(
        "the rows contradict the fit: the onsets lie {:.1} % (RMS of ln u) from the fitted \
         surface, and their noise, from {from}, is {:.1} % (F = {f}, p = {:.1e} < {LEVEL})",
        lof.rms_ln_utilisation * 100.0,
        noise * 100.0,
        lof.p_value.unwrap_or(0.0)
    );
    let l = half_length_m;
    let cause = match (shape, torsion_lean(slip, residuals)) {
        (FingerShape::Rect, Some(d)) if d < 0.0 => format!(
            "The onsets with a moment slip at less torsion than the fit allows: the finger may \
             be a hemisphere (shape disc), or its patch shorter than the half-length ({l} m)."
        ),
        (FingerShape::Rect, Some(_)) => format!(
            "The onsets with a moment slip at more torsion than the fit allows: the patch may \
             be longer than the half-length ({l} m)."
        ),
        (FingerShape::Rect, None) => {
            format!("Check the shape (a hemisphere is disc) and the half-length ({l} m).")
        }
        (FingerShape::Disc, _) => "Check the shape: the finger may be a hemicylinder (shape \
                                   rect, with its half-length)."
            .to_string(),
    };
    Some(format!("{head}. {cause}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn onset(n: f64, ft: f64, mn: f64) -> SlipOnset {
        SlipOnset {
            normal_force_n: n,
            tangential_force_n: ft,
            torsional_moment_nm: mn,
        }
    }

    /// Two repeats of each kind at each of two forces, a hundredth apart; the mixed ones
    /// at two ratios.
    fn rows() -> Vec<SlipOnset> {
        let mut out = Vec::new();
        for n in [1.0, 2.0] {
            for r in [1.0, 1.01] {
                let m = n * r;
                out.extend([
                    onset(m, 0.8 * m, 0.0),
                    onset(m, 0.0, 2e-3 * m),
                    onset(m, 0.5 * m, 1e-3 * 0.5 * m * r),
                    onset(m, 0.3 * m, 3e-3 * 0.3 * m),
                ]);
            }
        }
        out
    }

    #[test]
    fn repeats_are_grouped_by_kind_force_and_ratio() {
        let groups = repeat_groups(&rows());
        assert_eq!(groups.len(), 8);
        assert!(groups.iter().all(|g| g.len() == 2), "{groups:?}");
    }

    #[test]
    fn a_misfit_beyond_the_repeats_scatter_is_a_contradiction() {
        let slip = rows();
        // The repeats differ by a hundredth either way; the groups by far more (a model
        // that misses), or by as little (one that fits).
        let noise = |i: usize| if i % 8 < 4 { 0.01 } else { -0.01 };
        let miss: Vec<f64> = (0..slip.len())
            .map(|i| noise(i) + if i % 2 == 0 { 0.3 } else { -0.3 })
            .collect();
        let l = assess(&slip, &miss, 2);
        assert_eq!(l.noise_from, NoiseSource::Repeats);
        assert!(l.contradicted && l.p_value.unwrap() < 1e-6, "{l:?}");
        let w = warning(&l, FingerShape::Disc, 0.01, &slip, &miss).unwrap();
        assert!(w.contains("hemicylinder (shape rect"), "{w}");
        let fits: Vec<f64> = (0..slip.len()).map(noise).collect();
        let l = assess(&slip, &fits, 2);
        assert!(
            !l.contradicted && l.rms_ln_utilisation < MATERIAL_RMS,
            "{l:?}"
        );
        assert!(warning(&l, FingerShape::Disc, 0.01, &slip, &fits).is_none());
        // Too few rows for any noise: not tested.
        let l = assess(&slip[..4], &miss[..4], 2);
        assert_eq!(l.noise_from, NoiseSource::None);
        assert!(!l.contradicted);
    }
}
