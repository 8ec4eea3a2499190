//! What the actuator does with the command: its lag and slew, identified online from the
//! commanded and the measured normal force, so that the lead ([`lead`](super::lead))
//! works through an actuator nobody described.
//!
//! The model is a first-order lag `τ` with a slew limit `r`: the force moves toward the
//! command at `(u − N)/τ`, never faster than `r`. Each good tick gives the command `u` of
//! the tick before and the measured force `N`; both pass through the same low-pass filter
//! (time constant [`FILTER_TAU_S`], so its delay cancels between them) into `ū` and `N̄`,
//! and the filtered rate `Ṅ = ΔN̄/dt`. Only a tick on which the command moves
//! (`|u̇| ≥` [`RATE_MIN_N_PER_S`], filtered; the command's rate, which the force sensor's
//! noise does not touch) and the force moves toward it (`Ṅ` with the sign of the gap
//! `e = ū − N̄`) says anything. Then:
//!
//! - **slew**: once the lag rests on [`LAG_SAMPLES_FOR_SLEW`] samples, a tick whose gap
//!   exceeds [`SLEW_GAP_N`] while `Ṅ` is under [`SLEW_RATE_SHARE`] of what the lag would
//!   give (`e/τ̂`), in a stretch of at least [`SLEW_RUN_TICKS`] such ticks, is
//!   slew-limited; its rate is a sample of `r`, and `r̂` follows them up fast and down
//!   slowly ([`SLEW_GAIN`] per sample up, an eighth of it down: the ticks that enter or
//!   leave a slewing stretch move slower than the slew). Without such a tick `r̂` stays at
//!   the configured `actuator_slew_n_per_s` (∞ when not given);
//! - **lag**: any other such tick is a sample of `e = τ·Ṅ`; `τ̂ = Σ e·Ṅ / Σ Ṅ²` over the
//!   samples, each new sample weighing the sums down by `1 − 1/`[`MEMORY_SAMPLES`],
//!   started from the configured `actuator_lag_s` with the weight of [`PRIOR_SAMPLES`]
//!   samples at [`PRIOR_RATE_N_PER_S`]. A lag of 0 says "not told", not "no lag": the
//!   sums then start from [`UNTOLD_LAG_S`] with the weight of [`UNTOLD_PRIOR_SAMPLES`]
//!   samples, so the first rise of the load, which comes before any sample (the command
//!   sits at `N_min` until the load needs more), is led as a typical soft-finger actuator
//!   would need, and the actuator's own samples outweigh the guess within a few ticks
//!   of moving. To describe an ideal actuator, give a lag under [`LAG_FLOOR_TICKS`]
//!   ticks (one tick, say): it is never led. A slew
//!   that binds before the lag is known makes `τ̂` the effective delay of closing the gap
//!   at that slew, which is what the lead needs.
//!
//! An actuator that follows the command within a tick (the measurement is then the last
//! command plus noise) gives `τ̂` of about one tick; below [`LAG_FLOOR_TICKS`] ticks the
//! lead takes the actuator as ideal, so such an actuator changes no command. Sensor noise
//! of 0.05 N on the normal force moves `Ṅ` by about 12 N/s after the filter, under the
//! rate floor. A bad, stale or missing measurement updates nothing.
//!
//! Accuracy (0.02 N of noise on every channel): from a prior of 0 or of twice the truth,
//! `τ̂` comes within 12 % of a 10, 30 or 60 ms lag by the end of two lifts, and `r̂`
//! within 4 % of a 100 N/s slew that binds after a light lift showed the lag
//! (`cargo test --release --test actuator_id -- --nocapture` prints the figures). Cost per
//! tick: two filters and a comparison; on a tick that is a sample, about ten more
//! operations and one division.

use crate::real::Real;

/// Time constant of the filter on the command and the measured force \[s\].
pub const FILTER_TAU_S: f64 = 0.004;
/// Least filtered rate of the command at which a tick is a sample of the actuator [N/s].
pub const RATE_MIN_N_PER_S: f64 = 30.0;
/// Least gap between the filtered command and force on a slew-limited tick \[N\].
pub const SLEW_GAP_N: f64 = 0.3;
/// Ticks in a row that must look slew-limited before they are taken as slew samples.
pub const SLEW_RUN_TICKS: u8 = 5;
/// A tick is slew-limited when its rate is under this share of what the lag would give.
pub const SLEW_RATE_SHARE: f64 = 0.6;
/// Weight of a new slew sample in the running mean of `r̂`.
pub const SLEW_GAIN: f64 = 0.2;
/// How many samples the lag's sums remember (each new sample weighs the old ones down by
/// `1 − 1/MEMORY_SAMPLES`).
pub const MEMORY_SAMPLES: f64 = 400.0;
/// The prior lag's weight, in samples.
pub const PRIOR_SAMPLES: f64 = 20.0;
/// The rate at which the prior's samples count [N/s].
pub const PRIOR_RATE_N_PER_S: f64 = 50.0;
/// Lag samples needed before a tick can be judged slew-limited (the judgement compares
/// the rate with the lag's).
pub const LAG_SAMPLES_FOR_SLEW: u16 = 50;
/// Identified lags below this many tick periods are an ideal actuator (no lead).
pub const LAG_FLOOR_TICKS: f64 = 2.5;

/// `1/x`, 0 for an infinite `x`.
fn inv(x: f64) -> f64 {
    if x.is_finite() {
        1.0 / x
    } else {
        0.0
    }
}

/// The weight of the prior lag in the lag's sums [(N/s)²]: [`PRIOR_SAMPLES`] samples at
/// [`PRIOR_RATE_N_PER_S`] for a configured lag; [`UNTOLD_PRIOR_SAMPLES`] for
/// `actuator_lag_s = 0`, which says "not told", not "no lag".
fn prior_weight(actuator_lag_s: f64) -> f64 {
    if actuator_lag_s > 0.0 {
        PRIOR_SAMPLES * PRIOR_RATE_N_PER_S * PRIOR_RATE_N_PER_S
    } else {
        UNTOLD_PRIOR_SAMPLES * PRIOR_RATE_N_PER_S * PRIOR_RATE_N_PER_S
    }
}

/// The lag assumed of an actuator nobody described (`actuator_lag_s = 0`) until its own
/// samples say otherwise \[s\]: what tendon, cable and geared-motor grippers take to follow
/// a step of force (tens of milliseconds), at the slow end, since the lead that guess
/// buys is also all the first rise gets for a slew limit nobody described either.
/// Without a guess the first lift through a slow actuator nobody described starts unled
/// from `N_min`: on the bench's `shake` family (untold 5–30 ms actuators slewing at
/// 100–500 N/s) that lift-off slip dropped 5 of 30 trials in ellipse mode at safety 1.3
/// on a held-out seed (101), 1 of 30 with a 20 ms guess (`bench --family shake --seeds
/// 101 --trials 30`). On held-out seeds 101–404, table mode, 40 ms instead of 20 ms
/// took the `shake` drops at safety 1.2, 1.25, 1.3 and 1.35 from 22, 16, 10 and 5 of
/// 120 to 8, 5, 4 and 3 (8 % more force there at 1.2, 1 % less from 1.35), and 60 ms did
/// no better. The cost through an ideal actuator is the lead on each rise of the load
/// that moves the command slower than the identifier's [`RATE_MIN_N_PER_S`]: 0.2 % more
/// force on the `lift-hold` family than with 20 ms.
pub const UNTOLD_LAG_S: f64 = 0.04;
/// The weight of [`UNTOLD_LAG_S`], in samples: a guess, outweighed by the actuator's
/// own first samples.
pub const UNTOLD_PRIOR_SAMPLES: f64 = 2.0;

/// The lag the identifier starts from: the configured one, or [`UNTOLD_LAG_S`] when not told.
fn prior_lag(actuator_lag_s: f64) -> f64 {
    if actuator_lag_s > 0.0 {
        actuator_lag_s
    } else {
        UNTOLD_LAG_S
    }
}

/// The identifier's constants and state.
#[derive(Debug, Clone)]
pub(crate) struct ActuatorId<T> {
    alpha: T,
    inv_dt: T,
    min_step: T,
    forget: T,
    prior_lag: T,
    prior_weight: T,
    prior_slew: T,
    floor: T,
    // State.
    started: bool,
    u_bar: T,
    n_bar: T,
    s_en: T,
    s_nn: T,
    slew: T,
    inv_slew: T,
    slewed: bool,
    lag_samples: u16,
    lag: T,
    lead_lag: T,
    limited_run: u8,
}

impl<T: Real> ActuatorId<T> {
    /// For a validated configuration's actuator lag and slew (the priors) and tick period.
    pub(crate) fn new(actuator_lag_s: f64, actuator_slew_n_per_s: f64, tick_period_s: f64) -> Self {
        let w = prior_weight(actuator_lag_s);
        let actuator_lag_s = prior_lag(actuator_lag_s);
        Self {
            alpha: T::of(tick_period_s / (FILTER_TAU_S + tick_period_s)),
            inv_dt: T::of(1.0 / tick_period_s),
            min_step: T::of(RATE_MIN_N_PER_S * tick_period_s),
            forget: T::of(1.0 - 1.0 / MEMORY_SAMPLES),
            prior_lag: T::of(actuator_lag_s),
            prior_weight: T::of(w),
            prior_slew: T::of(actuator_slew_n_per_s),
            floor: T::of(LAG_FLOOR_TICKS * tick_period_s),
            started: false,
            u_bar: T::zero(),
            n_bar: T::zero(),
            s_en: T::of(w * actuator_lag_s),
            s_nn: T::of(w),
            slew: T::of(actuator_slew_n_per_s),
            inv_slew: T::of(inv(actuator_slew_n_per_s)),
            slewed: false,
            lag_samples: 0,
            lag: T::of(actuator_lag_s),
            lead_lag: T::zero(),
            limited_run: 0,
        }
        .with_lead_lag()
    }

    /// Back to the priors.
    pub(crate) fn reset(&mut self) {
        let w = self.prior_weight;
        self.started = false;
        self.n_bar = T::zero();
        self.s_en = w * self.prior_lag;
        self.s_nn = w;
        self.slew = self.prior_slew;
        self.inv_slew = T::of(inv(self.prior_slew.to_f64()));
        self.slewed = false;
        self.lag_samples = 0;
        self.lag = self.prior_lag;
        self.lead_lag = self.floored(self.lag);
        self.limited_run = 0;
    }

    fn with_lead_lag(mut self) -> Self {
        self.lead_lag = self.floored(self.lag);
        self
    }

    /// The identified lag `τ̂` [s] (0 for an actuator faster than the floor).
    #[inline]
    pub(crate) fn lag_s(&self) -> T {
        self.lead_lag
    }

    /// `τ̂` as the lead takes it: 0 below the floor.
    fn floored(&self, lag: T) -> T {
        if lag >= self.floor && lag.is_finite() {
            lag
        } else {
            T::zero()
        }
    }

    /// The identified slew `r̂` [N/s] (the prior, ∞ when not given, until a slew-limited
    /// tick is seen).
    #[inline]
    pub(crate) fn slew_n_per_s(&self) -> T {
        self.slew
    }

    /// `1/r̂` [s/N] (0 for an actuator that is not slew-limited).
    #[inline]
    pub(crate) fn inv_slew(&self) -> T {
        self.inv_slew
    }

    /// Takes a good tick: `commanded_n` the command of the tick before, `measured_n` the
    /// normal force measured now (both finite: the caller checked the measurement).
    pub(crate) fn observe(&mut self, commanded_n: T, measured_n: T) {
        if !self.started {
            self.started = true;
            self.u_bar = commanded_n;
            self.n_bar = measured_n;
            return;
        }
        let u_bar = self.u_bar;
        let u_next = u_bar + (commanded_n - u_bar) * self.alpha;
        let n_bar = self.n_bar;
        let n_next = n_bar + (measured_n - n_bar) * self.alpha;
        self.u_bar = u_next;
        self.n_bar = n_next;
        // Selected on the command's rate, which the force sensor's noise does not touch
        // (selecting on the measured rate would favour ticks whose noise inflates it).
        if !((u_next - u_bar).abs() >= self.min_step) {
            return;
        }
        let rate = (n_next - n_bar) * self.inv_dt;
        let gap = u_next - n_next;
        if !(gap * rate > T::zero()) {
            return;
        }
        // Slew-limited: a large gap closed at under a share of the rate the lag would give.
        let limited = self.lag_samples >= LAG_SAMPLES_FOR_SLEW
            && gap.abs() > T::of(SLEW_GAP_N)
            && rate.abs() * self.lag < T::of(SLEW_RATE_SHARE) * gap.abs();
        self.limited_run = if limited {
            self.limited_run.saturating_add(1)
        } else {
            0
        };
        if limited && self.limited_run < SLEW_RUN_TICKS {
            // Not yet a slewing stretch: a command that jumps looks like one for a tick or
            // two before the force responds.
            return;
        }
        if limited {
            // Up fast, down slowly: the ticks that enter or leave a slewing stretch move
            // slower than the slew, and should not drag it down.
            let r = rate.abs();
            self.slew = if self.slewed && self.slew.is_finite() {
                let gain = if r > self.slew {
                    SLEW_GAIN
                } else {
                    SLEW_GAIN / 8.0
                };
                self.slew + (r - self.slew) * T::of(gain)
            } else {
                r
            };
            self.inv_slew = self.slew.recip();
            self.slewed = true;
            return;
        }
        // Each new sample weighs the older ones down by the forgetting factor.
        // Finite: the measurement passed the sensor-range check and the command is within
        // [N_min, N_max], so |gap| and |rate|·dt are bounded by the ranges, and the
        // forgetting bounds the sums.
        self.s_en = self.s_en * self.forget + gap * rate;
        self.s_nn = self.s_nn * self.forget + rate * rate;
        if self.lag_samples < LAG_SAMPLES_FOR_SLEW {
            self.lag_samples += 1;
        }
        self.lag = self.s_en / self.s_nn;
        self.lead_lag = self.floored(self.lag);
    }
}
