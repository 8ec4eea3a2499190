//! Closing the loop on slip: the controller's belief `μ̂` about friction, the margin it
//! keeps on the safety factor, and how a tactile sensor's slip signal changes both.
//!
//! A signal is *incipient* (the patch's edge slides, its centre sticks) or *gross* (the
//! object slides or turns). `u` is the highest utilisation (under the present `μ̂`, no
//! safety factor) of the last [`LOOKBACK_S`] to 2·[`LOOKBACK_S`]: a sensor reports a slip
//! after it began. On a signal the controller
//!
//! 1. raises the margin by `slip_step_incipient` or `slip_step_gross` (at most
//!    `slip_margin_max`); the command jumps to the new requirement in the same tick,
//!    past the rise-rate limit (the *emergency rise*, still capped by `N_max`);
//! 2. on a gross slip, or an incipient one that persists past a first step of the margin,
//!    lowers `μ̂ ← μ̂·u` (never above the present `μ̂`, never below `mu_floor_fraction`
//!    of the configured `μ`), unless `u` < [`PLAUSIBLE_UTILISATION`] (not a slip of that
//!    load: margin only);
//! 3. takes an incipient report at `u` < [`CREEP_UTILISATION`] as *creep* (a soft patch's
//!    edge sliding long before the contact does): the margin rises at most to
//!    `creep_margin_max`, `μ̂` does not move, and a margin above that cap relaxes toward
//!    it as it would toward 1 in silence.
//!
//! Timing: an incipient report counts once it has lasted [`INCIPIENT_CONFIRM_S`], a gross
//! one at once; a persisting signal steps again only after [`REFRACTORY_S`]. After
//! [`MARGIN_QUIET_S`] with no signal the margin relaxes toward 1 (time constant
//! [`MARGIN_RELAX_TAU_S`]); after [`QUIET_S`] of silence `μ̂` relaxes toward `μ` (time
//! constant [`RELAX_TAU_S`]). Once both are within `1e-4` of their configured values they
//! snap back, and the commands are bit for bit those of a controller that never saw a
//! slip; with no signal ever, nothing here changes a bit
//! (`tests/robust_grip.rs::after_relaxing_a_slip_the_commands_are_bit_identical`).
//!
//! Shown by `tests/robust_grip.rs` and `tests/creep.rs`; the values are
//! docs/decisions/slip-response-steps.md. Cost per tick: a few comparisons; a division on
//! a tick that changes `μ̂`.

use crate::controller::config::ControllerConfig;
use crate::controller::math::{greater, lesser};
use crate::real::Real;
use serde::{Deserialize, Serialize};

/// What a tactile slip sensor reports with a measurement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SlipSignal {
    /// No slip seen (or no slip sensor).
    #[default]
    None,
    /// Incipient slip: the patch's edge slides, its centre still sticks.
    Incipient,
    /// Gross slip: the object slides or turns in the grasp.
    Gross,
}

impl SlipSignal {
    /// The name used in reports and JSON.
    pub fn name(self) -> &'static str {
        match self {
            SlipSignal::None => "none",
            SlipSignal::Incipient => "incipient",
            SlipSignal::Gross => "gross",
        }
    }
}

/// A slip at a utilisation below this is no evidence about `μ` \[-\]: a false alarm or a
/// load the sensor did not see (`tests/robust_grip.rs::a_false_alarm_does_not_lower_mu`).
pub const PLAUSIBLE_UTILISATION: f64 = 0.4;
/// An incipient report at a recent utilisation below this is creep, not slip \[-\]
/// (`tests/creep.rs`; docs/decisions/slip-response-steps.md).
pub const CREEP_UTILISATION: f64 = 0.7;
/// How long an incipient report must persist before it counts \[s\]: two ticks at
/// 1 kHz, the usual debounce of slip detectors (docs/decisions/slip-response-steps.md).
pub const INCIPIENT_CONFIRM_S: f64 = 0.002;
/// How far back the utilisation of a reported slip is looked for (one to two of these)
/// \[s\]: covers a sensor latency up to this (docs/decisions/slip-response-steps.md).
pub const LOOKBACK_S: f64 = 0.01;
/// Least time between two steps of the margin while a signal persists \[s\]: the
/// actuator's time to act on the first (docs/decisions/slip-response-steps.md).
pub const REFRACTORY_S: f64 = 0.02;
/// Slip-free time before the margin starts to relax \[s\]
/// (docs/decisions/slip-response-steps.md).
pub const MARGIN_QUIET_S: f64 = 0.1;
/// Time constant of the margin's relaxation \[s\] (docs/decisions/slip-response-steps.md).
pub const MARGIN_RELAX_TAU_S: f64 = 0.2;
/// Slip-free time before `μ̂` starts to relax \[s\] (docs/decisions/slip-response-steps.md).
pub const QUIET_S: f64 = 1.0;
/// Time constant of `μ̂`'s relaxation \[s\] (docs/decisions/slip-response-steps.md).
pub const RELAX_TAU_S: f64 = 5.0;

/// The controller's belief about friction and its margin, and how slip changes them.
#[derive(Debug, Clone)]
pub(crate) struct SlipResponse<T> {
    mu: T,
    inv_mu: T,
    mu_floor: T,
    step_incipient: T,
    step_gross: T,
    margin_max: T,
    creep_margin_max: T,
    refractory_ticks: u32,
    confirm_ticks: u32,
    lookback_ticks: u32,
    quiet_ticks: u32,
    relax_rate: T,
    margin_quiet_ticks: u32,
    margin_relax_rate: T,
    // State.
    mu_hat: T,
    inv_mu_hat: T,
    margin: T,
    since_slip: u32,
    since_step: u32,
    incipient_run: u32,
    episode_steps: u8,
    peak_now: T,
    peak_before: T,
    peak_age: u32,
    pristine: bool,
}

fn ticks_of(seconds: f64, tick_period_s: f64) -> u32 {
    let t = libm::ceil(seconds / tick_period_s - 1e-9);
    if t >= f64::from(u32::MAX) {
        u32::MAX
    } else {
        t.max(1.0) as u32
    }
}

impl<T: Real> SlipResponse<T> {
    /// For a validated configuration: its `μ`, tick period, slip steps and caps and `μ`
    /// floor.
    pub(crate) fn new(config: &ControllerConfig) -> Self {
        let (mu, tick_period_s) = (config.mu, config.tick_period_s);
        Self {
            mu: T::of(mu),
            inv_mu: T::of(1.0 / mu),
            mu_floor: T::of(mu * config.mu_floor_fraction),
            step_incipient: T::of(config.slip_step_incipient),
            step_gross: T::of(config.slip_step_gross),
            margin_max: T::of(config.slip_margin_max),
            creep_margin_max: T::of(config.creep_margin_max),
            refractory_ticks: ticks_of(REFRACTORY_S, tick_period_s),
            confirm_ticks: ticks_of(INCIPIENT_CONFIRM_S, tick_period_s),
            lookback_ticks: ticks_of(LOOKBACK_S, tick_period_s),
            quiet_ticks: ticks_of(QUIET_S, tick_period_s),
            relax_rate: T::of((tick_period_s / RELAX_TAU_S).min(1.0)),
            margin_quiet_ticks: ticks_of(MARGIN_QUIET_S, tick_period_s),
            margin_relax_rate: T::of((tick_period_s / MARGIN_RELAX_TAU_S).min(1.0)),
            mu_hat: T::of(mu),
            inv_mu_hat: T::of(1.0 / mu),
            margin: T::one(),
            since_slip: u32::MAX,
            since_step: u32::MAX,
            incipient_run: 0,
            episode_steps: 0,
            peak_now: T::zero(),
            peak_before: T::zero(),
            peak_age: 0,
            pristine: true,
        }
    }

    /// Forgets every slip.
    pub(crate) fn reset(&mut self) {
        self.mu_hat = self.mu;
        self.inv_mu_hat = self.inv_mu;
        self.margin = T::one();
        self.since_slip = u32::MAX;
        self.since_step = u32::MAX;
        self.incipient_run = 0;
        self.episode_steps = 0;
        self.peak_now = T::zero();
        self.peak_before = T::zero();
        self.peak_age = 0;
        self.pristine = true;
    }

    /// `1/μ̂`.
    #[inline]
    pub(crate) fn inv_mu_estimate(&self) -> T {
        self.inv_mu_hat
    }

    /// `μ̂`.
    #[inline]
    pub(crate) fn mu_estimate(&self) -> T {
        self.mu_hat
    }

    /// The margin (≥ 1) multiplying the safety factor.
    #[inline]
    pub(crate) fn margin(&self) -> T {
        self.margin
    }

    /// Whether no slip signal has been seen since the margin and `μ̂` last snapped back to
    /// their configured values (or ever).
    #[inline]
    pub(crate) fn pristine(&self) -> bool {
        self.pristine
    }

    /// `safety × margin`, exactly `safety` while no slip has been seen.
    #[inline]
    pub(crate) fn safety(&self, safety: T) -> T {
        if self.pristine {
            safety
        } else {
            safety * self.margin
        }
    }

    /// Takes one tick's signal; `utilisation` is that of the tick's load at the measured
    /// normal force under the present `μ̂` (no safety factor). Returns whether the margin
    /// rose or `μ̂` fell (the tick then allows the emergency rise).
    pub(crate) fn observe(&mut self, signal: SlipSignal, utilisation: T) -> bool {
        self.since_step = self.since_step.saturating_add(1);
        // The recent peak of the utilisation, in two windows of `lookback_ticks`.
        self.peak_age = self.peak_age.saturating_add(1);
        if self.peak_age > self.lookback_ticks {
            self.peak_before = self.peak_now;
            self.peak_now = T::zero();
            self.peak_age = 1;
        }
        if utilisation > self.peak_now {
            self.peak_now = utilisation;
        }
        self.incipient_run = match signal {
            SlipSignal::Incipient => self.incipient_run.saturating_add(1),
            _ => 0,
        };
        let step = match signal {
            SlipSignal::Incipient if self.incipient_run < self.confirm_ticks => {
                // Not yet confirmed: neither evidence nor quiet.
                return false;
            }
            SlipSignal::None => {
                self.since_slip = self.since_slip.saturating_add(1);
                if !self.pristine && self.since_slip >= self.margin_quiet_ticks {
                    self.relax();
                }
                return false;
            }
            SlipSignal::Incipient => self.step_incipient,
            SlipSignal::Gross => self.step_gross,
        };
        let u = greater(self.peak_now, self.peak_before);
        if signal == SlipSignal::Incipient && u < T::of(CREEP_UTILISATION) {
            return self.creep(step);
        }
        // A new episode once the margin has had its quiet time.
        if self.since_slip >= self.margin_quiet_ticks {
            self.episode_steps = 0;
        }
        self.since_slip = 0;
        if self.since_step < self.refractory_ticks {
            return false;
        }
        self.since_step = 0;
        self.pristine = false;
        let margin = lesser(self.margin + step, self.margin_max);
        let mut changed = margin > self.margin;
        self.margin = margin;
        // Evidence about μ: a gross slip, or an incipient one that outlasted a first step
        // of the margin. (A first incipient report is often a transient, such as a load
        // that rose faster than the grip; the margin covers it.)
        let evidence = signal == SlipSignal::Gross || self.episode_steps > 0;
        self.episode_steps = self.episode_steps.saturating_add(1);
        if evidence && u >= T::of(PLAUSIBLE_UTILISATION) && u < T::one() {
            let mu = greater(self.mu_hat * u, self.mu_floor);
            if mu < self.mu_hat {
                self.mu_hat = mu;
                self.inv_mu_hat = mu.recip();
                changed = true;
                // Utilisations under the old belief are not comparable with new ones.
                self.peak_now = T::zero();
                self.peak_before = T::zero();
            }
        }
        changed
    }

    /// A creep tick: a little margin, no evidence about μ. Creep is no slip, so it does
    /// not hold up a margin that a slip raised: after the margin's quiet time it relaxes
    /// toward `creep_margin_max` as it would toward 1 on a quiet tick. `μ̂` keeps what a
    /// slip taught while the sensor reports anything (it relaxes only on silence), and
    /// the creep's ticks count toward that silence's quiet time. (Comparisons, not
    /// `min`/`max`: on the Cortex-M4F those are calls.)
    fn creep(&mut self, step: T) -> bool {
        let cap = self.creep_margin_max;
        self.since_slip = self.since_slip.saturating_add(1);
        if self.margin > cap {
            if self.since_slip >= self.margin_quiet_ticks {
                self.margin = self.margin + (cap - self.margin) * self.margin_relax_rate;
            }
            return false;
        }
        if self.since_step < self.refractory_ticks || !(self.margin < cap) {
            return false;
        }
        self.since_step = 0;
        self.pristine = false;
        let raised = self.margin + step;
        self.margin = if raised < cap { raised } else { cap };
        true
    }

    fn relax(&mut self) {
        let k = self.margin_relax_rate;
        self.margin = self.margin + (T::one() - self.margin) * k;
        if self.since_slip >= self.quiet_ticks && self.mu_hat != self.mu {
            let k = self.relax_rate;
            self.mu_hat = self.mu_hat + (self.mu - self.mu_hat) * k;
            self.inv_mu_hat = self.mu_hat.recip();
        }
        let close = T::of(1e-4);
        if self.margin - T::one() <= close && (self.mu - self.mu_hat) <= close * self.mu {
            self.reset();
        }
    }
}
