//! Cattaneo–Mindlin partial slip before gross slip (the paper's Eq. 4 and 5; Cattaneo
//! 1938, Mindlin 1949, Johnson 1985).
//!
//! Both formulas take the load ratio `T/(μN)`. They are total functions: the ratio is taken
//! by magnitude, a ratio at or above 1 (or NaN) means gross slip (stick radius 0, the
//! deflection at its limit), so a hostile input can only ever read as "slipping".

use crate::error::{check, ConfigError};
use crate::real::Real;

/// Clamps a load ratio `T/(μN)` into `[0, 1]`, reading NaN as 1 (gross slip).
fn clamp_ratio<T: Real>(load_ratio: T) -> T {
    if load_ratio.is_nan() {
        return T::one();
    }
    load_ratio.abs().min(T::one())
}

/// Radius `â` of the stick zone (Eq. 4): `â = a (1 − T/(μN))^(1/3)`.
///
/// `a` in any length unit; the result is in the same unit. Accurate to a few ulp, also for
/// ratios within 1e-15 of 1 (the cube root is taken of `1 − ratio`, computed exactly).
pub fn stick_radius<T: Real>(half_width: T, load_ratio: T) -> T {
    let r = clamp_ratio(load_ratio);
    half_width * (T::one() - r).libm_cbrt()
}

/// Elastic properties of the fingertip for the deflection formula.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elasticity<T> {
    /// Poisson's ratio `ν`.
    pub poisson: T,
    /// Shear modulus `G = E/(2 + 2ν)` \[Pa\].
    pub shear_modulus_pa: T,
}

impl<T: Real> Elasticity<T> {
    /// Validates Young's modulus `E > 0` \[Pa\] and Poisson's ratio `ν ∈ [0, 1/2]`.
    pub fn new(youngs_modulus_pa: f64, poisson: f64) -> Result<Self, ConfigError> {
        check(
            "E",
            youngs_modulus_pa,
            youngs_modulus_pa > 0.0 && youngs_modulus_pa.is_finite(),
            "E > 0",
        )?;
        check(
            "nu",
            poisson,
            (0.0..=0.5).contains(&poisson),
            "0 <= nu <= 0.5",
        )?;
        Ok(Self {
            poisson: T::of(poisson),
            shear_modulus_pa: T::of(youngs_modulus_pa / (2.0 + 2.0 * poisson)),
        })
    }
}

/// Tangential deflection `δ` \[m\] before gross slip (Eq. 5):
/// `δ = 3μN/(16a) · (2−ν)/G · [1 − (1 − T/(μN))^(2/3)]`.
///
/// `friction_force_n` is `μN` \[N\], `half_width_m` is `a` \[m\]. The bracket is evaluated as
/// `−expm1(⅔·ln1p(−ratio))`, so it keeps full relative accuracy for tiny ratios. At and above
/// a ratio of 1 the deflection stays at its gross-slip limit `3μN(2−ν)/(16aG)`.
pub fn deflection_m<T: Real>(
    elasticity: &Elasticity<T>,
    friction_force_n: T,
    half_width_m: T,
    load_ratio: T,
) -> T {
    let r = clamp_ratio(load_ratio);
    let bracket = if r == T::one() {
        T::one()
    } else {
        -((T::of(2.0 / 3.0)) * (-r).libm_ln_1p()).libm_exp_m1()
    };
    let scale = T::of(3.0) * friction_force_n / (T::of(16.0) * half_width_m)
        * (T::of(2.0) - elasticity.poisson)
        / elasticity.shear_modulus_pa;
    scale * bracket
}
