//! Contact size under load: the power law `a = c · N^γ` (the paper's "Models of the soft
//! contact"; Xydas & Kao 1999).
//!
//! `γ = n/(n+1) ∈ [0, 1/2]`: `γ = 1/2` is the linear-elastic cylinder of Timoshenko and
//! Goodier, `γ = 1/3` the Hertzian sphere, `γ = 0` a patch of fixed size.

use crate::error::{check, ConfigError};
use crate::real::Real;

/// The power-law contact size `a = c · N^γ`, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactSize<T> {
    c_m_per_n_gamma: T,
    gamma: T,
}

impl<T: Real> ContactSize<T> {
    /// Validates `c > 0` (metres per newton^γ) and `γ ∈ [0, 1/2]`.
    pub fn new(c_m_per_n_gamma: f64, gamma: f64) -> Result<Self, ConfigError> {
        check(
            "c",
            c_m_per_n_gamma,
            c_m_per_n_gamma > 0.0 && c_m_per_n_gamma.is_finite(),
            "c > 0",
        )?;
        check(
            "gamma",
            gamma,
            (0.0..=0.5).contains(&gamma),
            "0 <= gamma <= 1/2",
        )?;
        Ok(Self {
            c_m_per_n_gamma: T::of(c_m_per_n_gamma),
            gamma: T::of(gamma),
        })
    }

    /// The coefficient `c` in m/N^γ.
    pub fn c(&self) -> T {
        self.c_m_per_n_gamma
    }

    /// The exponent `γ`.
    pub fn gamma(&self) -> T {
        self.gamma
    }

    /// Contact half-width `a` \[m\] at normal force `normal_force_n` \[N\].
    ///
    /// Total: a negative or NaN force counts as no force (`a = 0` for `γ > 0`, `a = c` for
    /// `γ = 0`), `+∞` gives `+∞` for `γ > 0`. Cost: one `powf`.
    pub fn half_width_m(&self, normal_force_n: T) -> T {
        let n = normal_force_n.max(T::zero());
        if self.gamma == T::zero() {
            return self.c_m_per_n_gamma;
        }
        self.c_m_per_n_gamma * n.libm_powf(self.gamma)
    }

    /// The normal force \[N\] at which the half-width reaches `half_width_m` (the inverse
    /// law); `None` for `γ = 0`, where the size does not depend on the force.
    pub fn normal_force_n(&self, half_width_m: T) -> Option<T> {
        if self.gamma == T::zero() {
            return None;
        }
        let ratio = (half_width_m / self.c_m_per_n_gamma).max(T::zero());
        Some(ratio.libm_powf(T::one() / self.gamma))
    }
}
