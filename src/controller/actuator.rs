//! What the actuator does with the command: its lag `τ` and slew `r`, identified online
//! from the commanded and the measured normal force, so that the lead
//! ([`lead`](super::lead)) works through an actuator nobody described.
//!
//! Model: a first-order lag with a slew limit; the force moves toward the command `u` at
//! `(u − N)/τ`, never faster than `r`. The command of the tick before and the measured
//! force pass through the same low-pass ([`FILTER_TAU_S`], so its delay cancels) into `ū`
//! and `N̄`; `Ṅ = ΔN̄/dt` and the gap `e = ū − N̄`. A tick is a sample only when the
//! filtered command moves at [`RATE_MIN_N_PER_S`] or more (the command's rate, which
//! sensor noise does not touch) and `Ṅ` has the sign of `e`. Then:
//!
//! - **slew**: once the lag rests on [`LAG_SAMPLES_FOR_SLEW`] samples, a run of at least
//!   [`SLEW_RUN_TICKS`] ticks with `|e|` > [`SLEW_GAP_N`] and `|Ṅ|` under
//!   [`SLEW_RATE_SHARE`] of `|e|/τ̂` is slew-limited; each such tick's rate is a sample of
//!   `r`, which `r̂` follows up by [`SLEW_GAIN`] and down by an eighth of it. Until then
//!   `r̂` is the configured `actuator_slew_n_per_s` (∞ when not given).
//! - **lag**: any other sample gives `e = τ·Ṅ`; `τ̂ = Σ e·Ṅ / Σ Ṅ²`, each new sample
//!   weighing the sums down by `1 − 1/`[`MEMORY_SAMPLES`], started from the configured
//!   `actuator_lag_s` with the weight of [`PRIOR_SAMPLES`] samples at
//!   [`PRIOR_RATE_N_PER_S`]. A lag of 0 says "not told": the sums start from
//!   `untold_lag_s` weighing [`UNTOLD_PRIOR_SAMPLES`] samples, so the load's first rise
//!   is led before any sample.
//! - `τ̂` below [`LAG_FLOOR_TICKS`] ticks is an ideal actuator: the lead gets 0 and changes
//!   no command. To describe an ideal actuator, give a lag of one tick.
//!
//! A bad, stale or missing measurement updates nothing. What `tests/actuator_id.rs`
//! asserts, with 0.02 N of noise on every channel: from a prior of 0 or twice the truth,
//! `τ̂` within 30 % of a 10, 30 or 60 ms lag, both 0.2 s into the first lift and after two
//! lifts (`the_lag_is_found_from_a_wrong_prior`); `r̂` within 15 % of a 100 N/s slew that
//! binds after a light lift, with `τ̂` within 50 % (`a_slew_that_binds_is_found`); an
//! untold 25 ms lag within 25 % (`an_untold_actuator_is_led_through_a_lift_and_a_shake`);
//! an ideal actuator changes no command (`an_ideal_actuator_changes_no_command`).
//! `cargo test --release --test actuator_id -- --nocapture` prints the figures.
//!
//! Cost per tick: two filters and a comparison; on a sample, about ten more operations and
//! one division.

use crate::controller::config::ControllerConfig;
use crate::real::Real;

/// Time constant of the filter on the command and the measured force \[s\]
/// (`tests/actuator_id.rs`).
pub const FILTER_TAU_S: f64 = 0.004;
/// Least filtered rate of the command at which a tick is a sample \[N/s\]
/// (`tests/actuator_id.rs`).
pub const RATE_MIN_N_PER_S: f64 = 30.0;
/// Least gap between the filtered command and force on a slew-limited tick \[N\]
/// (`tests/actuator_id.rs::a_slew_that_binds_is_found`).
pub const SLEW_GAP_N: f64 = 0.3;
/// Ticks in a row that must look slew-limited before they are slew samples: a command that
/// jumps looks slew-limited for a tick or two (`tests/actuator_id.rs`).
pub const SLEW_RUN_TICKS: u8 = 5;
/// A tick is slew-limited when its rate is under this share of the lag's `|e|/τ̂` \[-\]
/// (`tests/actuator_id.rs::a_slew_that_binds_is_found`).
pub const SLEW_RATE_SHARE: f64 = 0.6;
/// Weight of a new, faster slew sample in `r̂` \[-\]; a slower one weighs an eighth of
/// it (`tests/actuator_id.rs::a_slew_that_binds_is_found`).
pub const SLEW_GAIN: f64 = 0.2;
/// How many samples the lag's sums remember: each new one weighs the old ones down by
/// `1 − 1/MEMORY_SAMPLES` (`tests/actuator_id.rs::the_lag_is_found_from_a_wrong_prior`).
pub const MEMORY_SAMPLES: f64 = 400.0;
/// A told lag's weight as a prior, in samples
/// (`tests/actuator_id.rs::the_lag_is_found_from_a_wrong_prior`).
pub const PRIOR_SAMPLES: f64 = 20.0;
/// The rate at which the prior's samples count \[N/s\] (`tests/actuator_id.rs`).
pub const PRIOR_RATE_N_PER_S: f64 = 50.0;
/// Lag samples needed before a tick can be judged slew-limited (the judgement uses `τ̂`;
/// `tests/actuator_id.rs::a_slew_that_binds_is_found`).
pub const LAG_SAMPLES_FOR_SLEW: u16 = 50;
/// Identified lags below this many tick periods are an ideal actuator: no lead
/// (`tests/actuator_id.rs::an_ideal_actuator_changes_no_command`).
pub const LAG_FLOOR_TICKS: f64 = 2.5;

/// `1/x`, 0 for an infinite `x`.
fn inv(x: f64) -> f64 {
    if x.is_finite() {
        1.0 / x
    } else {
        0.0
    }
}

/// The weight of the prior lag in the lag's sums \[(N/s)²\]: [`PRIOR_SAMPLES`] samples at
/// [`PRIOR_RATE_N_PER_S`] for a configured lag; [`UNTOLD_PRIOR_SAMPLES`] for
/// `actuator_lag_s = 0`, which says "not told", not "no lag".
fn prior_weight(actuator_lag_s: f64) -> f64 {
    if actuator_lag_s > 0.0 {
        PRIOR_SAMPLES * PRIOR_RATE_N_PER_S * PRIOR_RATE_N_PER_S
    } else {
        UNTOLD_PRIOR_SAMPLES * PRIOR_RATE_N_PER_S * PRIOR_RATE_N_PER_S
    }
}

/// The weight of the untold lag (`untold_lag_s`), in samples: a guess the actuator's own first samples
/// outweigh (docs/decisions/untold-actuator-lag.md).
pub const UNTOLD_PRIOR_SAMPLES: f64 = 2.0;

/// The lag the identifier starts from: the configured one, or `untold_lag_s` when not
/// told.
fn prior_lag(actuator_lag_s: f64, untold_lag_s: f64) -> f64 {
    if actuator_lag_s > 0.0 {
        actuator_lag_s
    } else {
        untold_lag_s
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
    pub(crate) fn new(config: &ControllerConfig) -> Self {
        let (actuator_slew_n_per_s, tick_period_s) =
            (config.actuator_slew_n_per_s, config.tick_period_s);
        let w = prior_weight(config.actuator_lag_s);
        let actuator_lag_s = prior_lag(config.actuator_lag_s, config.untold_lag_s);
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

    /// The identified lag `τ̂` \[s\] (0 for an actuator faster than the floor).
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

    /// The identified slew `r̂` \[N/s\] (the prior, ∞ when not given, until a slew-limited
    /// tick is seen).
    #[inline]
    pub(crate) fn slew_n_per_s(&self) -> T {
        self.slew
    }

    /// `1/r̂` \[s/N\] (0 for an actuator that is not slew-limited).
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
