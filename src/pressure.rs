//! Contact pressure: the k-family of the paper (Eq. 1–3) on the rectangle and on the disc,
//! and its skewed, ray-scaled form (Eq. 6–9) as `docs/model.md` reads it.
//!
//! All profiles share the shape function `g(s) = (1 − s^k)^(1/k)` of the normalised
//! distance `s ∈ [0, 1]` from the pressure peak to the patch edge along a ray. `k = 2` is
//! Timoshenko–Goodier (Eq. 1) on the rectangle and Hertz on the disc; `k → ∞` (accepted as
//! `f64::INFINITY`) is uniform pressure.

mod gamma;

use crate::error::{check, ConfigError};
use crate::real::Real;
use gamma::gamma_1p;

/// The shape exponent `k ≥ 1` (real; `+∞` means uniform) and its normalising constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KProfile<T> {
    k: T,
    inv_k: T,
    kind: KKind,
    c_k: f64,
    b_k: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum KKind {
    One,
    Two,
    Uniform,
    General,
}

impl<T: Real> KProfile<T> {
    /// Validates `k ≥ 1` (or `+∞`) and computes `C_k` and `B_k` in f64.
    pub fn new(k: f64) -> Result<Self, ConfigError> {
        check("k", k, k >= 1.0, "k >= 1")?;
        let kind = if k == 1.0 {
            KKind::One
        } else if k == 2.0 {
            KKind::Two
        } else if k.is_infinite() {
            KKind::Uniform
        } else {
            KKind::General
        };
        Ok(Self {
            k: T::of(k),
            inv_k: T::of(1.0 / k),
            kind,
            c_k: rect_constant(k),
            b_k: disc_moment(k, 1.0),
        })
    }

    /// The exponent `k`.
    pub fn k(&self) -> T {
        self.k
    }

    /// `C_k = π k Γ(2/k) / Γ(1/k)²` (Eq. 3), evaluated as `(π/2) Γ(1+2/k) / Γ(1+1/k)²`,
    /// which stays accurate for any real `k ≥ 1` and tends to `π/2` as `k → ∞`.
    pub fn rect_constant(&self) -> f64 {
        self.c_k
    }

    /// `B_k = ∫₀¹ t (1 − t^k)^(1/k) dt = B(2/k, 1+1/k)/k`: the disc's normaliser.
    pub fn disc_constant(&self) -> f64 {
        self.b_k
    }

    /// The shape `g(s) = (1 − s^k)^(1/k)` given `s` and its complement `c = 1 − s`, both in
    /// `[0, 1]` (the complement is passed separately so that points near the edge keep full
    /// relative accuracy). Cost: a square root for `k = 2`, otherwise two logarithms and two
    /// exponentials. Returns a value in `[0, 1]` for any inputs in range.
    #[inline]
    pub fn shape(&self, s: T, c: T) -> T {
        let s = s.max(T::zero()).min(T::one());
        let c = c.max(T::zero()).min(T::one());
        match self.kind {
            KKind::One => c,
            KKind::Two => (c * (T::one() + s)).libm_sqrt(),
            KKind::Uniform => {
                if c > T::zero() {
                    T::one()
                } else {
                    T::zero()
                }
            }
            KKind::General => {
                if c == T::zero() {
                    return T::zero();
                }
                let half = T::of(0.5);
                // 1 − s^k, from whichever of s and c is known more accurately.
                let omega = if s <= half {
                    T::one() - (self.k * s.libm_ln()).libm_exp()
                } else {
                    -(self.k * (-c).libm_ln_1p()).libm_exp_m1()
                };
                (omega.libm_ln() * self.inv_k).libm_exp()
            }
        }
    }
}

/// `C_k` (Eq. 3) in the overflow-free form `(π/2) Γ(1+2/k) / Γ(1+1/k)²`.
pub fn rect_constant(k: f64) -> f64 {
    if k.is_infinite() {
        return core::f64::consts::FRAC_PI_2;
    }
    let x = 1.0 / k;
    let g1 = gamma_1p(x);
    core::f64::consts::FRAC_PI_2 * gamma_1p(2.0 * x) / (g1 * g1)
}

/// `∫₀¹ t^j (1 − t^k)^(1/k) dt = B((j+1)/k, 1+1/k)/k` for the disc: `j = 1` is `B_k`, `j = 2`
/// gives the pitch's numerator. Evaluated in the form
/// `Γ(1+(j+1)/k) Γ(1+1/k) / ((j+1) Γ(1+(j+2)/k))` (arguments at most `1 + (j+2)`, so no
/// overflow for the `j ≤ 2` the crate uses), finite for every `k ≥ 1` and `k = ∞`; within
/// about 1e-15 relative.
pub fn disc_moment(k: f64, j: f64) -> f64 {
    if k.is_infinite() {
        return 1.0 / (j + 1.0);
    }
    let x = 1.0 / k;
    gamma_1p((j + 1.0) * x) * gamma_1p(x) / ((j + 1.0) * gamma_1p((j + 2.0) * x))
}

/// Symmetric pressure on the rectangle `[-l, l] × [-a, a]` (Eq. 2), in Pa.
///
/// `p(y) = C_k N/(2π a l) · g(|y|/a)`; zero outside the patch.
pub fn rect_symmetric_pa(profile: &KProfile<f64>, n: f64, a: f64, l: f64, x: f64, y: f64) -> f64 {
    rect_skewed_pa(profile, n, a, l, 0.0, x, y)
}

/// Skewed, ray-scaled pressure on the rectangle (Eq. 6–9), in Pa: the peak sits at
/// `y = Δy` (`|Δy| < a`), and `p(y) = C_k N/(2π a l) · g(|y − Δy| / ρ)` with
/// `ρ = a − Δy` above the peak and `a + Δy` below. Integrates to `N` for every `Δy`.
pub fn rect_skewed_pa(
    profile: &KProfile<f64>,
    n: f64,
    a: f64,
    l: f64,
    delta_y: f64,
    x: f64,
    y: f64,
) -> f64 {
    if x.abs() > l || y.abs() > a {
        return 0.0;
    }
    let (dist_peak, dist_edge) = if y >= delta_y {
        (y - delta_y, a - y)
    } else {
        (delta_y - y, y + a)
    };
    let rho = dist_peak + dist_edge;
    if rho <= 0.0 {
        return 0.0;
    }
    let g = profile.shape(dist_peak / rho, dist_edge / rho);
    profile.rect_constant() * n / (2.0 * core::f64::consts::PI * a * l) * g
}

/// Skewed, ray-scaled pressure on the disc of radius `a`, in Pa: the peak sits at
/// `(Δx, Δy)` inside the disc, each point is measured from the peak along the ray through it
/// and scaled by `ρ`, the distance from the peak to the circle along that ray:
/// `p = N/(2π a² B_k) · g(|r − r'| / ρ)`. With the peak at the centre this is the symmetric
/// disc profile. Integrates to `N` for every peak position.
pub fn disc_pa(profile: &KProfile<f64>, n: f64, a: f64, peak: (f64, f64), x: f64, y: f64) -> f64 {
    if x * x + y * y > a * a {
        return 0.0;
    }
    let (dx, dy) = (x - peak.0, y - peak.1);
    let dist = libm::hypot(dx, dy);
    let amplitude = n / (2.0 * core::f64::consts::PI * a * a * profile.disc_constant());
    if dist == 0.0 {
        return amplitude;
    }
    let rho = ray_to_circle(peak.0 / a, peak.1 / a, dx / dist, dy / dist) * a;
    if rho <= 0.0 {
        return 0.0;
    }
    let s = (dist / rho).min(1.0);
    amplitude * profile.shape(s, 1.0 - s)
}

/// Distance from the point `(px, py)` inside the unit circle to the circle along the unit
/// direction `(ex, ey)`, evaluated without cancellation.
#[inline]
pub(crate) fn ray_to_circle<T: Real>(px: T, py: T, ex: T, ey: T) -> T {
    let b = px * ex + py * ey;
    let r2 = px * px + py * py;
    let inside = ((T::one() - r2.libm_sqrt()) * (T::one() + r2.libm_sqrt())).max(T::zero());
    let root = (b * b + inside).libm_sqrt();
    if b > T::zero() {
        inside / (b + root)
    } else {
        root - b
    }
}
