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
    /// points (a two-by-two normal system). Returns `None` when the points do not determine it.
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

/// An ellipse `x²/A² + y²/B² ≤ 1` *inscribed* in the exact limit surface, in the
/// normalised coordinates `(x, y) = (f̃, m̃/pitch)` where the Eq. 10 ellipse is the unit
/// circle. The exact surface lies inside Eq. 10 near the diagonal, so a controller that
/// tests loads against Eq. 10 asks for too little force there; one that tests against an
/// inscribed ellipse never does.
///
/// Built by a fit and a shrink ([`InscribedEllipse::fit_within`]): an ellipse shape,
/// scaled by the largest factor that keeps it inside every chord of the sampled surface.
/// The chords lie inside the convex surface, so the result is inside the exact surface
/// (it touches the chord polygon, which lies within about `(Δθ)²/8` of the curve).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InscribedEllipse<T> {
    /// Semi-axis `A` along `x = f̃`.
    pub x_semi_axis: T,
    /// Semi-axis `B` along `y = m̃/pitch`.
    pub y_semi_axis: T,
}

impl<T: Real> InscribedEllipse<T> {
    /// The unit circle: Eq. 10 itself.
    pub fn unit() -> Self {
        Self {
            x_semi_axis: T::one(),
            y_semi_axis: T::one(),
        }
    }

    /// Fits an ellipse to the sampled surface `points` (`(f̃, m̃)`, from `d = 0` to
    /// `d = ∞`, pitch = the first point's `m̃`), inside every surface in `constraints`
    /// (each a sampled surface given the same way, normalised by its own pitch). `None`
    /// when the points do not determine an ellipse.
    ///
    /// The fit: for each ratio `q = B/A`, the ellipse `(1, q)` is scaled by the largest
    /// factor that keeps it inside every chord of every constraint; of these, the one
    /// whose largest force overhead over `points` (see [`Self::force_overhead`], 33
    /// directions) is least, found by a golden-section search over `ln q ∈ [−1, 1]` (40
    /// steps, no new surface evaluations). It starts from the least-squares ellipse's
    /// ratio and keeps it if nothing is better.
    pub fn fit_within(points: &[FlsPoint<T>], constraints: &[&[FlsPoint<T>]]) -> Option<Self> {
        let pitch = points.first()?.m;
        if !(pitch > T::zero()) {
            return None;
        }
        // The fit takes at most 129 points, evenly strided (the shrink and the overhead
        // use them all).
        let mut scaled = [FlsPoint::default(); 129];
        let stride = points.len().div_ceil(scaled.len()).max(1);
        let n = points.len().div_ceil(stride).min(scaled.len());
        for (s, p) in scaled.iter_mut().zip(points.iter().step_by(stride)) {
            *s = FlsPoint {
                d: p.d,
                f: p.f,
                m: p.m / pitch,
            };
        }
        let fit = EllipseFit::fit(scaled.get(..n)?)?;
        let shaped = |q: T| -> Option<(Self, T)> {
            let mut shrink = T::infinity();
            for surface in constraints {
                shrink = shrink.min(Self::room(T::one(), q, surface));
            }
            if !(shrink > T::zero() && shrink.is_finite()) {
                return None;
            }
            let e = Self {
                x_semi_axis: shrink,
                y_semi_axis: q * shrink,
            };
            let (max, _) = e.force_overhead(points, 33);
            Some((e, max))
        };
        let mut best = shaped(fit.m_semi_axis / fit.f_semi_axis)?;
        let (mut lo, mut hi) = (-T::one(), T::one());
        let ratio = T::of(0.618_033_988_749_894_9);
        let mut x1 = hi - ratio * (hi - lo);
        let mut x2 = lo + ratio * (hi - lo);
        let mut g1 = shaped(x1.libm_exp())?;
        let mut g2 = shaped(x2.libm_exp())?;
        for _ in 0..40 {
            if g1.1 < g2.1 {
                hi = x2;
                x2 = x1;
                g2 = g1;
                x1 = hi - ratio * (hi - lo);
                g1 = shaped(x1.libm_exp())?;
            } else {
                lo = x1;
                x1 = x2;
                g1 = g2;
                x2 = lo + ratio * (hi - lo);
                g2 = shaped(x2.libm_exp())?;
            }
        }
        for g in [g1, g2] {
            if g.1 < best.1 {
                best = g;
            }
        }
        Some(best.0)
    }

    /// The largest factor by which the ellipse `(a, b)` can be scaled and stay inside
    /// every chord of `surface` (normalised by its pitch): `min over chords of
    /// (distance of the chord's line from the origin) / (the ellipse's support there)`.
    fn room(a: T, b: T, surface: &[FlsPoint<T>]) -> T {
        let Some(pitch) = surface.first().map(|p| p.m) else {
            return T::infinity();
        };
        let mut room = T::infinity();
        for w in surface.windows(2) {
            let [p, q] = w else { continue };
            let (px, py) = (p.f, p.m / pitch);
            let (qx, qy) = (q.f, q.m / pitch);
            // The outward normal of the chord p→q (the curve runs clockwise from (0, 1) to
            // (1, 0)) and the chord line's distance from the origin along it.
            let (nx, ny) = (py - qy, qx - px);
            let dist = nx * px + ny * py;
            let support = ((a * nx) * (a * nx) + (b * ny) * (b * ny)).libm_sqrt();
            if dist > T::zero() && support > T::zero() {
                room = room.min(dist / support);
            }
        }
        room
    }

    /// Radius of the ellipse in the direction of `(x, y)`.
    pub fn radius(&self, x: T, y: T) -> T {
        let r = x.libm_hypot(y);
        if r == T::zero() {
            return T::zero();
        }
        let (c, s) = (x / r / self.x_semi_axis, y / r / self.y_semi_axis);
        (c * c + s * s).libm_sqrt().recip()
    }

    /// What the ellipse costs in force over the exact surface `points` (`(f̃, m̃)`),
    /// for loads in `directions` directions spread over the quadrant of `(x, y)` (evenly
    /// in `tan(θ/2)`, close to even in angle): the ratio of the force it asks to the force
    /// the exact surface asks, less one, as `(largest, mean)`, for a contact whose size does not change with the force
    /// (`γ = 0`; with `γ > 0` the force ratio is smaller). The exact radius is that of
    /// the chord polygon through the samples.
    pub fn force_overhead(&self, points: &[FlsPoint<T>], directions: usize) -> (T, T) {
        let Some(pitch) = points.first().map(|p| p.m) else {
            return (T::zero(), T::zero());
        };
        let (mut max, mut sum) = (T::zero(), T::zero());
        let n = directions.max(2);
        for i in 0..n {
            let u = T::of_usize(i) / T::of_usize(n - 1);
            let w = T::one() + u * u;
            let (x, y) = ((T::one() - u * u) / w, (u + u) / w);
            let exact = polygon_radius(points, pitch, x, y);
            let over = exact / self.radius(x, y) - T::one();
            max = max.max(over);
            sum = sum + over;
        }
        (max, sum / T::of_usize(n))
    }
}

/// Radius of the chord polygon through `points` (normalised by `pitch`) in the direction
/// `(x, y)`, `x, y ≥ 0`.
fn polygon_radius<T: Real>(points: &[FlsPoint<T>], pitch: T, x: T, y: T) -> T {
    for w in points.windows(2) {
        let [p, q] = w else { continue };
        let (px, py) = (p.f, p.m / pitch);
        let (qx, qy) = (q.f, q.m / pitch);
        // The ray t·(x, y) meets the chord where cross products change sign.
        let cp = px * y - py * x;
        let cq = qx * y - qy * x;
        if cp <= T::zero() && cq >= T::zero() {
            let (dx, dy) = (qx - px, qy - py);
            let den = x * dy - y * dx;
            if den != T::zero() {
                return (px * dy - py * dx) / den;
            }
        }
    }
    T::one()
}
