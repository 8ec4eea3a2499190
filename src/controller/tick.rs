//! The controller: validated once, then one total function per tick.

use crate::controller::actuator::ActuatorId;
use crate::controller::capacity::{Capacity, Solution, TableError};
use crate::controller::config::ControllerConfig;
use crate::controller::lead::Lead;
use crate::controller::math::{greater, lesser, Libm, TickMath};
use crate::controller::slip::{SlipResponse, SlipSignal};
use crate::controller::status::Status;
use crate::error::ConfigError;
use crate::real::Real;
use core::marker::PhantomData;

mod setup;

/// Why [`Controller::from_tables`] refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FromTablesError {
    /// The configuration itself is invalid.
    Config(ConfigError),
    /// The tables do not fit the configuration.
    Tables(TableError),
}

impl core::fmt::Display for FromTablesError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            FromTablesError::Config(e) => e.fmt(f),
            FromTablesError::Tables(e) => e.fmt(f),
        }
    }
}

impl core::error::Error for FromTablesError {}

/// One sensor reading. Any value is accepted; the tick decides what is usable.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Measurement<T> {
    /// Tangential force in the contact plane, two components \[N\].
    pub tangential_force_n: [T; 2],
    /// Torsional moment about the contact normal [N·m].
    pub torsional_moment_nm: T,
    /// Measured normal force \[N\] (the grip the contact has now).
    pub normal_force_n: T,
    /// When the reading was taken \[µs\], on the sensor's clock. Must increase.
    pub timestamp_us: u64,
    /// What a tactile slip sensor saw ([`SlipSignal::None`] without one).
    pub slip: SlipSignal,
}

/// What one tick decided. Every number is finite, always.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TickOutput<T> {
    /// The commanded normal force \[N\], in `[N_min, N_max]`.
    pub command_n: T,
    /// `N_req(s)`: the least force that holds the load with the safety margin \[N\] (may lie
    /// outside `[N_min, N_max]`: see [`Capacity`] for how it is extended there).
    pub required_n: T,
    /// `N_slip = N_req(1)`: the force at which this load would just start to slip \[N\].
    pub n_slip_n: T,
    /// How far the load is along its way to the limit surface of the contact at the
    /// measured normal force: `< 1` holds, `≥ 1` slips. In `[0, UTILISATION_MAX]`.
    pub utilisation: T,
    /// What happened.
    pub status: Status,
    /// Whether the input has been bad or stale for longer than the stale timeout, so the
    /// command is heading for the fault force.
    pub fault_active: bool,
    /// Illinois iterations spent in this tick (both solves), for cost accounting.
    pub iterations: u8,
    /// The friction coefficient the controller now believes: the configured `μ` until a
    /// slip signal lowers it (see [`slip`](super::slip)).
    pub mu_estimate: T,
    /// The margin multiplying the safety factor: the slip response's margin (see
    /// [`slip`](super::slip)) times the load's factor (`cyclic_factor` while the load
    /// cycles, a factor ramping from 1 to `steady_factor` while it is steady: see
    /// [`lead`](super::lead)).
    /// The force asked is `N_req` at the safety factor times this margin, floored at 1:
    /// never below `N_slip`. It is `slip_margin · load_factor`.
    pub margin: T,
    /// The slip response's part of `margin`: 1 until a slip signal raises it \[-\].
    pub slip_margin: T,
    /// The load's part of `margin` \[-\]: `cyclic_factor` while the load cycles, the
    /// steady factor (ramping from 1 to `steady_factor`) while it is steady, else 1.
    pub load_factor: T,
    /// How far the target leads the requirement for the actuator's lag \[N\], `≥ 0`: the
    /// target is `min(required_n, N_max)` plus this, before the clamp into
    /// `[N_min, N_max]` and the rate limits (0 on a tick without a good measurement).
    pub lead_n: T,
}

/// Frames in a row, each plausibly newer than the one before, that re-anchor the
/// controller's clock when they all disagree with its anchor (see [`Controller`], "Time").
pub const RESYNC_FRAMES: u8 = 3;

/// The slip-prevention controller.
///
/// Built once by [`Controller::new`], which validates the [`ControllerConfig`] into a
/// [`ConfigError`] naming the bad field and precomputes the [`Capacity`] grid (this is
/// where all `powf` and quadrature happen). After that [`Controller::tick`] cannot fail,
/// does not allocate and runs in bounded time: two solves of at most
/// `log2(force_nodes) + max_illinois_iterations` steps each, and one utilisation (two on
/// a tick whose slip signal lowers `μ̂`).
///
/// Each tick, for a good measurement (finite, within the sensor ranges, newer than the
/// last good one):
/// 1. `N_slip = N_req(1)` and `N_req(s)` from the load `(|f_t|, |m_n|)` at the believed
///    `μ̂`, `s` being the safety factor times the [`margin`](TickOutput::margin) (floored
///    at 1), a round patch's moment times its torsion factor
///    ([`Controller::tick_required_force`]);
/// 2. the target: `N_req(s)` led ahead of the actuator ([`lead`](super::lead)), clamped
///    into `[N_min, N_max]`; status `Saturated` when `N_req(s) > N_max`;
/// 3. the command moves toward the target by at most `rise_rate·dt` up or
///    `fall_rate·dt` down (`dt` the tick period): it rises fast and relaxes slowly.
///
/// For a bad measurement (NaN, ±∞, beyond the sensor range: `SensorFault`) or a stale one
/// (see "Time": `StaleInput`) it holds the last command and reports the last good
/// `N_req`, `N_slip` and utilisation. Once no good measurement has arrived for
/// `stale_timeout_s` it moves the command, rate-limited, to the fault target and sets
/// `fault_active` until a good measurement comes. The fault target is
/// `max(fault_force_n, min(N_req, N_max))` with `N_req` the last good tick's required
/// force: never less than what the last known load needed, so a dead sensor or link never
/// opens the hand (`fault_force_n` only ever raises it). The command starts at `N_min`.
///
/// Silence is only seen by a loop that ticks without a measurement: [`Controller::idle`],
/// once per tick period with no frame (the device loop's timer does, see
/// `softgrip::device`).
///
/// **Time.** Timestamps are compared with wrapping arithmetic: a measurement is newer when
/// its timestamp is 1 µs to 1 s (or four tick periods, if longer) after the last good one,
/// modulo 2⁶⁴, so a sensor clock that wraps keeps working; each bad or idle tick since the
/// last good measurement widens the window by two tick periods, so frames after a silence
/// of any length are taken at once. Anything else (a repeat, an
/// older frame, a jump into the far future such as `u64::MAX`) is refused as
/// `StaleInput`, counted ([`Controller::time_rejections`]), and leaves the anchor where it
/// was: one bad timestamp costs exactly one frame. When [`RESYNC_FRAMES`] refused frames
/// in a row each follow the one before by a plausible step, the sensor's clock has really
/// moved (a restart, a long silence): the last of them is accepted and becomes the new
/// anchor.
///
/// **Continuity.** The command moves by at most `rise_rate·dt` up and `fall_rate·dt`
/// down per tick and stays in `[N_min, N_max]`, whatever the input; the one exception is
/// the emergency rise on a slip signal (see [`slip`](super::slip)). A reconfiguration
/// hands over with [`Controller::take_over_from`].
///
/// `T` is the precision of the tick (f32 on the Cortex-M4F), `M` its math backend.
#[derive(Debug, Clone)]
pub struct Controller<T, M = Libm> {
    config: ControllerConfig,
    capacity: Capacity<T>,
    inv_mu: T,
    safety: T,
    n_min: T,
    n_max: T,
    torsion_factor: T,
    rise_step: T,
    fall_step: T,
    fault_force: T,
    force_range: T,
    moment_range: T,
    stale_ticks: u32,
    lead: Lead<T>,
    actuator: ActuatorId<T>,
    slip_response: SlipResponse<T>,
    // State.
    command: T,
    last: Option<TickOutput<T>>,
    last_good_us: Option<u64>,
    max_step_us: u64,
    period_us: u64,
    resync: Option<(u64, u8)>,
    time_rejections: u32,
    bad_ticks: u32,
    slip_node: usize,
    _math: PhantomData<M>,
}

impl<T: Real, M: TickMath<T>> Controller<T, M> {
    /// The configuration it was built from.
    pub fn config(&self) -> &ControllerConfig {
        &self.config
    }

    /// The precomputed grid.
    pub fn capacity(&self) -> &Capacity<T> {
        &self.capacity
    }

    /// The present command \[N\].
    pub fn command_n(&self) -> T {
        self.command
    }

    /// Back to the start-up state (command `N_min`, no history), keeping the grid.
    pub fn reset(&mut self) {
        self.command = self.n_min;
        self.last = None;
        self.last_good_us = None;
        self.resync = None;
        self.bad_ticks = 0;
        self.slip_node = 0;
        self.lead.reset();
        self.actuator.reset();
        self.slip_response.reset();
    }

    /// `N_req` for a load, without touching the controller's state: the pure rule of
    /// docs/model.md, the model's requirement of `(s·f_t, s·m_n)` at the configured `μ`.
    /// `safety` scales the load (1 gives `N_slip`, as [`Self::slip_force`] does). The tick
    /// asks the same of a hemicylinder; of a round patch it asks
    /// [`Self::tick_required_force`]. Non-finite inputs give `None`. Cost: one solve.
    pub fn required_force(
        &self,
        tangential_force_n: T,
        torsional_moment_nm: T,
        safety: T,
    ) -> Option<Solution<T>> {
        let (f, m) = (tangential_force_n.abs(), torsional_moment_nm.abs());
        if !(f.is_finite() && m.is_finite() && safety.is_finite()) {
            return None;
        }
        let s = safety.abs() * self.inv_mu;
        Some(self.capacity.required_force::<M>(f * s, m * s))
    }

    /// `N_req` for a load as the tick asks it of a steady load at safety factor `safety`
    /// (no slip signal, the configured `μ`), without touching the controller's state: the
    /// model's requirement of `(s·f_t, s·β·m_n)`, `β` being
    /// `disc_torsion_factor` ([`ControllerConfig::torsion_factor`]) on a round patch
    /// and 1 on a hemicylinder (where it is [`Self::required_force`]). Non-finite inputs
    /// give `None`. Cost: one solve.
    pub fn tick_required_force(
        &self,
        tangential_force_n: T,
        torsional_moment_nm: T,
        safety: T,
    ) -> Option<Solution<T>> {
        self.required_force(
            tangential_force_n,
            torsional_moment_nm * self.torsion_factor,
            safety,
        )
    }

    /// `N_slip` for a load, without touching the controller's state: the normal force at
    /// which the model's contact starts to slip under `(f_t, m_n)` at the configured `μ`
    /// (no safety factor, on either shape). Non-finite inputs give `None`. Cost: one solve.
    pub fn slip_force(&self, tangential_force_n: T, torsional_moment_nm: T) -> Option<Solution<T>> {
        let (f, m) = (tangential_force_n.abs(), torsional_moment_nm.abs());
        if !(f.is_finite() && m.is_finite()) {
            return None;
        }
        Some(
            self.capacity
                .required_force::<M>(f * self.inv_mu, m * self.inv_mu),
        )
    }

    /// Utilisation of a load at normal force `normal_force_n` (no safety factor), without
    /// touching the state. Non-finite inputs give `None`.
    pub fn utilisation(
        &self,
        tangential_force_n: T,
        torsional_moment_nm: T,
        normal_force_n: T,
    ) -> Option<T> {
        let (f, m) = (tangential_force_n.abs(), torsional_moment_nm.abs());
        if !(f.is_finite() && m.is_finite() && normal_force_n.is_finite()) {
            return None;
        }
        Some(
            self.capacity
                .utilisation::<M>(f * self.inv_mu, m * self.inv_mu, normal_force_n),
        )
    }

    fn in_range(&self, m: &Measurement<T>) -> bool {
        let [fx, fy] = m.tangential_force_n;
        let r = self.force_range;
        // `!(|x| <= r)` is also true for NaN.
        fx.abs() <= r
            && fy.abs() <= r
            && m.normal_force_n.abs() <= r
            && m.torsional_moment_nm.abs() <= self.moment_range
    }

    fn rate_limited(&self, target: T) -> T {
        let up = self.command + self.rise_step;
        let down = self.command - self.fall_step;
        lesser(
            greater(greater(lesser(target, up), down), self.n_min),
            self.n_max,
        )
    }

    /// One control tick. Total: any measurement, however hostile, gives a finite output
    /// and leaves the controller in a documented state (see the type's docs).
    pub fn tick(&mut self, m: &Measurement<T>) -> TickOutput<T> {
        let status = if !self.in_range(m) {
            Status::SensorFault
        } else if !self.timestamp_ok(m.timestamp_us) {
            Status::StaleInput
        } else {
            return self.good_tick(m);
        };
        self.bad_tick(status)
    }

    /// Whether a measurement stamped `t` may be used (see the type's docs, "Time"); counts
    /// and tracks those that may not.
    fn timestamp_ok(&mut self, t: u64) -> bool {
        let Some(last) = self.last_good_us else {
            return true;
        };
        let step = t.wrapping_sub(last);
        // Silence (bad or idle ticks) widens the window by twice the time it took.
        let window = self
            .max_step_us
            .saturating_add(u64::from(self.bad_ticks).saturating_mul(self.period_us * 2));
        if step > 0 && step <= window {
            self.resync = None;
            return true;
        }
        self.time_rejections = self.time_rejections.saturating_add(1);
        let agreeing = match self.resync {
            Some((prev, n)) => {
                let d = t.wrapping_sub(prev);
                if d > 0 && d <= self.max_step_us {
                    n.saturating_add(1)
                } else {
                    1
                }
            }
            None => 1,
        };
        if agreeing >= RESYNC_FRAMES {
            // The sensor's clock really moved (a wrap, a restart, a long silence):
            // re-anchor on it.
            self.resync = None;
            return true;
        }
        self.resync = Some((t, agreeing));
        false
    }

    /// The friction coefficient the controller now believes (see [`slip`](super::slip)).
    pub fn mu_estimate(&self) -> T {
        self.slip_response.mu_estimate()
    }

    /// The actuator's lag the controller has identified \[s\] (0: ideal, or none seen yet;
    /// see [`actuator`](super::actuator)).
    pub fn actuator_lag_estimate_s(&self) -> T {
        self.actuator.lag_s()
    }

    /// The actuator's slew the controller has identified [N/s] (the configured one, ∞
    /// when not given, until a slew-limited tick is seen).
    pub fn actuator_slew_estimate_n_per_s(&self) -> T {
        self.actuator.slew_n_per_s()
    }

    /// The margin multiplying the safety factor: the slip response's (see
    /// [`slip`](super::slip)) times the cyclic or the steady load's (see [`lead`](super::lead)).
    pub fn margin(&self) -> T {
        self.slip_response.margin() * self.load_factor_and_safety().0
    }

    /// The load's factor on the safety factor (see [`lead`](super::lead)), and the safety
    /// factor with the slip response's margin and that factor on it (not yet floored at
    /// 1). The steady load's factor, below 1, only while the slip response is pristine: a
    /// contact that has slipped keeps its whole margin until the slip is forgotten. (One
    /// test of `pristine` for both: the M4F's tick budget.)
    #[inline]
    fn load_factor_and_safety(&self) -> (T, T) {
        if self.slip_response.pristine() {
            let factor = self.lead.safety_factor();
            (factor, self.safety * factor)
        } else {
            let factor = self.lead.cyclic_factor_or_one();
            (factor, self.slip_response.safety(self.safety) * factor)
        }
    }

    /// Measurements refused for their timestamp so far (saturating).
    pub fn time_rejections(&self) -> u32 {
        self.time_rejections
    }

    /// A tick with no measurement at all: call it once per tick period when the sensor
    /// (or the link) delivered nothing, from a timer-driven loop. It counts like a stale
    /// input (`StaleInput`): the command holds, and once no good measurement has arrived
    /// for the stale timeout it moves to the fault force. This is how a silent sensor or
    /// link is detected; a loop that only ticks on arriving frames never calls it, and
    /// then holds its command through silence. The fault target is never below the last
    /// required force ([`Controller::fault_target_n`]). Cost: a few comparisons.
    pub fn idle(&mut self) -> TickOutput<T> {
        self.bad_tick(Status::StaleInput)
    }

    /// Whether the input has been bad, stale or silent for the stale timeout, so the
    /// command is at or heading for [`Controller::fault_target_n`].
    pub fn fault_active(&self) -> bool {
        self.bad_ticks >= self.stale_ticks
    }

    /// Where the command goes once the fault is active \[N\]: `fault_force_n`, or the last
    /// good tick's required force `N_req` (capped at `N_max`) when that is greater, so a
    /// fault never lowers the grip below what the last known load needed.
    pub fn fault_target_n(&self) -> T {
        match self.last {
            Some(o) if o.required_n > self.fault_force => o.required_n.min(self.n_max),
            _ => self.fault_force,
        }
    }

    fn bad_tick(&mut self, status: Status) -> TickOutput<T> {
        self.bad_ticks = self.bad_ticks.saturating_add(1);
        let fault_active = self.fault_active();
        if fault_active {
            self.command = self.rate_limited(self.fault_target_n());
        }
        let last = self.last;
        let load_factor = self.load_factor_and_safety().0;
        let slip_margin = self.slip_response.margin();
        TickOutput {
            command_n: self.command,
            required_n: last.map_or(self.n_min, |o| o.required_n),
            n_slip_n: last.map_or(T::zero(), |o| o.n_slip_n),
            utilisation: last.map_or(T::zero(), |o| o.utilisation),
            status,
            fault_active,
            iterations: 0,
            mu_estimate: self.slip_response.mu_estimate(),
            margin: slip_margin * load_factor,
            slip_margin,
            load_factor,
            lead_n: T::zero(),
        }
    }

    fn good_tick(&mut self, m: &Measurement<T>) -> TickOutput<T> {
        self.last_good_us = Some(m.timestamp_us);
        self.bad_ticks = 0;
        let [fx, fy] = m.tangential_force_n;
        let ft = M::sqrt(fx * fx + fy * fy);
        let mn = m.torsional_moment_nm.abs();
        let mut inv_mu = self.slip_response.inv_mu_estimate();
        let (mut f, mut mz) = (ft * inv_mu, mn * inv_mu);
        let mut utilisation = self.capacity.utilisation::<M>(f, mz, m.normal_force_n);
        let stepped = self.slip_response.observe(m.slip, utilisation);
        if stepped && self.slip_response.inv_mu_estimate() != inv_mu {
            inv_mu = self.slip_response.inv_mu_estimate();
            (f, mz) = (ft * inv_mu, mn * inv_mu);
            utilisation = self.capacity.utilisation::<M>(f, mz, m.normal_force_n);
        }
        // The cyclic or the steady load's factor; never below `N_slip` (a steady factor
        // below 1 on a safety factor near 1).
        let (factor, safety) = self.load_factor_and_safety();
        let safety = greater(safety, T::one());
        let slip = self
            .capacity
            .required_force_near::<M>(f, mz, self.slip_node);
        self.slip_node = slip.node;
        let req =
            self.capacity
                .required_force_scaled::<M>(f, mz * self.torsion_factor, &slip, safety);
        let status = if req.force_n > self.n_max {
            Status::Saturated
        } else {
            Status::Ok
        };
        // A tick whose slip response stepped jumps the command past the rate limit (the
        // emergency rise below): no sample of the actuator's normal response.
        if !stepped {
            self.actuator.observe(self.command, m.normal_force_n);
        }
        let capped = lesser(req.force_n, self.n_max);
        let ahead = self.lead.target(
            capped,
            slip.force_n,
            self.actuator.lag_s(),
            self.actuator.inv_slew(),
        );
        let target = lesser(greater(ahead, self.n_min), self.n_max);
        let limited = self.rate_limited(target);
        // The emergency rise: on a slip signal the command goes to its new target at once.
        self.command = if stepped {
            greater(limited, target)
        } else {
            limited
        };
        let out = TickOutput {
            command_n: self.command,
            required_n: req.force_n,
            n_slip_n: slip.force_n,
            utilisation,
            status,
            fault_active: false,
            iterations: slip.iterations.saturating_add(req.iterations),
            mu_estimate: self.slip_response.mu_estimate(),
            margin: self.slip_response.margin() * factor,
            slip_margin: self.slip_response.margin(),
            load_factor: factor,
            lead_n: ahead - capped,
        };
        self.last = Some(out);
        out
    }
}
