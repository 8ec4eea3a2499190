//! Closing the loop on slip: what the controller believes about `μ` and how much margin
//! it keeps, and how a slip signal from a tactile sensor changes both.
//!
//! The configured `μ` is a belief, rarely better than ±30 % (skin, oil, dust, wear). A
//! tactile skin can say when the contact starts to slip (*incipient*: the edge of the
//! patch slides while its centre sticks) or slides as a whole (*gross*). On such a signal
//! the controller
//! 1. lowers its estimate `μ̂` to what is consistent with the load at which the contact
//!    slipped: the load had utilisation `u` under the belief `μ̂`, and a contact slips at
//!    utilisation 1, so `μ̂ ← μ̂·u` (never above the present estimate, never below
//!    [`MU_FLOOR_FRACTION`] of the configured `μ`). For an incipient slip, which starts
//!    below the true limit, this errs low, on the safe side. A signal at a load below
//!    [`PLAUSIBLE_UTILISATION`] cannot be a slip of that load (a false alarm, or a load the
//!    sensor did not see): it changes the margin only.
//! 2. multiplies its safety factor by a margin raised at once by [`MARGIN_STEP_INCIPIENT`]
//!    or [`MARGIN_STEP_GROSS`] (at most [`MARGIN_MAX`]); the command jumps to the new
//!    requirement in the same tick, past the rise-rate limit (the *emergency rise*, still
//!    capped by `N_max`).
//!
//! A signal that persists steps the margin and the estimate again only after
//! [`REFRACTORY_S`]: the actuator needs that long to act on the first step, and the
//! load measured meanwhile sits on a force that is already rising.
//!
//! After [`QUIET_S`] with no slip signal, `μ̂` and the margin relax back toward the
//! configured `μ` and 1 with the time constant [`RELAX_TAU_S`]; once within 1e-4 of them
//! they snap back exactly, and the controller is again bit for bit the one that never saw
//! a slip. With no slip signal ever, nothing here changes a single bit of the commands.
//!
//! Cost per tick: a few comparisons; a division on a tick that changes `μ̂`.

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

/// Margin added on an incipient slip signal (to a margin that starts at 1).
pub const MARGIN_STEP_INCIPIENT: f64 = 0.15;
/// Margin added on a gross slip signal.
pub const MARGIN_STEP_GROSS: f64 = 0.5;
/// The largest margin (the command is capped by `N_max` in any case).
pub const MARGIN_MAX: f64 = 3.0;
/// The lowest `μ̂`, as a fraction of the configured `μ`.
pub const MU_FLOOR_FRACTION: f64 = 0.5;
/// A slip signal at a utilisation below this (under the present belief) is not taken as
/// evidence about `μ`.
pub const PLAUSIBLE_UTILISATION: f64 = 0.4;
/// Least time between two steps of the margin while a signal persists [s].
pub const REFRACTORY_S: f64 = 0.02;
/// Slip-free time before the estimate and the margin start to relax [s].
pub const QUIET_S: f64 = 1.0;
/// Time constant of the relaxation [s].
pub const RELAX_TAU_S: f64 = 5.0;

/// The controller's belief about friction and its margin, and how slip changes them.
#[derive(Debug, Clone)]
pub(crate) struct SlipResponse<T> {
    mu: T,
    inv_mu: T,
    mu_floor: T,
    refractory_ticks: u32,
    quiet_ticks: u32,
    relax_rate: T,
    // State.
    mu_hat: T,
    inv_mu_hat: T,
    margin: T,
    since_slip: u32,
    since_step: u32,
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
    /// For the configured `μ` and tick period (both validated).
    pub(crate) fn new(mu: f64, tick_period_s: f64) -> Self {
        Self {
            mu: T::of(mu),
            inv_mu: T::of(1.0 / mu),
            mu_floor: T::of(mu * MU_FLOOR_FRACTION),
            refractory_ticks: ticks_of(REFRACTORY_S, tick_period_s),
            quiet_ticks: ticks_of(QUIET_S, tick_period_s),
            relax_rate: T::of((tick_period_s / RELAX_TAU_S).min(1.0)),
            mu_hat: T::of(mu),
            inv_mu_hat: T::of(1.0 / mu),
            margin: T::one(),
            since_slip: u32::MAX,
            since_step: u32::MAX,
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
        let step = match signal {
            SlipSignal::None => {
                self.since_slip = self.since_slip.saturating_add(1);
                if !self.pristine && self.since_slip >= self.quiet_ticks {
                    self.relax();
                }
                return false;
            }
            SlipSignal::Incipient => T::of(MARGIN_STEP_INCIPIENT),
            SlipSignal::Gross => T::of(MARGIN_STEP_GROSS),
        };
        self.since_slip = 0;
        if self.since_step < self.refractory_ticks {
            return false;
        }
        self.since_step = 0;
        self.pristine = false;
        let margin = (self.margin + step).min(T::of(MARGIN_MAX));
        let mut changed = margin > self.margin;
        self.margin = margin;
        let u = utilisation;
        if u >= T::of(PLAUSIBLE_UTILISATION) && u < T::one() {
            let mu = (self.mu_hat * u).max(self.mu_floor);
            if mu < self.mu_hat {
                self.mu_hat = mu;
                self.inv_mu_hat = mu.recip();
                changed = true;
            }
        }
        changed
    }

    fn relax(&mut self) {
        let k = self.relax_rate;
        self.margin = self.margin + (T::one() - self.margin) * k;
        self.mu_hat = self.mu_hat + (self.mu - self.mu_hat) * k;
        self.inv_mu_hat = self.mu_hat.recip();
        let close = T::of(1e-4);
        if self.margin - T::one() <= close && (self.mu - self.mu_hat) <= close * self.mu {
            self.reset();
        }
    }
}
