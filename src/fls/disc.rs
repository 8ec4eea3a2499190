//! The limit-surface integrals on the unit disc (lengths in units of `a`).
//!
//! **Symmetric profile.** The pressure depends on `r` only, so the angular integral over a
//! ring of radius `r` around the centre has a closed form in the complete elliptic integrals
//! `K(m)`, `E(m)` with `m = 4rd/(r+d)²` (the ring passes through the centre of rotation when
//! `r = d`, where `K` diverges logarithmically). Both ring kernels are evaluated from one
//! arithmetic-geometric mean in forms without cancellation:
//!
//! - `∫ (r cosθ − d)/R dθ = 4K·(2rσ − d)/(r+d)` (the force),
//! - `∫ (r² − d r cosθ)/R dθ = 4rK·(r − 2dσ)/(r+d)` (the moment),
//!
//! where `σ = (K − E)/(mK) − 1/2 = Σ_{n≥1} 2^(n−1) c_n²/m` is summed from the AGM's own
//! `c_n`. The radial integral is then 1-D, split at `r = d`.
//!
//! **Skewed profile.** The peak `O'` moves to `(Δx, Δy)` and the pressure is ray-scaled from
//! it, so the integral is done in polar coordinates about `O'`: outer angle split at the
//! direction of the centre of rotation and at the direction of the nearest edge point, inner
//! radius split at the ray's closest approach to the centre of rotation. Every
//! singularity then sits at an interval end.

use crate::pressure::{ray_to_circle, KProfile};
use crate::quadrature::{QuadPoint, TanhSinh};
use crate::real::Real;

/// AGM iterations cap: quadratic convergence needs at most about 6 plus
/// `log2(ln(1/b₀))` steps, so 40 covers every `b₀` above the f64 underflow threshold.
const AGM_MAX_STEPS: usize = 40;

/// Ring kernels `[force, moment]` for ring radius `r`, centre of rotation `d`, and
/// `|r − d|` passed separately (known accurately near the split).
#[inline]
pub(crate) fn ring_kernels<T: Real>(r: T, d: T, abs_r_minus_d: T) -> [T; 2] {
    let s = r + d;
    if s <= T::zero() {
        return [T::zero(), T::zero()];
    }
    let four = T::of(4.0);
    let b0 = abs_r_minus_d / s;
    if b0 <= T::zero() {
        // r = d: K is infinite but the kernels have finite limits, −4E(1) and 4dE(1).
        return [-four, four * d];
    }
    let m = four * r * d / (s * s);
    let mut a = T::one();
    let mut b = b0;
    let mut q = T::one(); // c_n²/m
    let mut pow2 = T::one(); // 2^(n−1) for the next term
    let mut sigma = T::zero();
    let sixteen = T::of(16.0);
    let half = T::of(0.5);
    let eps = T::epsilon();
    for _ in 0..AGM_MAX_STEPS {
        let a_next = (a + b) * half;
        let b_next = (a * b).libm_sqrt();
        q = q * q * m / (sixteen * a_next * a_next);
        sigma = sigma + pow2 * q;
        pow2 = pow2 + pow2;
        a = a_next;
        b = b_next;
        if a - b <= eps * a {
            break;
        }
    }
    let k = T::FRAC_PI_2() / a;
    let two = T::of(2.0);
    [
        four * k * (two * r * sigma - d) / s,
        four * r * k * (r - two * d * sigma) / s,
    ]
}

/// `(f̃, m̃)` for the symmetric disc profile at centre of rotation `d ≥ 0`.
pub(crate) fn symmetric_point<T: Real>(rule: &TanhSinh<T>, profile: &KProfile<T>, d: T) -> (T, T) {
    let one = T::one();
    let kern = |r: T, c: T, gap: T| {
        let g = profile.shape(r, c);
        let k = ring_kernels(r, d, gap);
        [g * r * k[0], g * r * k[1]]
    };
    let sums = if d > T::zero() && d < one {
        let one_minus_d = one - d;
        let inner = rule.integrate(T::zero(), d, |p: QuadPoint<T>| {
            kern(p.x, one_minus_d + p.to_hi, p.to_hi)
        });
        let outer = rule.integrate(d, one, |p: QuadPoint<T>| kern(p.x, p.to_hi, p.from_lo));
        [inner[0] + outer[0], inner[1] + outer[1]]
    } else {
        rule.integrate(T::zero(), one, |p: QuadPoint<T>| {
            kern(p.x, p.to_hi, (p.x - d).abs())
        })
    };
    let norm = T::of(2.0) * T::PI() * T::of(profile.disc_constant());
    ((sums[0] / norm).abs(), (sums[1] / norm).abs())
}

/// Where a piece of a segment from the peak lies against the segment's closest approach to
/// the centre of rotation, `s*`: it sets the offset `s − s*` handed to the kernel.
#[derive(Clone, Copy)]
enum Piece {
    /// `[0, s*]`, with `0 < s* < 1`.
    BeforeApproach,
    /// `[s*, 1]`, with `0 < s* < 1`.
    AfterApproach,
    /// `[0, 1]`, with `s* ≥ 1`.
    ApproachBeyond,
    /// `[0, 1]`, with `s* ≤ 0`.
    ApproachBefore,
}

/// `(f̃, m̃)` for the disc with the pressure peak at `(px, py)` (inside the unit disc) and the
/// centre of rotation at `(d, 0)`.
///
/// Coordinates: a boundary point `B(ψ) = (cos ψ, sin ψ)` and the fraction `s ∈ [0, 1]` of
/// the way from the peak to it, `P = (1 − s)·O' + s·B`. The pressure is `g(s)` by the
/// definition of the ray-scaled profile, and the area element `s (1 − O'·B) ds dψ` is smooth
/// in `ψ` however close the peak is to the edge. The outer integral runs over
/// `[ψ_c, ψ_c + 2π]`, where `B(ψ_c)` is the boundary point on the ray from the peak through
/// the centre of rotation; the inner one is split at the segment's closest approach to it.
pub(crate) fn skewed_point<T: Real>(
    rule: &TanhSinh<T>,
    profile: &KProfile<T>,
    peak: (T, T),
    d: T,
) -> (T, T) {
    let (px, py) = peak;
    if px == T::zero() && py == T::zero() {
        return symmetric_point(rule, profile, d);
    }
    let two_pi = T::of(2.0) * T::PI();
    // Vector from the peak to the centre of rotation.
    let c = (d - px, -py);
    let psi_c = rotation_centre_angle(peak, c);
    let mut sums = [T::zero(); 3];
    for (lo, hi) in period_pieces(psi_c, two_pi) {
        let part = rule.integrate(lo, hi, |p: QuadPoint<T>| {
            per_angle(rule, profile, peak, c, p.x)
        });
        for (s, v) in sums.iter_mut().zip(part) {
            *s = *s + v;
        }
    }
    let norm = two_pi * T::of(profile.disc_constant());
    let fx = sums[0] / norm;
    let fy = sums[1] / norm;
    let m = sums[2] / norm;
    (fx.libm_hypot(fy), m.abs())
}

/// `ψ_c` \[rad\]: the angle of the boundary point on the ray from the peak along `c` (the
/// vector from the peak to the centre of rotation); 0 if the peak is the centre.
fn rotation_centre_angle<T: Real>(peak: (T, T), c: (T, T)) -> T {
    let ((px, py), (cx, cy)) = (peak, c);
    let c_len = cx.libm_hypot(cy);
    if c_len > T::zero() {
        let (ex, ey) = (cx / c_len, cy / c_len);
        let rho = ray_to_circle(px, py, ex, ey);
        (py + rho * ey).libm_atan2(px + rho * ex)
    } else {
        T::zero()
    }
}

/// Pieces of the period `[ψ_c, ψ_c + 2π]`: split at ψ_c, at the boundary point nearest the
/// centre of rotation (ψ = 0, where the integrand turns sharply when the centre is near the
/// edge) and opposite ψ_c, so that each piece is at most half a turn.
fn period_pieces<T: Real>(psi_c: T, two_pi: T) -> [(T, T); 3] {
    let mut nearest = T::zero();
    while nearest <= psi_c {
        nearest = nearest + two_pi;
    }
    let opposite = psi_c + T::PI();
    let (b1, b2) = if nearest < opposite {
        (nearest, opposite)
    } else {
        (opposite, nearest)
    };
    [(psi_c, b1), (b1, b2), (b2, psi_c + two_pi)]
}

/// The inner integral along the segment from the peak to the boundary point `B(ψ)`:
/// `[f̃x, f̃y, m̃]` before normalisation. `c` is the vector from the peak to the centre of
/// rotation. The outer quadrature's integrand (hot at start-up), hence inlined.
#[inline]
fn per_angle<T: Real>(
    rule: &TanhSinh<T>,
    profile: &KProfile<T>,
    peak: (T, T),
    c: (T, T),
    psi: T,
) -> [T; 3] {
    let ((px, py), (cx, cy)) = (peak, c);
    let one = T::one();
    let (by, bx) = psi.libm_sin_cos();
    let (vx, vy) = (bx - px, by - py);
    let v2 = vx * vx + vy * vy;
    let jac_psi = one - (px * bx + py * by);
    if !(v2 > T::zero()) {
        return [T::zero(); 3];
    }
    // Closest approach of the segment's line to the centre of rotation, and the
    // perpendicular offset there: P − c = w + (s − s*)·V.
    let along = cx * vx + cy * vy;
    let s_star = along / v2;
    let (wx, wy) = (s_star * vx - cx, s_star * vy - cy);
    let kern = |s: T, comp: T, ds: T| -> [T; 3] {
        let g = profile.shape(s, comp);
        let (qx, qy) = (wx + ds * vx, wy + ds * vy);
        let r = (qx * qx + qy * qy).libm_sqrt();
        if r <= T::zero() {
            return [T::zero(); 3];
        }
        let (pxs, pys) = (px + s * vx, py + s * vy);
        let jac = g * s * jac_psi / r;
        [-jac * qy, jac * qx, jac * (pxs * qx + pys * qy)]
    };
    let mut sums = [T::zero(); 3];
    for (lo, hi, piece) in segment_pieces(s_star) {
        let part = rule.integrate(lo, hi, |p: QuadPoint<T>| match piece {
            Piece::BeforeApproach => kern(p.x, one - p.x, -p.to_hi),
            Piece::AfterApproach => kern(p.x, p.to_hi, p.from_lo),
            Piece::ApproachBeyond => kern(p.x, p.to_hi, -(p.to_hi + (s_star - one))),
            Piece::ApproachBefore => kern(p.x, p.to_hi, p.from_lo - s_star),
        });
        for (s, v) in sums.iter_mut().zip(part) {
            *s = *s + v;
        }
    }
    sums
}

/// The segment in two pieces, `[0, s*]` and `[s*, 1]`, when the closest approach `s*` is
/// inside it, else `[0, 1]` and an empty piece (which integrates to 0): one call site for
/// all of them, so the integrand is inlined once.
#[inline]
fn segment_pieces<T: Real>(s_star: T) -> [(T, T, Piece); 2] {
    let one = T::one();
    if s_star > T::zero() && s_star < one {
        [
            (T::zero(), s_star, Piece::BeforeApproach),
            (s_star, one, Piece::AfterApproach),
        ]
    } else {
        let piece = if s_star >= one {
            Piece::ApproachBeyond
        } else {
            Piece::ApproachBefore
        };
        [(T::zero(), one, piece), (one, one, piece)]
    }
}
