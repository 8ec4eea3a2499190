//! The ellipse approximation of the limit surface (Eq. 10) and how far the exact surface
//! lies inside it.

use crate::fls::{FlsModel, FlsPoint, FlsTable};
use crate::real::Real;

/// A least-squares ellipse `f̃²/A² + m̃²/B² = 1` through a sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipseFit<T> {
    /// Semi-axis `A` along `f̃`.
    pub f_semi_axis: T,
    /// Semi-axis `B` along `m̃`.
    pub m_semi_axis: T,
    /// Root-mean-square residual of `f̃²/A² + m̃²/B² − 1` over the points.
    pub rms_residual: T,
}

impl<T: Real> EllipseFit<T> {
    /// Fits `p f̃² + q m̃² = 1` by linear least squares in `(p, q) = (1/A², 1/B²)` over the
    /// points (a 2×2 normal system). Returns `None` when the points do not determine it.
    pub fn fit(points: &[FlsPoint<T>]) -> Option<Self> {
        let (mut s_ff, mut s_fm, mut s_mm, mut s_f, mut s_m) =
            (T::zero(), T::zero(), T::zero(), T::zero(), T::zero());
        for p in points {
            let (a, b) = (p.f * p.f, p.m * p.m);
            s_ff = s_ff + a * a;
            s_fm = s_fm + a * b;
            s_mm = s_mm + b * b;
            s_f = s_f + a;
            s_m = s_m + b;
        }
        let det = s_ff * s_mm - s_fm * s_fm;
        if !(det > T::zero()) {
            return None;
        }
        let p = (s_f * s_mm - s_m * s_fm) / det;
        let q = (s_ff * s_m - s_fm * s_f) / det;
        if !(p > T::zero() && q > T::zero()) {
            return None;
        }
        let mut sq = T::zero();
        for pt in points {
            let r = p * pt.f * pt.f + q * pt.m * pt.m - T::one();
            sq = sq + r * r;
        }
        Some(Self {
            f_semi_axis: p.libm_sqrt().recip(),
            m_semi_axis: q.libm_sqrt().recip(),
            rms_residual: (sq / T::of_usize(points.len().max(1))).libm_sqrt(),
        })
    }
}

/// The largest radial gap between the exact surface and the Eq. 10 ellipse
/// `f̃² + (m̃/pitch)² = 1`, measured along rays from the origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RadialGap<T> {
    /// `r_ellipse − r_exact` at its largest (positive: the surface lies inside).
    pub max_gap: T,
    /// The same gap divided by `r_ellipse`.
    pub max_relative_gap: T,
    /// The point of the exact surface where the gap is largest.
    pub at: FlsPoint<T>,
    /// How far the exact surface pokes *outside* the ellipse, `max(r_exact − r_ellipse)`
    /// over the table's samples, or 0 if it never does. The symmetric profiles stay inside;
    /// a strong, fast skew can push the surface out near pure torsion.
    pub max_outside: T,
}

/// Radius of the ellipse `f̃² + (m̃/pitch)² = 1` in the direction of `(f, m)`.
pub fn ellipse_radius<T: Real>(pitch: T, f: T, m: T) -> T {
    let r = f.libm_hypot(m);
    if r == T::zero() {
        return T::zero();
    }
    let (c, s) = (f / r, m / r);
    (c * c + (s / pitch) * (s / pitch)).libm_sqrt().recip()
}

impl<T: Real> RadialGap<T> {
    /// Finds the largest gap: the best sample of `table`, refined by a golden-section search
    /// over the sweep parameter between its neighbours with exact `model` evaluations
    /// (40 more points; the location is then known to about 1e-8 in `t`).
    pub fn find<const CAP: usize>(model: &FlsModel<T>, table: &FlsTable<T, CAP>) -> Self {
        let pitch = table.pitch();
        let gap = |p: &FlsPoint<T>| ellipse_radius(pitch, p.f, p.m) - p.f.libm_hypot(p.m);
        let pts = table.points();
        let mut best = 0;
        let mut best_gap = T::neg_infinity();
        let mut max_outside = T::zero();
        for (i, p) in pts.iter().enumerate() {
            let g = gap(p);
            max_outside = max_outside.max(-g);
            if g > best_gap {
                best_gap = g;
                best = i;
            }
        }
        let map = table.map();
        let t_at = |i: usize| pts.get(i).map_or(T::zero(), |p| map.t_of(p.d));
        let mut lo = t_at(best.saturating_sub(1));
        let mut hi = t_at((best + 1).min(pts.len().saturating_sub(1)));
        let mut best_point = pts.get(best).copied().unwrap_or_default();
        let ratio = T::of(0.618_033_988_749_894_9);
        let eval = |t: T| {
            let p = model.point(map.d_of(t));
            (gap(&p), p)
        };
        let mut x1 = hi - ratio * (hi - lo);
        let mut x2 = lo + ratio * (hi - lo);
        let (mut g1, mut p1) = eval(x1);
        let (mut g2, mut p2) = eval(x2);
        for _ in 0..40 {
            if g1 > g2 {
                hi = x2;
                x2 = x1;
                g2 = g1;
                p2 = p1;
                x1 = hi - ratio * (hi - lo);
                (g1, p1) = eval(x1);
            } else {
                lo = x1;
                x1 = x2;
                g1 = g2;
                p1 = p2;
                x2 = lo + ratio * (hi - lo);
                (g2, p2) = eval(x2);
            }
        }
        for (g, p) in [(g1, p1), (g2, p2)] {
            if g > best_gap {
                best_gap = g;
                best_point = p;
            }
        }
        let r_e = ellipse_radius(pitch, best_point.f, best_point.m);
        Self {
            max_gap: best_gap,
            max_relative_gap: if r_e > T::zero() {
                best_gap / r_e
            } else {
                T::zero()
            },
            at: best_point,
            max_outside,
        }
    }
}
