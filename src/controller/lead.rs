//! Commanding ahead of the load: the grip force a lagging actuator must be asked for now
//! so that it has arrived when the load needs it.
//!
//! People lead: their grip force rises tens of milliseconds before the load force does.
//! A controller that asks for the force the load needs *now* is late by the actuator's
//! lag, and a rising load (a lift, a shake) then eats the safety margin. With
//! `actuator_lag_s = τ > 0` the controller estimates how fast its own requirement
//! `N_req(s)` is rising and asks for it one lead horizon `h` ahead:
//!
//! ```text
//! N_target = N_req + max(0, Ṅ_req − Ṅ₀)·h,   h = min(τ / (1 − Ṅ_req/r), HORIZON_MAX_LAGS·τ)
//! ```
//!
//! where `r` is the actuator's slew rate (`actuator_slew_n_per_s`, ∞ when not limited).
//! A first-order lag tracks a ramp `Ṅ` with the delay `τ`, so `h = τ` makes up for it; an
//! actuator that can rise only at `r` needs a further `h·Ṅ/r` to climb the `h·Ṅ` it must
//! add, which gives the horizon above (and its cap, [`HORIZON_MAX_LAGS`]·τ, when `Ṅ`
//! approaches `r`). The target is never below the present `N_req`: a falling load gets
//! no lead (the lag then holds the force up, on the safe side).
//!
//! `Ṅ_req` comes from two first-order low-pass stages with the time constant
//! [`FILTER_TAU_S`]: one on `N_req`, one on its difference quotient; rates below the dead
//! band `Ṅ₀` = [`RATE_DEADBAND_N_PER_S`] are taken as noise. Sensor noise of 0.02 N on each
//! force component (the simulator's `sensor_noise` default) then moves the command by
//! under a hundredth of a newton on average (`tests/robust_grip.rs` measures it), while a
//! lift or a shake (tens to hundreds of N/s) gets its full lead. The filters delay the
//! estimate by about `2·FILTER_TAU_S`; loads that change much faster than that are
//! covered by the safety factor and, with a slip sensor, by the slip response.
//!
//! With `actuator_lag_s = 0` none of this runs: the target is `N_req`, bit for bit.
//! Cost per tick: about ten multiplications and one division.

use crate::real::Real;

/// Time constant of each of the two rate filters [s].
pub const FILTER_TAU_S: f64 = 0.006;
/// Rates of `N_req` up to this are taken as sensor noise and get no lead [N/s].
pub const RATE_DEADBAND_N_PER_S: f64 = 2.0;
/// The longest lead horizon, in actuator lags.
pub const HORIZON_MAX_LAGS: f64 = 4.0;

/// The lead filter's constants and state.
#[derive(Debug, Clone)]
pub(crate) struct Lead<T> {
    enabled: bool,
    lag_s: T,
    inv_slew: T,
    max_horizon_s: T,
    alpha: T,
    inv_dt: T,
    deadband: T,
    // State.
    level: Option<T>,
    rate: T,
}

impl<T: Real> Lead<T> {
    /// For a validated configuration's actuator lag, actuator slew and tick period.
    pub(crate) fn new(actuator_lag_s: f64, actuator_slew_n_per_s: f64, tick_period_s: f64) -> Self {
        let inv_slew = if actuator_slew_n_per_s.is_finite() {
            1.0 / actuator_slew_n_per_s
        } else {
            0.0
        };
        Self {
            enabled: actuator_lag_s > 0.0,
            lag_s: T::of(actuator_lag_s),
            inv_slew: T::of(inv_slew),
            max_horizon_s: T::of(actuator_lag_s * HORIZON_MAX_LAGS),
            alpha: T::of(tick_period_s / (FILTER_TAU_S + tick_period_s)),
            inv_dt: T::of(1.0 / tick_period_s),
            deadband: T::of(RATE_DEADBAND_N_PER_S),
            level: None,
            rate: T::zero(),
        }
    }

    /// Forgets the load's history.
    pub(crate) fn reset(&mut self) {
        self.level = None;
        self.rate = T::zero();
    }

    /// Takes this tick's (finite, non-negative) requirement `required_n` and returns the
    /// target: `required_n` plus the lead, never less than `required_n`.
    #[inline]
    pub(crate) fn target(&mut self, required_n: T) -> T {
        if !self.enabled {
            return required_n;
        }
        let Some(level) = self.level else {
            self.level = Some(required_n);
            return required_n;
        };
        let next = level + (required_n - level) * self.alpha;
        let raw = (next - level) * self.inv_dt;
        self.rate = self.rate + (raw - self.rate) * self.alpha;
        self.level = Some(next);
        let rising = self.rate - self.deadband;
        if !(rising > T::zero()) {
            return required_n;
        }
        let climb = T::one() - self.rate * self.inv_slew;
        let horizon = if climb > T::zero() {
            (self.lag_s / climb).min(self.max_horizon_s)
        } else {
            self.max_horizon_s
        };
        let lead = rising * horizon;
        if lead.is_finite() {
            required_n + lead
        } else {
            required_n
        }
    }
}
