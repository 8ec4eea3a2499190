//! An independent brute-force 2-D integrator for one point of the friction limit surface,
//! written straight from `docs/model.md` ("Sliding, friction and the limit surface") to check the
//! fast path ([`softgrip::FlsModel::point`]): the reference of the core's tests
//! (`tests/fls_brute_force.rs`, the stress suites), of `benches/fls.rs` and of `host-sim
//! accuracy`'s comparison at matched accuracy.
//!
//! It shares nothing with the crate's quadrature or its closed-form row and ring kernels:
//! only the pressure functions [`softgrip::pressure::rect_skewed_pa`] and
//! [`softgrip::pressure::disc_pa`] and the skew law are taken from the crate (with `N = 1`,
//! `a = 1`, `l = aspect`), because the pressure is checked on its own (its integral is `N`).
//!
//! With `N = μ = a = 1` and the centre of rotation at `(d, 0)` it integrates the sliding
//! direction `v̄ = (−y, x − d) / |(−y, x − d)|` weighted by the pressure over the patch and
//! returns `f̃ = |∫∫ p v̄ dΩ|` and `m̃ = |∫∫ p (x v̄_y − y v̄_x) dΩ|` (the sign of
//! `τ = −p v̄` does not matter under the absolute values).
//!
//! # The rule
//!
//! A composite tensor-product Gauss–Legendre rule ([`GL_ORDER`] × [`GL_ORDER`] points per
//! cell, nodes and weights computed here by Newton's method on the Legendre recurrence):
//!
//! - **Rectangle** `[-λ, λ] × [-1, 1]`, Cartesian. Each axis is cut at every line where the
//!   integrand is not smooth: the patch edges, the centre of rotation's lines `x = d` (when
//!   `|d| < λ`) and `y = 0`, and the pressure peak's line `y = Δy`.
//! - **Disc**, polar coordinates `(r, θ)` about the disc centre (`dΩ = r dr dθ`), cut at
//!   `r = 1`, `r = d` (when `d < 1`), `θ = 0`, and at the peak's radius and angle.
//!
//! Every singular point of the integrand (the centre of rotation, where `v̄` has no limit;
//! the pressure peak, where a skewed profile is only `C¹`; the edge, where the pressure
//! falls like `dist^(1/k)`) then sits on a cell boundary. Each piece `[u₀, u₁]` between two
//! cuts is mapped from `t ∈ [0, 1]` by the "smootherstep" polynomial
//! `u = u₀ + (u₁ − u₀)(10t³ − 15t⁴ + 6t⁵)`, whose Jacobian `30 t²(1 − t)²` vanishes at both
//! ends. That turns an edge behaviour `dist^(1/k)` into `t^(2 + 3/k)` and damps the
//! centre-of-rotation discontinuity by `t²`, so uniform cells in `t` converge like
//! `cells^-(3 + 3/k)` (measured: `cells^-4.5` for k = 2, `cells^-3.7` for k = 4, faster for
//! the k = 3 disc). `cells` is the number of uniform cells in `t` per piece and per axis.
//!
//! Cost: `(pieces_x · cells · 4) · (pieces_y · cells · 4)` pressure evaluations, with 2–4
//! pieces per axis (about 0.4 ms for a rectangle point at `cells = 16` in release).
//!
//! Accuracy, measured against `cells = 128` over the cases of `tests/fls_brute_force.rs`
//! (rectangle k = 2 at aspects 0.3, 1, 3; rectangle k = 4 skewed; disc k = 2; disc k = 3
//! skewed; `d ∈ {0, 0.3, edge, 1.7, 20}`), worst error in `f̃` or `m̃`:
//!
//! | cells | 2      | 4      | 8      | 16     | 32      |
//! | ----- | ------ | ------ | ------ | ------ | ------- |
//! | error | 4.5e-3 | 2.6e-5 | 2.8e-7 | 7.7e-9 | 5.6e-10 |
//!
//! and for `∫∫ p dΩ = 1` (exact; k = 1…4, peaks up to 0.99 of the way to the edge):
//! 1.4e-8 at `cells = 16`, 1.0e-9 at `cells = 32`.

#![forbid(unsafe_code)]

use softgrip::pressure::{disc_pa, rect_skewed_pa, KProfile};
use softgrip::skew::SkewLaw;

/// Gauss–Legendre points per cell and per axis.
pub const GL_ORDER: usize = 4;

/// `n`-point Gauss–Legendre nodes and weights on `[-1, 1]`, ascending nodes, by Newton's
/// method on `P_n` from the three-term recurrence (converged to machine precision).
pub fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    assert!(n >= 1, "need at least one node");
    let mut rule = Vec::with_capacity(n);
    for i in 0..n {
        // Chebyshev-like first guess for the (n − i)-th root (roots descend with i).
        let mut x = (core::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            // P_n(x) and P_n'(x).
            let (mut p0, mut p1) = (1.0, x);
            for j in 2..=n {
                let jf = j as f64;
                let p2 = ((2.0 * jf - 1.0) * x * p1 - (jf - 1.0) * p0) / jf;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let pn = p1;
            let step = pn / dp;
            x -= step;
            if step.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        rule.push((x, w));
    }
    rule.reverse();
    rule
}

/// A 1-D composite rule over the pieces between consecutive `cuts` (sorted, deduplicated
/// here): `cells` uniform cells in `t` per piece, each with the Gauss–Legendre rule `gl`,
/// through the smootherstep map. Returns `(node, weight)` pairs.
pub fn axis_rule(cuts: &[f64], cells: usize, gl: &[(f64, f64)]) -> Vec<(f64, f64)> {
    assert!(cells >= 1, "need at least one cell per piece");
    let mut cuts: Vec<f64> = cuts.to_vec();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() <= 1e-15 * (1.0 + b.abs()));
    let mut out = Vec::with_capacity((cuts.len().saturating_sub(1)) * cells * gl.len());
    for piece in cuts.windows(2) {
        let (lo, hi) = (piece[0], piece[1]);
        let len = hi - lo;
        for c in 0..cells {
            for &(u, w) in gl {
                let t = (c as f64 + 0.5 * (u + 1.0)) / cells as f64;
                let wt = 0.5 * w / cells as f64;
                let phi = t * t * t * (10.0 + t * (-15.0 + 6.0 * t));
                let dphi = 30.0 * t * t * (1.0 - t) * (1.0 - t);
                out.push((lo + len * phi, wt * len * dphi));
            }
        }
    }
    out
}

/// The patch shape (lengths in units of `a`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Patch {
    /// The rectangle `[-aspect, aspect] × [-1, 1]`.
    Rect {
        /// `λ = l/a`.
        aspect: f64,
    },
    /// The unit disc.
    Disc,
}

/// One limit surface: shape, pressure exponent and optional skew `(Δ/a, α, h/a)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Case {
    /// Patch shape.
    pub patch: Patch,
    /// Pressure exponent `k ≥ 1`.
    pub k: f64,
    /// Skew `(Δ/a, α, h/a)` or `None`.
    pub skew: Option<(f64, f64, f64)>,
}

impl Case {
    /// The pressure peak `(Δx, Δy)` (units of `a`) at centre of rotation `d`, from the skew
    /// law (Eq. 16, 17); `(0, 0)` when symmetric.
    pub fn peak(&self, d: f64) -> (f64, f64) {
        match self.skew {
            None => (0.0, 0.0),
            Some((delta, alpha, h)) => SkewLaw::<f64>::new(delta, alpha, h)
                .expect("valid skew law")
                .peak(d),
        }
    }

    /// Integrates `[p, p v̄_x, p v̄_y, p (x v̄_y − y v̄_x)]` over the patch, with the pressure
    /// peak placed by the skew law for the centre of rotation `d` and `v̄` taken about `d`.
    pub fn integrals(&self, d: f64, cells: usize) -> [f64; 4] {
        integrals(self.patch, self.k, self.peak(d), d, cells)
    }

    /// The limit-surface point `(f̃, m̃)` at `d = d_c/a`, with `cells` cells per piece.
    pub fn point(&self, d: f64, cells: usize) -> (f64, f64) {
        let [_, fx, fy, m] = self.integrals(d, cells);
        (fx.hypot(fy), m.abs())
    }
}

/// `∫∫ p dΩ / N` for the pressure with exponent `k` and its peak at `peak = (Δx, Δy)` (only
/// `Δy` matters on the rectangle): 1 at equilibrium.
pub fn pressure_total(patch: Patch, k: f64, peak: (f64, f64), cells: usize) -> f64 {
    integrals(patch, k, peak, 0.0, cells)[0]
}

/// Integrates `[p, p v̄_x, p v̄_y, p (x v̄_y − y v̄_x)]` over `patch`, for the pressure with
/// exponent `k` and its peak at `peak = (Δx, Δy)` (units of `a`; only `Δy` matters on the
/// rectangle) and the centre of rotation at `(d, 0)`, with `cells` cells per piece.
pub fn integrals(patch: Patch, k: f64, peak: (f64, f64), d: f64, cells: usize) -> [f64; 4] {
    let profile = KProfile::<f64>::new(k).expect("valid k");
    let gl = gauss_legendre(GL_ORDER);
    let mut acc = [0.0f64; 4];
    let mut add = |x: f64, y: f64, p: f64, w: f64| {
        let (vx, vy) = (-y, x - d);
        let norm = vx.hypot(vy);
        let pw = p * w;
        acc[0] += pw;
        if norm > 0.0 {
            let (vx, vy) = (vx / norm, vy / norm);
            acc[1] += pw * vx;
            acc[2] += pw * vy;
            acc[3] += pw * (x * vy - y * vx);
        }
    };
    match patch {
        Patch::Rect { aspect } => {
            let mut xcuts = vec![-aspect, aspect];
            if d.abs() < aspect {
                xcuts.push(d);
            }
            let mut ycuts = vec![-1.0, 1.0, 0.0];
            if peak.1.abs() < 1.0 {
                ycuts.push(peak.1);
            }
            let xs = axis_rule(&xcuts, cells, &gl);
            let ys = axis_rule(&ycuts, cells, &gl);
            for &(y, wy) in &ys {
                for &(x, wx) in &xs {
                    let p = rect_skewed_pa(&profile, 1.0, 1.0, aspect, peak.1, x, y);
                    add(x, y, p, wx * wy);
                }
            }
        }
        Patch::Disc => {
            use core::f64::consts::PI;
            let mut rcuts = vec![0.0, 1.0];
            if d > 0.0 && d < 1.0 {
                rcuts.push(d);
            }
            let mut tcuts = vec![-PI, PI, 0.0];
            let peak_r = peak.0.hypot(peak.1);
            if peak_r > 0.0 {
                rcuts.push(peak_r);
                tcuts.push(peak.1.atan2(peak.0));
            }
            let rs = axis_rule(&rcuts, cells, &gl);
            let ts = axis_rule(&tcuts, cells, &gl);
            for &(t, wt) in &ts {
                let (s, c) = t.sin_cos();
                for &(r, wr) in &rs {
                    let (x, y) = (r * c, r * s);
                    let p = disc_pa(&profile, 1.0, 1.0, peak, x, y);
                    add(x, y, p, wr * wt * r);
                }
            }
        }
    }
    acc
}
