//! The limit-surface integrals on the rectangle `[-λ, λ] × [-1, 1]` (lengths in units of `a`).
//!
//! The pressure depends on `y` only, so the `x` integral of every Coulomb-traction component
//! has a closed form, and each limit-surface point is a 1-D integral over `y` of the pressure
//! times three row kernels. With the centre of rotation at `(d, 0)`, `u₁ = −λ − d`,
//! `u₂ = λ − d`, `R_i = sqrt(u_i² + y²)`, `S = R₁ + R₂`:
//!
//! - `∫ (x−d)/R dx = R₂ − R₁ = −4λd/S` (the force along `y`),
//! - `∫ −y/R dx = −y·D`, `D = asinh(u₂/|y|) − asinh(u₁/|y|)` (the force along `x`),
//! - `∫ (x(x−d) + y²)/R dx = λ(S+2d)(S−2d)/(2S) + y²D/2` (the moment about the centre),
//!
//! each in a form without cancellation for every `d ∈ [0, ∞)`, including `d` on the patch
//! edge (`u₂ = 0`) and `d ≫ λ`, where the textbook antiderivatives lose everything to
//! cancellation. The row kernels are singular only at `y = 0` (`y ln|y|`), so the `y`
//! integral is split there, at the pressure peak and at the patch edges.

use crate::pressure::KProfile;
use crate::quadrature::{QuadPoint, TanhSinh};
use crate::real::{Real, SqrtFn};

/// The three row kernels `[y·D, 1/S, M]` at height `y` for half-length `λ` and centre of
/// rotation `d ≥ 0`, with `sqrt` for the two row lengths.
#[inline]
pub(crate) fn row_kernels<T: Real>(lambda: T, d: T, y: T, sqrt: SqrtFn<T>) -> [T; 3] {
    let ay = y.abs();
    let y2 = y * y;
    let au1 = lambda + d;
    let u2 = lambda - d;
    let r1 = sqrt.sqrt(au1 * au1 + y2);
    let r2 = sqrt.sqrt(u2 * u2 + y2);
    let s = r1 + r2;
    let (y_d, y2_d) = if y2 == T::zero() {
        (T::zero(), T::zero())
    } else {
        let big_d = if u2 >= T::zero() {
            ((u2 + r2) / ay).libm_ln() + ((au1 + r1) / ay).libm_ln()
        } else {
            let four = T::of(4.0);
            let num = T::of(2.0) * lambda + four * lambda * d / s;
            (num / (r2 - u2)).libm_ln_1p()
        };
        (y * big_d, y2 * big_d)
    };
    let s_minus_2d = y2 / (r1 + au1)
        + if u2 >= T::zero() {
            r2 + u2
        } else {
            y2 / (r2 - u2)
        };
    let two = T::of(2.0);
    let m = lambda * (s + two * d) * s_minus_2d / (two * s) + y2_d / two;
    [y_d, s.recip(), m]
}

/// The normalised point `(f̃, m̃)` on the rectangle for centre of rotation `d ≥ 0` and the
/// pressure peak at `y = δ ∈ [0, 1)` (the skew; 0 for the symmetric profile).
///
/// `cache`, when given, holds `g(y)` at the rule's nodes on `[0, 1]` for the symmetric
/// profile, saving the shape evaluations; `sqrt` is the kernels' square root.
pub(crate) fn point<T: Real>(
    rule: &TanhSinh<T>,
    profile: &KProfile<T>,
    lambda: T,
    delta: T,
    d: T,
    cache: Option<&[T]>,
    sqrt: SqrtFn<T>,
) -> (T, T) {
    let c_k = T::of(profile.rect_constant());
    let pi = T::PI();
    let one = T::one();
    let sums = if delta <= T::zero() {
        // Symmetric: even integrands, the x-force vanishes; integrate [0, 1] twice.
        let mut acc = [T::zero(); 3];
        let mut cached = cache.map(|c| c.iter());
        for (pt, w) in rule.points(T::zero(), one) {
            let g = match cached.as_mut().and_then(|it| it.next()) {
                Some(&g) => g,
                None => profile.shape(pt.from_lo, pt.to_hi),
            };
            let k = row_kernels(lambda, d, pt.x, sqrt);
            let wg = w * g;
            acc[1] = acc[1] + wg * k[1];
            acc[2] = acc[2] + wg * k[2];
        }
        let two = T::of(2.0);
        [T::zero(), two * acc[1], two * acc[2]]
    } else {
        let below = one + delta;
        let above = one - delta;
        let kern = |g: T, y: T| {
            let k = row_kernels(lambda, d, y, sqrt);
            [g * k[0], g * k[1], g * k[2]]
        };
        // [-1, 0]: below the peak, distance to the edge is from_lo.
        let a = rule.integrate(-one, T::zero(), |p: QuadPoint<T>| {
            let g = profile.shape((delta - p.x) / below, p.from_lo / below);
            kern(g, p.x)
        });
        // [0, δ]: below the peak, distance to the peak is to_hi.
        let b = rule.integrate(T::zero(), delta, |p: QuadPoint<T>| {
            let g = profile.shape(p.to_hi / below, (one + p.x) / below);
            kern(g, p.x)
        });
        // [δ, 1]: above the peak.
        let c = rule.integrate(delta, one, |p: QuadPoint<T>| {
            let g = profile.shape(p.from_lo / above, p.to_hi / above);
            kern(g, p.x)
        });
        [a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]]
    };
    let two_pi_lambda = T::of(2.0) * pi * lambda;
    let f_x = c_k / two_pi_lambda * sums[0];
    let f_y = T::of(2.0) * c_k * d / pi * sums[1];
    let m = c_k / two_pi_lambda * sums[2];
    (f_x.libm_hypot(f_y), m.abs())
}

/// `g(y)` at the rule's nodes on `[0, 1]`, in the order `point` visits them.
pub(crate) fn shape_cache<T: Real>(rule: &TanhSinh<T>, profile: &KProfile<T>, out: &mut [T]) {
    for (slot, (pt, _)) in out.iter_mut().zip(rule.points(T::zero(), T::one())) {
        *slot = profile.shape(pt.from_lo, pt.to_hi);
    }
}
