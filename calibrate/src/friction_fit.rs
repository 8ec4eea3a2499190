//! The joint fit of every parameter to both lab files: nonlinear least squares on
//! log-scale residuals,
//!
//! - indentation row: `ln a − ln c − γ ln N`;
//! - slip onset: `ln u`, where `u` is the utilisation of the measured load on the exact
//!   surface at the fitted `μ`, `k`, skew and `a(N) = c·N^γ` (an onset lies on the surface,
//!   `u = 1`). Pure force onsets give `u = f_t/(μN)`, pure torsion `m_n/(μ N a pitch(k,
//!   l/a))`, mixed ones the surface's shape in between.
//!
//! Each file's residuals are divided by that file's residual scale `σ` (estimated from the
//! fit, `n − p` degrees of freedom), so the two files weigh as their noise says; the
//! covariance of the estimate is `(JᵀJ)⁻¹` of the weighted residuals. Parameters: `ln c`,
//! `γ ∈ [0, ½]`, `ln μ`, `κ = 1/k ∈ [0, 1]` and `s = (Δ/a)² ∈ [0, MAX_SKEW²]` (the surface
//! moves about linearly in `s`, and not at all to first order in `Δ/a` at 0:
//! docs/decisions/calibration-fit.md). Cost: two Levenberg–Marquardt solves from three
//! starts in `κ`; about 1–3 ms for 60 rows.

use crate::contact_fit::ContactFit;
use crate::interval::invert;
use crate::lab_csv::{Indentation, SlipOnset};
use crate::lsq::{minimise, Param};
use crate::surface::{SurfaceGrid, MAX_SKEW};

/// Index of `ln c` in the parameter vector.
pub const LN_C: usize = 0;
/// Index of `γ`.
pub const GAMMA: usize = 1;
/// Index of `ln μ`.
pub const LN_MU: usize = 2;
/// Index of `κ = 1/k`.
pub const KAPPA: usize = 3;
/// Index of `s = (Δ/a)²`.
pub const SKEW_SQ: usize = 4;
/// Number of parameters.
pub const PARAMS: usize = 5;

/// Which parameters move, and the values the fixed ones are held at.
#[derive(Debug, Clone, Copy)]
pub struct FitPlan {
    /// Start (free) or held (fixed) values, by index.
    pub start: [f64; PARAMS],
    /// Which are fitted.
    pub free: [bool; PARAMS],
    /// Half-length `l` \[m\] (the rectangle's aspect `l/a`).
    pub half_length_m: f64,
}

/// The joint optimum.
#[derive(Debug, Clone)]
pub struct JointFit {
    /// Every parameter, by index.
    pub values: [f64; PARAMS],
    /// Covariance, `PARAMS × PARAMS` row-major (zero rows for held parameters).
    pub cov: Vec<f64>,
    /// Residual scale of the indentation rows (`ln a`).
    pub sigma_indentation: f64,
    /// Residual scale of the onsets (`ln u`).
    pub sigma_slip: f64,
    /// Degrees of freedom of the intervals: the smaller file's `n − p`.
    pub df: usize,
    /// `ln u` of each onset at the optimum (0 on the fitted surface).
    pub slip_residuals: Vec<f64>,
}

/// `ln u` of `onset` at the parameters `p`.
pub fn onset_residual(grid: &SurfaceGrid, l_m: f64, p: &[f64], o: &SlipOnset) -> f64 {
    let n = o.normal_force_n;
    let a = p[LN_C].exp() * n.powf(p[GAMMA]);
    let mu = p[LN_MU].exp();
    let u = grid.utilisation(
        p[KAPPA],
        l_m / a,
        p[SKEW_SQ].max(0.0).sqrt(),
        o.tangential_force_n / (mu * n),
        o.torsional_moment_nm / (mu * n * a),
    );
    u.ln()
}

fn residuals(
    grid: &SurfaceGrid,
    plan: &FitPlan,
    ind: &[Indentation],
    slip: &[SlipOnset],
    sig: (f64, f64),
    p: &[f64],
) -> Vec<f64> {
    let ind_r = ind
        .iter()
        .map(|r| (r.half_width_m.ln() - p[LN_C] - p[GAMMA] * r.normal_force_n.ln()) / sig.0);
    let slip_r = slip
        .iter()
        .map(|o| onset_residual(grid, plan.half_length_m, p, o) / sig.1);
    ind_r.chain(slip_r).collect()
}

fn params(plan: &FitPlan, kappa: f64) -> Vec<Param> {
    let bounds = [
        (-1e3, 1e3, 1e-6),
        (0.0, 0.5, 1e-6),
        (-1e3, 1e3, 1e-6),
        (0.0, 1.0, 1e-3),
        (0.0, MAX_SKEW * MAX_SKEW, 1e-3),
    ];
    (0..PARAMS)
        .map(|i| Param {
            value: if i == KAPPA && plan.free[i] {
                kappa
            } else {
                plan.start[i]
            },
            lo: bounds[i].0,
            hi: bounds[i].1,
            step: bounds[i].2,
            free: plan.free[i],
        })
        .collect()
}

/// The best of three starts spread over `κ`'s range (one if `κ` is held) at weights `sig`.
fn solve_weighted(
    grid: &SurfaceGrid,
    plan: &FitPlan,
    ind: &[Indentation],
    slip: &[SlipOnset],
    sig: (f64, f64),
) -> crate::lsq::LsqFit {
    let f = |p: &[f64]| residuals(grid, plan, ind, slip, sig, p);
    let starts: &[f64] = if plan.free[KAPPA] {
        &[0.1, 0.5, 0.9]
    } else {
        &[0.0]
    };
    let cost = |r: &[f64]| r.iter().map(|x| x * x).sum::<f64>();
    starts
        .iter()
        .map(|&k| minimise(&f, &params(plan, k)))
        .min_by(|a, b| cost(&a.residuals).total_cmp(&cost(&b.residuals)))
        .unwrap_or_else(|| minimise(&f, &params(plan, 0.5)))
}

/// Fits the free parameters of `plan` to both files. `contact` is the closed-form
/// indentation fit (its `σ` weighs the indentation rows). `None` when the information
/// matrix is singular (a parameter the rows do not determine was left free).
pub fn fit_joint(
    grid: &SurfaceGrid,
    plan: &FitPlan,
    contact: &ContactFit,
    ind: &[Indentation],
    slip: &[SlipOnset],
) -> Option<JointFit> {
    let floor = 1e-9;
    let sig_ind = contact.sigma_ln.max(floor);
    let n_ind_free = [LN_C, GAMMA].iter().filter(|&&i| plan.free[i]).count();
    let n_slip_free = [LN_MU, KAPPA, SKEW_SQ]
        .iter()
        .filter(|&&i| plan.free[i])
        .count();
    let df_slip = slip.len().saturating_sub(n_slip_free);
    let mut sig_slip = sig_ind;
    let mut fit = solve_weighted(grid, plan, ind, slip, (sig_ind, sig_slip));
    for _ in 0..2 {
        let sse: f64 = fit.residuals[ind.len()..]
            .iter()
            .map(|r| (r * sig_slip).powi(2))
            .sum();
        sig_slip = (sse / df_slip.max(1) as f64).sqrt().max(floor);
        fit = solve_weighted(grid, plan, ind, slip, (sig_ind, sig_slip));
    }
    let m = fit.free.len();
    let (jtj, _) = crate::lsq::normal_equations(&fit.jacobian, &fit.residuals, m);
    let inv = invert(&jtj, m)?;
    let mut cov = vec![0.0; PARAMS * PARAMS];
    for (a, &i) in fit.free.iter().enumerate() {
        for (b, &j) in fit.free.iter().enumerate() {
            cov[i * PARAMS + j] = inv[a * m + b];
        }
    }
    let mut values = [0.0; PARAMS];
    values.copy_from_slice(&fit.values);
    Some(JointFit {
        values,
        cov,
        sigma_indentation: contact.sigma_ln,
        sigma_slip: sig_slip,
        df: ind.len().saturating_sub(n_ind_free).min(df_slip),
        slip_residuals: fit.residuals[ind.len()..]
            .iter()
            .map(|r| r * sig_slip)
            .collect(),
    })
}
