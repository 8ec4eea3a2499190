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
//! `τ` and `r` are what the controller has identified of its actuator
//! ([`actuator`](super::actuator)), starting from `actuator_lag_s` and
//! `actuator_slew_n_per_s` as priors: an actuator nobody described is led as a 20 ms
//! lag until the first rise of the load has shown its own. While the identified lag is 0
//! (an ideal actuator: one told, or one whose samples show it follows within the
//! identifier's floor) the target is `N_req`, bit for bit.
//!
//! **Oscillating loads.** For a load that swings up and down faster than the command may
//! fall (`fall_rate_n_per_s`), leading every rise would ratchet the command up to the
//! swing's peak plus a lead on top of it: a sinusoid through a lag `τ` asks for an
//! amplitude `sqrt(1 + (ωτ)²)` times its own, 2.7 × at 10 Hz through 40 ms. Holding it
//! only needs the actuator at the peak, which the slow fall keeps it near anyway. So once
//! the requirement has turned down (a local peak) within the last [`SWING_WINDOW_S`], a
//! target below that peak (the highest requirement of the rise that ended there) is
//! capped at it: the lead brings the command up to the last peak early, never above it.
//! A requirement past the peak is new territory (a lift, a swing that grows) and gets the
//! whole lead.
//!
//! Cost per tick: about fifteen multiplications and one division.

use crate::real::Real;

/// Time constant of each of the two rate filters [s].
pub const FILTER_TAU_S: f64 = 0.006;
/// Rates of `N_req` up to this are taken as sensor noise and get no lead [N/s].
pub const RATE_DEADBAND_N_PER_S: f64 = 2.0;
/// The longest lead horizon, in actuator lags.
pub const HORIZON_MAX_LAGS: f64 = 4.0;
/// How long after a peak of the requirement its lead stays capped at the window's peak
/// [s] (covers a period of shakes of 2 Hz and faster).
pub const SWING_WINDOW_S: f64 = 0.5;

/// The lead filter's constants and state.
#[derive(Debug, Clone)]
pub(crate) struct Lead<T> {
    alpha: T,
    alpha_per_s: T,
    deadband: T,
    window_ticks: u32,
    // State.
    started: bool,
    level: T,
    rate: T,
    since_peak: u32,
    peak: T,
    rise_max: T,
}

impl<T: Real> Lead<T> {
    /// For a validated configuration's tick period.
    pub(crate) fn new(tick_period_s: f64) -> Self {
        let w = libm::ceil(SWING_WINDOW_S / tick_period_s).clamp(1.0, f64::from(u32::MAX / 2));
        Self {
            alpha: T::of(tick_period_s / (FILTER_TAU_S + tick_period_s)),
            alpha_per_s: T::of(1.0 / (FILTER_TAU_S + tick_period_s)),
            deadband: T::of(RATE_DEADBAND_N_PER_S),
            window_ticks: w as u32,
            started: false,
            level: T::zero(),
            rate: T::zero(),
            since_peak: u32::MAX,
            peak: T::zero(),
            rise_max: T::zero(),
        }
    }

    /// Forgets the load's history.
    pub(crate) fn reset(&mut self) {
        self.started = false;
        self.rate = T::zero();
        self.since_peak = u32::MAX;
        self.peak = T::zero();
        self.rise_max = T::zero();
    }

    /// Takes this tick's (finite, non-negative) requirement `required_n` and the
    /// identified actuator (`lag_s` ≥ 0, 0 for none; `inv_slew` = 1/slew ≥ 0, 0 when not
    /// limited) and returns the target: `required_n` plus the lead, never less than
    /// `required_n`. With no lag it only keeps the rate filters warm.
    #[inline]
    pub(crate) fn target(&mut self, required_n: T, lag_s: T, inv_slew: T) -> T {
        if !self.started {
            self.started = true;
            self.level = required_n;
            return required_n;
        }
        let level = self.level;
        let step = required_n - level;
        let next = level + step * self.alpha;
        let raw = step * self.alpha_per_s;
        let before = self.rate;
        self.rate = self.rate + (raw - self.rate) * self.alpha;
        self.level = next;
        if !(lag_s > T::zero()) {
            return required_n;
        }
        // A local peak of the requirement: its rate turned from rising to falling. The
        // peak is the highest requirement of the rise that ended there.
        if required_n > self.rise_max {
            self.rise_max = required_n;
        }
        if before > self.deadband && !(self.rate > self.deadband) {
            self.since_peak = 0;
            self.peak = self.rise_max;
            self.rise_max = required_n;
        } else {
            self.since_peak = self.since_peak.saturating_add(1);
        }
        let rising = self.rate - self.deadband;
        if !(rising > T::zero()) {
            return required_n;
        }
        let horizon = if inv_slew > T::zero() {
            let max_horizon = lag_s * T::of(HORIZON_MAX_LAGS);
            let climb = T::one() - self.rate * inv_slew;
            let h = lag_s / climb;
            if climb > T::zero() && h < max_horizon {
                h
            } else {
                max_horizon
            }
        } else {
            lag_s
        };
        // Finite: the filters' state and the identified lag are.
        let ahead = required_n + rising * horizon;
        // Below the last peak, the lead stops at it; past it the load is in new territory
        // (a lift, or a swing that grows) and gets the whole lead.
        // (Comparisons, not `min`: on the Cortex-M4F that is a call.)
        if self.since_peak < self.window_ticks && required_n < self.peak && ahead > self.peak {
            self.peak
        } else {
            ahead
        }
    }
}
