//! The calibration: which parameters the lab files can identify, the joint fit of those
//! ([`crate::friction_fit`]), their 95 % intervals and the conservative values
//! (docs/calibration.md; the intervals' choice: docs/decisions/calibration-fit.md).
//!
//! Rules, from the rows alone (before any fit):
//!
//! - indentation: at least [`MIN_INDENTATION_ROWS`] rows; `γ` needs two distinct forces,
//!   else it is held at 0 (`a(N) ≤ a(N₀)` above the measured force `N₀`);
//! - slip: at least [`MIN_TANGENTIAL_ONSETS`] onsets with a tangential force (pure force or
//!   mixed: `μ`), and `k` needs [`MIN_MOMENT_ONSETS`] with a moment (pure torsion or
//!   mixed), else it is held at 2, the capacity-lowering end of its plausible range
//!   `[2, ∞]` (a lower `k` shrinks the whole surface);
//! - the skew (rectangle only, `α` held at the paper's 1.1, docs/decisions/calibration-fit.md):
//!   fitted when there are
//!   [`MIN_MIXED_ONSETS`] mixed onsets; identified only if its interval excludes 0, else
//!   held at 0, no skew: the skew only enlarges the surface, so none is conservative.
//!
//! Cost: [`calibrate`] builds a [`SurfaceGrid`] (most of its time, the more so with the
//! skew axis) and fits; [`calibrate_on`] reuses a grid and costs the fit alone (a few ms).

use crate::contact_fit::{fit_contact, ContactFit};
use crate::error::CalibError;
use crate::estimate::FrictionContact;
pub use crate::estimate::{Estimate, ResolvedSetup, Setup, SetupSource};
use crate::friction_fit::{
    fit_joint, FitPlan, JointFit, GAMMA, KAPPA, LN_C, LN_MU, PARAMS, SKEW_SQ,
};
use crate::interval::{t975, wald};
use crate::lab_csv::{Indentation, OnsetKind, SlipOnset};
use crate::lack_of_fit::{assess, warning, LackOfFit};
use crate::surface::{SurfaceGrid, MAX_SKEW, SKEW_ALPHA};
use serde::Serialize;
use softgrip::controller::{FingerShape, SkewParams};

/// Fewest indentation rows.
pub const MIN_INDENTATION_ROWS: usize = 3;
/// Fewest onsets with a tangential force.
pub const MIN_TANGENTIAL_ONSETS: usize = 3;
/// Fewest onsets with a moment for `k` to be fitted.
pub const MIN_MOMENT_ONSETS: usize = 2;
/// Fewest mixed onsets for the skew to be fitted.
pub const MIN_MIXED_ONSETS: usize = 3;
/// `k` when no onset has a moment: the low end of the plausible range `[2, ∞]`.
pub const K_HELD: f64 = 2.0;
/// `γ` when every indentation is at one force.
pub const GAMMA_HELD: f64 = 0.0;
/// Aspect nodes of the grid [`calibrate`] builds.
pub const GRID_ASPECTS: usize = 16;

/// The skew's three settings, as `[effect.skewed_pressure]` names them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkewEstimates {
    /// `Δ/a`.
    pub delta_over_a: Estimate,
    /// `α`.
    pub alpha: Estimate,
    /// `h/a`.
    pub locus_over_a: Estimate,
}

/// How well the fit went.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitSummary {
    /// Indentation rows.
    pub indentation_rows: usize,
    /// Onsets: pure force, pure torsion, mixed.
    pub onsets_force_torsion_mixed: [usize; 3],
    /// Residual standard deviation of `ln a` in the indentation file.
    pub sigma_ln_half_width: f64,
    /// Residual standard deviation of `ln u` (utilisation) of the onsets.
    pub sigma_ln_utilisation: f64,
    /// Degrees of freedom of the intervals' t quantile.
    pub df: usize,
    /// Whether the onsets contradict the fit ([`crate::lack_of_fit`]).
    pub lack_of_fit: LackOfFit,
}

/// The calibrated finger: every parameter under its finger-TOML name.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Calibration {
    /// `rect` or `disc`.
    pub shape: &'static str,
    /// Half-length `l` \[m\] (given, not fitted).
    pub half_length_m: f64,
    /// Friction coefficient.
    pub mu: Estimate,
    /// Pressure exponent.
    pub k: Estimate,
    /// `c` in `a = c·N^γ` [m/N^γ].
    pub c: Estimate,
    /// `γ`.
    pub gamma: Estimate,
    /// The skew (`[effect.skewed_pressure]`).
    pub skewed_pressure: SkewEstimates,
    /// Residual scales and counts.
    pub fit: FitSummary,
    /// Whether [`Calibration::conservative`] moved the values.
    pub conservative: bool,
    /// What the rows say against the fit: empty, or why its values do not describe the
    /// finger and the likely cause ([`crate::lack_of_fit`]). The joint fit's, kept by
    /// [`Calibration::conservative`] and [`Calibration::with_friction_contact`].
    pub warnings: Vec<String>,
    /// Set when [`Calibration::with_friction_contact`] moved `μ` and `c` or the
    /// half-length to the contact friction sees: what it moved, and the joint fit's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_contact: Option<FrictionContact>,
    /// The least indentation force [N] and the lower bound of `ln a`'s interval there
    /// ([`Calibration::conservative`]'s contact law).
    #[serde(skip)]
    contact_floor: (f64, f64),
}

fn kinds(slip: &[SlipOnset]) -> [usize; 3] {
    let mut k = [0; 3];
    for o in slip {
        k[match o.kind() {
            OnsetKind::Force => 0,
            OnsetKind::Torsion => 1,
            OnsetKind::Mixed => 2,
        }] += 1;
    }
    k
}

/// Refuses files with too few rows, stating the minimum.
fn check_counts(
    ind_file: &str,
    ind: &[Indentation],
    slip_file: &str,
    slip: &[SlipOnset],
) -> Result<(), CalibError> {
    if ind.len() < MIN_INDENTATION_ROWS {
        return Err(CalibError::TooFew {
            file: ind_file.to_string(),
            needed: format!(
                "indentation needs at least {MIN_INDENTATION_ROWS} rows (at 2 or more \
                 distinct forces to fit gamma); found {}",
                ind.len()
            ),
        });
    }
    let [force, _, mixed] = kinds(slip);
    if force + mixed < MIN_TANGENTIAL_ONSETS {
        return Err(CalibError::TooFew {
            file: slip_file.to_string(),
            needed: format!(
                "slip needs at least {MIN_TANGENTIAL_ONSETS} onsets with a tangential force \
                 (pure force or mixed) to fit mu; found {}",
                force + mixed
            ),
        });
    }
    Ok(())
}

fn setup_error(setup: &Setup) -> Option<CalibError> {
    let l = setup.half_length_m;
    (setup.shape == FingerShape::Rect && !(l > 0.0 && l.is_finite()))
        .then(|| CalibError::Setting(format!("half-length: {l} must be a finite number > 0 [m]")))
}

/// The grid the data need: aspects `l/a(N)` over every force of both files (by the
/// closed-form contact fit), widened by a fixed factor each way; the skew axis when the rectangle
/// has [`MIN_MIXED_ONSETS`] mixed onsets.
pub fn grid_for(
    setup: &Setup,
    ind: &[Indentation],
    slip: &[SlipOnset],
) -> Result<SurfaceGrid, CalibError> {
    if let Some(e) = setup_error(setup) {
        return Err(e);
    }
    let contact = fit_contact(ind, GAMMA_HELD);
    let forces = ind
        .iter()
        .map(|r| r.normal_force_n)
        .chain(slip.iter().map(|o| o.normal_force_n));
    let (lo, hi) = forces.fold((f64::INFINITY, 0.0f64), |(lo, hi), n| {
        (lo.min(n), hi.max(n))
    });
    let aspect = |n: f64| setup.half_length_m / (contact.c_m_per_n_gamma * n.powf(contact.gamma));
    let (amin, amax) = (aspect(hi) / 1.5, aspect(lo) * 1.5);
    let skew = kinds(slip)[2] >= MIN_MIXED_ONSETS;
    SurfaceGrid::build(setup.shape, amin, amax, GRID_ASPECTS, skew)
}

/// Calibrates from the two files' rows (`ind_file`, `slip_file` name them in errors),
/// building the grid the data need ([`grid_for`]).
pub fn calibrate(
    setup: &Setup,
    ind_file: &str,
    ind: &[Indentation],
    slip_file: &str,
    slip: &[SlipOnset],
) -> Result<Calibration, CalibError> {
    check_counts(ind_file, ind, slip_file, slip)?;
    let grid = grid_for(setup, ind, slip)?;
    calibrate_on(&grid, setup, ind_file, ind, slip_file, slip)
}

/// The plan: which parameters move, their starts.
fn plan(setup: &Setup, grid: &SurfaceGrid, contact: &ContactFit, slip: &[SlipOnset]) -> FitPlan {
    let [force, torsion, mixed] = kinds(slip);
    let ratio = |o: &SlipOnset| (o.tangential_force_n / o.normal_force_n).ln();
    let pure: Vec<f64> = slip
        .iter()
        .filter(|o| o.kind() == OnsetKind::Force)
        .map(ratio)
        .collect();
    let ln_mu = if pure.is_empty() {
        slip.iter().map(ratio).fold(f64::NEG_INFINITY, f64::max) + 0.1
    } else {
        pure.iter().sum::<f64>() / pure.len() as f64
    };
    let k_free = torsion + mixed >= MIN_MOMENT_ONSETS && force + mixed >= 1;
    FitPlan {
        start: [
            contact.c_m_per_n_gamma.ln(),
            contact.gamma,
            ln_mu,
            1.0 / K_HELD,
            0.0,
        ],
        free: [
            true,
            contact.gamma_fitted,
            true,
            k_free,
            grid.has_skew() && mixed >= MIN_MIXED_ONSETS && setup.shape == FingerShape::Rect,
        ],
        half_length_m: setup.half_length_m,
    }
}

/// [`calibrate`] on a prebuilt grid (of the setup's shape, spanning the data's aspects:
/// lookups clamp outside it).
pub fn calibrate_on(
    grid: &SurfaceGrid,
    setup: &Setup,
    ind_file: &str,
    ind: &[Indentation],
    slip_file: &str,
    slip: &[SlipOnset],
) -> Result<Calibration, CalibError> {
    check_counts(ind_file, ind, slip_file, slip)?;
    if let Some(e) = setup_error(setup) {
        return Err(e);
    }
    let contact = fit_contact(ind, GAMMA_HELD);
    let mut plan = plan(setup, grid, &contact, slip);
    let singular = || {
        CalibError::Setting(format!(
            "{slip_file}: the onsets do not determine the parameters (their information \
             matrix is singular): add onsets of another kind or at other forces"
        ))
    };
    let skewed = if plan.free[SKEW_SQ] {
        plan.start[SKEW_SQ] = 0.2;
        Some(fit_joint(grid, &plan, &contact, ind, slip).ok_or_else(singular)?)
    } else {
        None
    };
    let t_of = |f: &JointFit| t975(f.df.max(1));
    let skew_ci = skewed.as_ref().map(|f| {
        let se = f.cov[SKEW_SQ * PARAMS + SKEW_SQ].max(0.0).sqrt();
        wald(f.values[SKEW_SQ], se, t_of(f), 0.0, MAX_SKEW * MAX_SKEW)
    });
    let skew_identified = skew_ci.is_some_and(|(lo, _)| lo > 0.0);
    let fit = match skewed {
        Some(f) if skew_identified => f,
        _ => {
            plan.free[SKEW_SQ] = false;
            plan.start[SKEW_SQ] = 0.0;
            fit_joint(grid, &plan, &contact, ind, slip).ok_or_else(singular)?
        }
    };
    let skew_ci = skew_ci.map(|(lo, hi)| [lo.sqrt(), hi.sqrt()]);
    Ok(estimates(
        setup,
        &plan,
        &fit,
        ind,
        slip,
        skew_ci,
        skew_identified,
    ))
}

fn exp_pair((lo, hi): (f64, f64)) -> (f64, f64) {
    (lo.exp(), hi.exp())
}

const NO_SKEW: &str = "kept at 0, no skew (conservative: on the rectangle the skew only \
                       enlarges the limit surface)";

fn skew_estimates(
    setup: &Setup,
    mixed: usize,
    fit: &JointFit,
    ci: Option<[f64; 2]>,
    identified: bool,
) -> SkewEstimates {
    let delta = fit.values[SKEW_SQ].max(0.0).sqrt();
    let delta_over_a = if identified {
        Estimate::fitted(delta, ci.map_or((delta, delta), |c| (c[0], c[1])))
    } else if setup.shape == FingerShape::Disc {
        Estimate::held(
            0.0,
            None,
            "not fitted on the disc (its skewed surface is a 2-D integral per point): kept \
             at 0, no skew"
                .into(),
        )
    } else if ci.is_some() {
        Estimate::held(
            0.0,
            ci,
            format!(
                "the mixed onsets cannot tell it from no skew (its interval includes 0): {NO_SKEW}"
            ),
        )
    } else {
        Estimate::held(
            0.0,
            None,
            format!("needs {MIN_MIXED_ONSETS} mixed onsets, found {mixed}: {NO_SKEW}"),
        )
    };
    let held_delta = delta_over_a.value;
    SkewEstimates {
        delta_over_a,
        alpha: Estimate::held(
            SKEW_ALPHA,
            None,
            "limit-surface data cannot separate the skew's rate from its size: kept at 1.1, \
             the paper's (delta_over_a is fitted at it)"
                .into(),
        ),
        locus_over_a: Estimate::held(
            if setup.shape == FingerShape::Disc {
                0.0
            } else {
                held_delta / 2.0
            },
            None,
            if setup.shape == FingerShape::Disc {
                "the skew is not fitted on the disc: kept at 0, the symmetric profile's"
            } else {
                "the rectangle's surface does not depend on it: kept at delta_over_a/2, the \
                 paper's circular locus"
            }
            .into(),
        ),
    }
}

fn k_estimate(plan: &FitPlan, fit: &JointFit, t: f64, moment_onsets: usize) -> Estimate {
    if !plan.free[KAPPA] {
        return Estimate::held(
            K_HELD,
            None,
            format!(
                "needs {MIN_MOMENT_ONSETS} onsets with a torsional moment (pure torsion or \
                 mixed), found {moment_onsets}: kept at 2 (conservative: the low end of the \
                 plausible range [2, inf]; a lower k shrinks the whole limit surface)"
            ),
        );
    }
    let inv = |kappa: f64| {
        if kappa > 0.0 {
            1.0 / kappa
        } else {
            f64::INFINITY
        }
    };
    let kappa = fit.values[KAPPA];
    let se = fit.cov[KAPPA * PARAMS + KAPPA].max(0.0).sqrt();
    let (lo, hi) = wald(kappa, se, t, 0.0, 1.0);
    Estimate::fitted(inv(kappa), (inv(hi), inv(lo)))
}

fn estimates(
    setup: &Setup,
    plan: &FitPlan,
    fit: &JointFit,
    ind: &[Indentation],
    slip: &[SlipOnset],
    skew_ci: Option<[f64; 2]>,
    skew_identified: bool,
) -> Calibration {
    let t = t975(fit.df.max(1));
    let cov = |i: usize, j: usize| fit.cov[i * PARAMS + j];
    let se = |i: usize| cov(i, i).max(0.0).sqrt();
    let v = fit.values;
    let inf = f64::INFINITY;
    let n_min = ind.iter().map(|r| r.normal_force_n).fold(inf, f64::min);
    let gamma = if plan.free[GAMMA] {
        Estimate::fitted(v[GAMMA], wald(v[GAMMA], se(GAMMA), t, 0.0, 0.5))
    } else {
        Estimate::held(
            GAMMA_HELD,
            None,
            format!(
                "every indentation is at one force ({n_min} N): kept at 0 (conservative at and \
                 above that force, where a(N) stays at its measured size)"
            ),
        )
    };
    let x = n_min.ln();
    let var_ln_a = cov(LN_C, LN_C) + 2.0 * x * cov(LN_C, GAMMA) + x * x * cov(GAMMA, GAMMA);
    let ln_a_floor = v[LN_C] + v[GAMMA] * x - t * var_ln_a.max(0.0).sqrt();
    let k = kinds(slip);
    let p_slip = [LN_MU, KAPPA, SKEW_SQ]
        .iter()
        .filter(|&&i| plan.free[i])
        .count();
    let lack_of_fit = assess(slip, &fit.slip_residuals, p_slip);
    let warnings = warning(
        &lack_of_fit,
        setup.shape,
        setup.half_length_m,
        slip,
        &fit.slip_residuals,
    )
    .into_iter()
    .collect();
    Calibration {
        shape: setup.shape.name(),
        half_length_m: setup.half_length_m,
        mu: Estimate::fitted(
            v[LN_MU].exp(),
            exp_pair(wald(v[LN_MU], se(LN_MU), t, -inf, inf)),
        ),
        k: k_estimate(plan, fit, t, k[1] + k[2]),
        c: Estimate::fitted(
            v[LN_C].exp(),
            exp_pair(wald(v[LN_C], se(LN_C), t, -inf, inf)),
        ),
        gamma,
        skewed_pressure: skew_estimates(setup, k[2], fit, skew_ci, skew_identified),
        fit: FitSummary {
            indentation_rows: ind.len(),
            onsets_force_torsion_mixed: k,
            sigma_ln_half_width: fit.sigma_indentation,
            sigma_ln_utilisation: fit.sigma_slip,
            df: fit.df,
            lack_of_fit,
        },
        conservative: false,
        warnings,
        friction_contact: None,
        contact_floor: (n_min, ln_a_floor),
    }
}

impl Calibration {
    /// Every parameter at the end of its 95 % interval that lowers the capacity of the
    /// required-force rule (docs/calibration.md;
    /// host-sim/tests/calibrate_cli.rs::conservative_moves_each_parameter_toward_less_capacity):
    /// `μ`, `k` and the skew at their lower
    /// bounds (each shrinks the limit surface), `γ` at its lower bound and `c` such that
    /// `a(N)` is at its lower 95 % bound at the least indentation force `N₁` (then `a(N)`
    /// is below the fitted law at every `N ≥ N₁`; a smaller contact has a smaller moment
    /// arm `a·pitch(l/a)`). Held parameters stay where they are held. Of a calibration
    /// with a friction contact, the joint fit's conservative values ([`Calibration::joint`]:
    /// the refit has no interval to take an end of).
    pub fn conservative(&self) -> Self {
        let mut out = self.joint();
        out.mu.value = out.mu.lower();
        out.k.value = out.k.lower();
        out.gamma.value = out.gamma.lower();
        let (n_min, ln_a_floor) = self.contact_floor;
        out.c.value = (ln_a_floor - out.gamma.value * n_min.ln()).exp();
        let sp = &mut out.skewed_pressure;
        if sp.delta_over_a.identified {
            sp.delta_over_a.value = sp.delta_over_a.lower();
            if self.shape == FingerShape::Rect.name() {
                sp.locus_over_a.value = sp.delta_over_a.value / 2.0;
            }
        }
        out.conservative = true;
        out
    }

    /// This calibration with its warnings saying which settings of `resolved` were
    /// neither given nor recorded by the files (only the defaults): with a contradicted
    /// fit, the likeliest cause.
    pub fn noting_defaults(mut self, resolved: &ResolvedSetup) -> Self {
        let mut unsaid = Vec::new();
        if resolved.shape_from == SetupSource::Default {
            unsaid.push(format!("the shape ({})", resolved.setup.shape.name()));
        }
        if resolved.half_length_from == SetupSource::Default
            && resolved.setup.shape == FingerShape::Rect
        {
            unsaid.push(format!(
                "the half-length ({} m)",
                resolved.setup.half_length_m
            ));
        }
        if !unsaid.is_empty() {
            let (list, verb) = if unsaid.len() == 1 {
                (unsaid[0].clone(), "is only the default")
            } else {
                (unsaid.join(" and "), "are only the defaults")
            };
            for w in &mut self.warnings {
                w.push_str(&format!(
                    " Neither given nor recorded in the files, {list} {verb}."
                ));
            }
        }
        self
    }

    /// The least safety factor that covers `μ`'s interval
    /// (docs/decisions/calibration-fit.md): `μ / μ_lo`, since a controller told `μ` at
    /// safety `s` holds a true friction down to `μ/s`. `None` without an interval (a
    /// refitted `μ`). A drift the user expects multiplies it.
    pub fn safety_for_mu(&self) -> Option<f64> {
        let lo = self.mu.ci95?[0];
        (lo > 0.0 && lo.is_finite() && self.mu.value >= lo).then(|| self.mu.value / lo)
    }

    /// The finger's shape.
    pub fn finger_shape(&self) -> FingerShape {
        FingerShape::from_name(self.shape).unwrap_or(FingerShape::Rect)
    }

    /// The skew as the core takes it, `None` at `Δ/a = 0`.
    pub fn skew(&self) -> Option<SkewParams> {
        let s = &self.skewed_pressure;
        (s.delta_over_a.value > 0.0).then_some(SkewParams {
            delta_over_a: s.delta_over_a.value,
            alpha: s.alpha.value,
            locus_over_a: s.locus_over_a.value,
        })
    }

    /// The contact half-width `a(N) = c·N^γ` \[m\] at the calibration's values.
    pub fn half_width_m(&self, normal_n: f64) -> f64 {
        self.c.value * normal_n.powf(self.gamma.value)
    }
}
