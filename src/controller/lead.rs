//! Commanding ahead of the load, and the load's factor on the safety factor.
//!
//! **Lead.** Through an actuator with lag `τ` and slew limit `r` (∞ when not limited),
//! the target is the requirement `N_req(s)` one horizon `h` ahead:
//!
//! ```text
//! N_target = N_req + max(0, Ṅ_req − Ṅ₀)·h,   h = min(τ / (1 − Ṅ_req/r), HORIZON_MAX_LAGS·τ)
//! ```
//!
//! - `h = τ` makes up a first-order lag's delay on a ramp; a slew `r` adds `h·Ṅ/r`, which
//!   gives the horizon above, capped at [`HORIZON_MAX_LAGS`] lags as `Ṅ` nears `r`.
//! - `Ṅ_req = Ṅ_slip·N_req/N_slip`: the rate is the load's, from two first-order
//!   low-passes (time constant [`FILTER_TAU_S`]) of `N_slip = N_req(1)` and of its
//!   difference quotient. No safety factor or margin enters `N_slip`, so a step of the
//!   margin is not led. Exact for a pure force or a pure twist; in between the lead can
//!   miss by at most a factor `1 + γ`.
//! - `Ṅ₀` = [`RATE_DEADBAND_N_PER_S`]: slower rates are sensor noise and get no lead.
//! - `τ` and `r` are the identified actuator's ([`actuator`](super::actuator)); with
//!   `τ = 0` the target is `N_req`, bit for bit.
//! - The target is never below `N_req`; a falling load gets no lead.
//! - Swing cap: within [`SWING_WINDOW_S`] after a local peak of `N_req`, a target below
//!   that peak is capped at it (leading every rise of a fast swing would ratchet the
//!   command above the peak); a requirement past the peak gets the whole lead.
//!
//! Shown by `tests/robust_grip.rs` and `tests/actuator_id.rs`; the choices are
//! docs/decisions/lead-rate-and-horizon.md.
//!
//! **Load factor.** A factor on the safety factor (`Lead::safety_factor`), read from
//! the low-passed `N_slip` (so it cannot feed back into what it watches). A swing's depth
//! at an extreme `x` is [`CYCLE_DEPTH`]`·x` plus the `N_slip` of [`CYCLE_DEPTH_FLOOR_N`] of
//! load.
//!
//! - **Cyclic loads**: `cyclic_factor` while the load cycles. A turn is a fall
//!   (top) or rise (bottom) of a swing's depth from the extreme; the load cycles from a
//!   bottom turn that follows a top turn within [`SWING_WINDOW_S`] and another bottom turn
//!   within twice that, until twice [`SWING_WINDOW_S`] after it. One lift or one twist
//!   never cycles (`tests/load_margin.rs`; docs/decisions/cyclic-factor.md).
//! - **Steady loads**: once `N_slip` has stayed within a swing's depth of where it settled
//!   for [`STEADY_HOLD_S`] and the load does not cycle, the factor falls linearly from 1
//!   to `steady_factor` over `steady_ramp_s` (whole ticks, rounded up) and
//!   stays there. A fall of a swing's depth, or a rise of [`STEADY_RISE_N`] of load, ends
//!   it on the same tick. It waits while the slip response ([`slip`](super::slip))
//!   remembers a slip (`tests/load_margin.rs`; docs/decisions/steady-margin.md,
//!   docs/decisions/steady-ramp.md).
//! - Otherwise 1.
//!
//! [`Controller`](super::Controller) applies the factor and floors the product of the
//! safety factor and every factor on it at 1 (never below `N_slip`); it shows in
//! [`TickOutput::margin`](super::TickOutput).
//!
//! Cost per tick: about fifteen multiplications and two divisions (the horizon's and
//! `N_req/N_slip`) for the lead; a few comparisons for the detectors, and on the ramp's
//! ticks a conversion and a division. The firmware's budget: docs/firmware-costs.md.

use crate::controller::config::ControllerConfig;
use crate::real::Real;

/// Time constant of each of the two rate filters \[s\]; the rate lags by about two of
/// these (docs/decisions/lead-rate-and-horizon.md).
pub const FILTER_TAU_S: f64 = 0.006;
/// Rates of `N_req` up to this are sensor noise and get no lead \[N/s\]
/// (`tests/robust_grip.rs::the_lead_stays_calm_under_sensor_noise`).
pub const RATE_DEADBAND_N_PER_S: f64 = 2.0;
/// The longest lead horizon, in actuator lags, reached as `Ṅ_req` nears the slew
/// (`tests/robust_grip.rs::a_slew_limited_actuator_is_planned_for`).
pub const HORIZON_MAX_LAGS: f64 = 4.0;
/// How long a peak of the requirement caps the lead, and the cycle detector's window
/// \[s\]: a period of shakes of 2 Hz and faster (docs/decisions/cyclic-factor.md).
pub const SWING_WINDOW_S: f64 = 0.5;

/// How long the low-passed `N_slip` must stay within a swing's depth of where it settled
/// before the load is steady \[s\] (docs/decisions/steady-margin.md).
pub const STEADY_HOLD_S: f64 = 0.3;

/// The rise of tangential load that ends a steady hold \[N\] (`÷ μ` in `N_slip`): half of
/// [`CYCLE_DEPTH_FLOOR_N`], above a steady hold's filtered noise
/// (docs/decisions/steady-margin.md;
/// `tests/load_margin.rs::a_small_rise_ends_the_steady_factor_and_a_small_fall_does_not`).
pub const STEADY_RISE_N: f64 = 0.05;

/// The depth of a swing that counts as a turn, as a fraction of the swing's extreme \[-\]
/// (docs/decisions/cyclic-factor.md).
pub const CYCLE_DEPTH: f64 = 0.1;

/// The part of a swing's depth that does not scale with it, as tangential load \[N\]
/// (`÷ μ` in `N_slip`): 2 × the bench's largest sensor noise
/// (docs/decisions/cyclic-factor.md).
pub const CYCLE_DEPTH_FLOOR_N: f64 = 0.1;

/// The lead's filters, the load factor's detectors and their constants.
#[derive(Debug, Clone)]
pub(crate) struct Lead<T> {
    alpha: T,
    alpha_per_s: T,
    deadband: T,
    window_ticks: u64,
    cycle_ticks: u64,
    cyclic_factor: T,
    cycle_depth: T,
    cycle_floor: T,
    steady_factor: T,
    steady_rise: T,
    steady_ticks: u64,
    /// `1 − steady_factor`: the whole of the ramp's cut.
    steady_cut: T,
    /// Ticks of the ramp (`steady_ramp_s` in whole ticks, rounded up): from this many
    /// the factor is the steady one.
    ramp_ticks: u64,
    /// `ramp_ticks`, as a number.
    ramp_len: T,
    // State.
    started: bool,
    /// `N_slip`, low-passed (the first of the two rate filters).
    load_level: T,
    /// `N_slip`'s rate, low-passed (the second) \[N/s\].
    rate: T,
    /// Good ticks so far (the deadlines' clock).
    clock: u64,
    /// The swing cap's peak holds while `clock` is below this.
    peak_until: u64,
    peak: T,
    rise_max: T,
    /// The load cycles while `clock` is below this.
    cycle_until: u64,
    /// A bottom turn now follows a top turn closely enough while `clock` is below this.
    top_until: u64,
    /// A bottom turn now makes the second of a cycle while `clock` is below this.
    bottom_until: u64,
    swing_falling: bool,
    swing_extreme: T,
    /// The level past which the filtered `N_slip` turns.
    swing_turn: T,
    /// Where the filtered `N_slip` settled: the steady detector's anchor.
    steady_level: T,
    /// The load is steady while `clock` is at or past this.
    steady_from: u64,
}

impl<T: Real> Lead<T> {
    /// For a validated configuration: its tick period, `μ` (the swing depth's floor is
    /// [`CYCLE_DEPTH_FLOOR_N`] of load in `N_slip`'s units), `cyclic_factor`,
    /// `steady_factor` and `steady_ramp_s`.
    pub(crate) fn new(config: &ControllerConfig) -> Self {
        let (tick_period_s, mu) = (config.tick_period_s, config.mu);
        let ticks = |s: f64| libm::ceil(s / tick_period_s).clamp(1.0, f64::from(u32::MAX / 2));
        let w = ticks(SWING_WINDOW_S);
        let steady = ticks(STEADY_HOLD_S);
        let ramp = ticks(config.steady_ramp_s);
        Self {
            alpha: T::of(tick_period_s / (FILTER_TAU_S + tick_period_s)),
            alpha_per_s: T::of(1.0 / (FILTER_TAU_S + tick_period_s)),
            deadband: T::of(RATE_DEADBAND_N_PER_S),
            window_ticks: w as u64,
            cycle_ticks: 2 * w as u64,
            cyclic_factor: T::of(config.cyclic_factor),
            cycle_depth: T::of(CYCLE_DEPTH),
            cycle_floor: T::of(CYCLE_DEPTH_FLOOR_N / mu),
            steady_factor: T::of(config.steady_factor),
            steady_rise: T::of(STEADY_RISE_N / mu),
            steady_ticks: steady as u64,
            steady_cut: T::one() - T::of(config.steady_factor),
            ramp_ticks: ramp as u64,
            ramp_len: T::of(ramp),
            started: false,
            load_level: T::zero(),
            rate: T::zero(),
            clock: 0,
            peak_until: 0,
            peak: T::zero(),
            rise_max: T::zero(),
            cycle_until: 0,
            top_until: 0,
            bottom_until: 0,
            swing_falling: false,
            swing_extreme: T::zero(),
            swing_turn: T::zero(),
            steady_level: T::zero(),
            steady_from: u64::MAX,
        }
    }

    /// Forgets the load's history.
    pub(crate) fn reset(&mut self) {
        self.started = false;
        self.rate = T::zero();
        self.peak_until = 0;
        self.peak = T::zero();
        self.rise_max = T::zero();
        self.cycle_until = 0;
        self.top_until = 0;
        self.bottom_until = 0;
        self.swing_falling = false;
        self.swing_extreme = T::zero();
        self.swing_turn = T::zero();
        self.steady_from = u64::MAX;
    }

    /// The change of the filtered `N_slip` from a swing's extreme `extreme_n` that counts
    /// as a turn \[N\].
    #[inline]
    fn swing_depth(&self, extreme_n: T) -> T {
        extreme_n * self.cycle_depth + self.cycle_floor
    }

    /// The factor on the safety factor: `cyclic_factor` while the load cycles (module
    /// docs, "Cyclic loads"), else, while it is steady ("Steady loads"), 1 ramping down to
    /// `steady_factor` over `steady_ramp_s`, and 1 otherwise. Within
    /// `[steady_factor, cyclic_factor]`, never increasing
    /// along a steady hold.
    #[inline]
    pub(crate) fn safety_factor(&self) -> T {
        if self.clock < self.cycle_until {
            self.cyclic_factor
        } else if self.clock >= self.steady_from {
            let ticks = self.clock - self.steady_from;
            if ticks < self.ramp_ticks {
                // `ticks` < `ramp_ticks` ≤ 2³¹, so the cast is exact, and the fraction is
                // below 1 (one division: on the M4F one `VDIV`).
                T::one() - self.steady_cut * (T::of_u32(ticks as u32) / self.ramp_len)
            } else {
                self.steady_factor
            }
        } else {
            T::one()
        }
    }

    /// `cyclic_factor` while the load cycles, 1 otherwise: the factor for a
    /// contact that has slipped, which keeps its whole margin through a steady hold (the
    /// steady factor, at most 1, gives way to 1; a tick cheaper than
    /// [`Lead::safety_factor`]'s).
    #[inline]
    pub(crate) fn cyclic_factor_or_one(&self) -> T {
        if self.clock < self.cycle_until {
            self.cyclic_factor
        } else {
            T::one()
        }
    }

    /// Takes this tick's (finite, non-negative) requirement `required_n` and `N_slip`
    /// `n_slip_n`, and the identified actuator (`lag_s` ≥ 0, 0 for none; `inv_slew` =
    /// 1/slew ≥ 0, 0 when not limited); returns the target: `required_n` plus the lead,
    /// never less than `required_n`. With no lag it only keeps the filters and detectors
    /// going.
    #[inline]
    pub(crate) fn target(&mut self, required_n: T, n_slip_n: T, lag_s: T, inv_slew: T) -> T {
        if !self.started {
            self.start(n_slip_n);
            return required_n;
        }
        self.clock += 1;
        let clock = self.clock;
        let (load, before) = self.filter_load(n_slip_n);
        // The load's rate, carried to the requirement by their present ratio.
        let scale = if n_slip_n > T::zero() {
            required_n / n_slip_n
        } else {
            T::zero()
        };
        let rate = self.rate * scale;
        self.track_peak(required_n, before * scale, rate, clock);
        self.track_steady(load, clock);
        if self.swing_falling {
            self.swing_falling_tick(load, clock);
        } else {
            self.swing_rising_tick(load, clock);
        }
        if !(lag_s > T::zero()) {
            return required_n;
        }
        let rising = rate - self.deadband;
        if !(rising > T::zero()) {
            return required_n;
        }
        let horizon = self.horizon(rate, lag_s, inv_slew);
        // Finite: the filters' state and the identified lag are.
        let ahead = required_n + rising * horizon;
        // The swing cap. (Comparisons, not `min`: on the Cortex-M4F that is a call.)
        if self.clock < self.peak_until && required_n < self.peak && ahead > self.peak {
            self.peak
        } else {
            ahead
        }
    }

    /// The first tick: anchors the filters and the steady detector on `n_slip_n`.
    #[inline(always)]
    fn start(&mut self, n_slip_n: T) {
        self.started = true;
        self.load_level = n_slip_n;
        self.steady_level = n_slip_n;
        self.steady_from = self.clock + self.steady_ticks;
    }

    /// Steps both rate filters on `n_slip_n`; returns the new filtered level and the
    /// filtered rate before this step.
    #[inline(always)]
    fn filter_load(&mut self, n_slip_n: T) -> (T, T) {
        let step = n_slip_n - self.load_level;
        let raw = step * self.alpha_per_s;
        let before = self.rate;
        self.rate = self.rate + (raw - self.rate) * self.alpha;
        let load = self.load_level + step * self.alpha;
        self.load_level = load;
        (load, before)
    }

    /// The swing cap's peak: when the requirement's rate (`rate_before` on the last tick,
    /// `rate` now, both scaled) turns from rising to falling, the highest requirement of
    /// the rise that ended there caps the lead for the window.
    #[inline(always)]
    fn track_peak(&mut self, required_n: T, rate_before: T, rate: T, clock: u64) {
        if required_n > self.rise_max {
            self.rise_max = required_n;
        }
        let was_rising = rate_before > self.deadband;
        let is_rising = rate > self.deadband;
        if was_rising && !is_rising {
            self.peak_until = clock + self.window_ticks;
            self.peak = self.rise_max;
            self.rise_max = required_n;
        }
    }

    /// The steady detector: a fall past a swing's depth, or a rise past
    /// [`STEADY_RISE_N`], from where the load settled settles it anew.
    #[inline(always)]
    fn track_steady(&mut self, load: T, clock: u64) {
        if load - self.steady_level > self.steady_rise
            || self.steady_level - load > self.swing_depth(self.steady_level)
        {
            self.steady_level = load;
            self.steady_from = clock + self.steady_ticks;
        }
    }

    /// The cycle detector while the load falls: a new bottom, or a rise of a swing's depth
    /// from it (a bottom turn, which starts a cycle after a top turn and a bottom turn
    /// close enough before it). Deadlines on one tick clock, and the turn's level kept
    /// with its extreme: the Cortex-M4F's tick budget.
    #[inline(always)]
    fn swing_falling_tick(&mut self, load: T, clock: u64) {
        if load < self.swing_extreme {
            self.swing_extreme = load;
            self.swing_turn = load + self.swing_depth(load);
        }
        if load > self.swing_turn {
            self.swing_falling = false;
            self.swing_extreme = load;
            self.swing_turn = load - self.swing_depth(load);
            if clock < self.top_until && clock < self.bottom_until {
                self.cycle_until = clock + self.cycle_ticks;
            }
            self.bottom_until = clock + self.cycle_ticks;
        }
    }

    /// The cycle detector while the load rises: a new top, or a fall of a swing's depth
    /// from it (a top turn).
    #[inline(always)]
    fn swing_rising_tick(&mut self, load: T, clock: u64) {
        if load > self.swing_extreme {
            self.swing_extreme = load;
            self.swing_turn = load - self.swing_depth(load);
        }
        if load < self.swing_turn {
            self.swing_falling = true;
            self.swing_extreme = load;
            self.swing_turn = load + self.swing_depth(load);
            self.top_until = clock + self.window_ticks;
        }
    }

    /// The lead horizon \[s\] for the requirement's rate `rate` (see the module's docs).
    #[inline(always)]
    fn horizon(&self, rate: T, lag_s: T, inv_slew: T) -> T {
        if inv_slew > T::zero() {
            let max_horizon = lag_s * T::of(HORIZON_MAX_LAGS);
            let climb = T::one() - rate * inv_slew;
            let h = lag_s / climb;
            if climb > T::zero() && h < max_horizon {
                h
            } else {
                max_horizon
            }
        } else {
            lag_s
        }
    }
}
