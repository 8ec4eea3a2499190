//! Quasi-static loading and the onset of gross slip.
//!
//! [`equilibrium`] finds the object's pose at which the bristles of a contact transmit a
//! given wrench `(F_x, F_y, M)`, starting from a committed bristle state: Newton's method
//! on the pose with the bristles' consistent tangent stiffness (stuck and sliding), every iterate evaluated by the
//! stick–slip rules from the committed anchors (so a trial that slips an element is
//! judged from the same history as the last), step-halving on the residual, at most
//! [`ITERATIONS`] iterations. It fails (no equilibrium) when no bristle sticks, when the
//! iteration does not converge, or when the pose runs beyond [`RUNAWAY`] (the
//! displacement runs away). In pure torsion the continuum's stuck zone shrinks to the
//! centre only as `θ → ∞`; on the grid the last element to slip is the one nearest the
//! centre, so the onset is reached at a finite rotation and equals `Σ μ p A r` when
//! `μ_k = μ_s`.
//!
//! **Gross slip onset** ([`ramp`]): the load is ramped proportionally, `λ·(F, M)` from
//! `λ = 0` on fresh bristles, in steps of `λ*/STEPS` (`λ*` the linear interaction estimate
//! `1/(|F|/F_lim + |M|/M_lim)` from the full-slip limits `F_lim = Σ μ_s p A`,
//! `M_lim = Σ μ_s p A r`), committing each equilibrium; the onset is the largest `λ` for
//! which an equilibrium exists, refined between the last equilibrium and the first
//! failure by [`REFINE`] bisections, each from the last committed state. The ramp stops at
//! `λ = 3·λ*` (no onset: `None`); a convex limit surface lies between the diamond
//! `λ*` and the box `2·λ*`, so a contact that holds beyond that bound is not slipping.
//!
//! Accuracy: the onset is bracketed to `λ*/STEPS/2^REFINE`; the equilibria to
//! [`TOLERANCE`] of the normal force. Cost: a few bristle passes per step,
//! `STEPS·3 + REFINE` steps at most.

use super::bristles::{BristleWrench, Pose};
use super::contact::Contact;

/// Most Newton iterations per equilibrium.
pub const ITERATIONS: usize = 60;
/// Residual accepted as equilibrium, relative to `N` (forces) and `N·Y` (moment, `Y` the
/// mesh half-width). Tighter is not always reachable: near an element's stick–slip
/// switch the residual is not smooth and Newton's steps stall around `1e-8`.
pub const TOLERANCE: f64 = 1e-7;
/// Ramp steps up to the estimate `λ*`.
pub const STEPS: usize = 100;
/// Bisections refining the onset.
pub const REFINE: usize = 30;
/// Largest translation, as a multiple of the patch's half-extent, and rotation \[rad\] of an
/// equilibrium: a guard against numerical blow-up only, far beyond any displacement an
/// equilibrium needs (a full-slip stretch is `μ·p/k_t`, well under the patch's size; in
/// pure torsion the last stuck elements are the ones nearest the centre, so the rotation
/// at the onset is `μ·p/(k_t·r_min)`, several radians on fine grids: the kinematics are
/// linear in `θ`, so that is a parameter, not a pose).
pub const RUNAWAY: f64 = 1e3;

fn residual(w: &BristleWrench, target: [f64; 3], scale: [f64; 2]) -> ([f64; 3], f64) {
    let r = [
        target[0] - w.f_t_n[0],
        target[1] - w.f_t_n[1],
        target[2] - w.m_n_nm,
    ];
    let norm = (r[0] / scale[0])
        .hypot(r[1] / scale[0])
        .hypot(r[2] / scale[1]);
    (r, norm)
}

/// Solves `−K·dq = r` for the pose increment, `K` the bristles' symmetric tangent
/// (Cramer's rule); `None` when `K` is singular (no bristle resists some direction).
fn solve3(w: &BristleWrench, r: [f64; 3]) -> Option<[f64; 3]> {
    let t = w.tangent;
    let k = [[t[0], t[1], t[2]], [t[1], t[3], t[4]], [t[2], t[4], t[5]]];
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(&k);
    let scale = t[0] * t[3] * t[5];
    if !(d > 1e-12 * scale && d.is_finite()) {
        return None;
    }
    let mut x = [0.0; 3];
    for (c, xc) in x.iter_mut().enumerate() {
        let mut m = k;
        for (row, rv) in m.iter_mut().zip(r) {
            row[c] = -rv;
        }
        *xc = det(&m) / d;
    }
    Some(x)
}

/// The equilibrium pose for `target` from the committed state `committed` at pose `q0`
/// (see the module docs): the contact as it is there, or `None`.
pub fn equilibrium(committed: &Contact, q0: Pose, target: [f64; 3]) -> Option<(Contact, Pose)> {
    let patch = committed.patch();
    let reach = RUNAWAY
        * patch
            .half_width_m
            .max(patch.x_m.iter().fold(0.0, |a, x| a.max(x.abs())));
    let scale = [
        committed.normal_n().max(1e-12),
        committed.normal_n().max(1e-12) * patch.half_width_m,
    ];
    let mut q = q0;
    let mut c = committed.clone();
    let mut w = c.displace_with_tangent(q);
    let (mut r, mut norm) = residual(&w, target, scale);
    for _ in 0..ITERATIONS {
        if norm < TOLERANCE {
            return Some((c, q));
        }
        let dq = solve3(&w, r)?;
        let mut t = 1.0;
        loop {
            let trial = Pose {
                ux_m: q.ux_m + t * dq[0],
                uy_m: q.uy_m + t * dq[1],
                theta_rad: q.theta_rad + t * dq[2],
            };
            let mut ct = committed.clone();
            let wt = ct.displace_with_tangent(trial);
            let (rt, nt) = residual(&wt, target, scale);
            if nt < norm || t < 1e-4 {
                (q, c, w, r, norm) = (trial, ct, wt, rt, nt);
                break;
            }
            t *= 0.5;
        }
        if q.ux_m.hypot(q.uy_m) > reach || q.theta_rad.abs() > RUNAWAY || !norm.is_finite() {
            return None;
        }
    }
    (norm < TOLERANCE).then_some((c, q))
}

/// The committed state after loading to `lam`, or `None` without an equilibrium.
fn load_to(
    c: &Contact,
    q: Pose,
    normal_n: f64,
    unit: [f64; 2],
    lam: f64,
) -> Option<(Contact, Pose)> {
    let mut pressed = c.clone();
    pressed.press(normal_n, lam * unit[0]);
    equilibrium(&pressed, q, [0.0, lam * unit[0], lam * unit[1]])
}

/// The gross-slip onset `λ` on the ramp `λ·(F_y, M)` = `unit` at `normal_n` from the
/// fresh contact `fresh` (see the module docs), or `None`.
pub fn ramp(fresh: &Contact, normal_n: f64, unit: [f64; 2]) -> Option<f64> {
    if !(normal_n > 0.0 && normal_n.is_finite() && unit.iter().all(|u| u.is_finite())) {
        return None;
    }
    let mut c = fresh.clone();
    c.press(normal_n, 0.0);
    let (f_lim, m_lim) = c.full_slip_limits();
    let inv = unit[0].abs() / f_lim + unit[1].abs() / m_lim;
    if !(inv > 0.0 && inv.is_finite()) {
        return None;
    }
    let step = 1.0 / inv / STEPS as f64;
    let mut q = Pose::default();
    let mut lam = 0.0;
    for _ in 0..3 * STEPS {
        match load_to(&c, q, normal_n, unit, lam + step) {
            Some((next, qn)) => {
                (c, q, lam) = (next, qn, lam + step);
            }
            None => {
                let (mut lo, mut hi) = (lam, lam + step);
                for _ in 0..REFINE {
                    let mid = 0.5 * (lo + hi);
                    if load_to(&c, q, normal_n, unit, mid).is_some() {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return Some(lo);
            }
        }
    }
    None
}
