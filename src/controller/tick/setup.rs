//! Building a controller: from a configuration (validated, then the grid precomputed) or
//! from exported tables, into a new value or in place into an existing one (the device's
//! spare slot), and handing a running grasp over to a new configuration.

use super::{Controller, FromTablesError, TickOutput};
use crate::controller::actuator::ActuatorId;
use crate::controller::capacity::{Capacity, Tables};
use crate::controller::config::{Checked, ControllerConfig};
use crate::controller::lead::Lead;
use crate::controller::math::TickMath;
use crate::controller::slip::SlipResponse;
use crate::error::{BuildError, ConfigError, RangeOverflow};
use crate::real::{Real, SqrtFn};
use core::marker::PhantomData;

/// The largest plausible step between two good timestamps [µs]: 1 s, or four tick
/// periods if longer.
fn max_step_us(tick_period_s: f64) -> u64 {
    let us = libm::ceil((tick_period_s * 4.0).max(1.0) * 1e6);
    if us >= u64::MAX as f64 {
        u64::MAX / 2
    } else {
        us as u64
    }
}

impl<T: Real, M: TickMath<T>> Controller<T, M> {
    /// Validates `config` and precomputes in the tick's own precision `T`.
    pub fn new(config: ControllerConfig) -> Result<Self, ConfigError> {
        Self::new_precomputed_in::<T>(config)
    }

    /// Validates `config` and precomputes in precision `P` (for example f64 on the host
    /// for an f32 tick), storing the grid in `T`.
    pub fn new_precomputed_in<P: Real>(config: ControllerConfig) -> Result<Self, ConfigError> {
        let mut c = Self::blank();
        c.rebuild_precomputed_in::<P>(config)?;
        Ok(c)
    }

    /// A controller from a configuration already checked ([`ControllerConfig::check`]), its
    /// grid precomputed in the tick's precision `T`: the host's way to build one, validated
    /// once. A refused sensor range says which factor overflows ([`BuildError`]).
    pub fn from_checked(config: &Checked) -> Result<Self, BuildError> {
        Self::from_checked_in::<T>(config)
    }

    /// [`Controller::from_checked`] with the grid precomputed in precision `P` (stored in
    /// `T`).
    pub fn from_checked_in<P: Real>(config: &Checked) -> Result<Self, BuildError> {
        let cfg = *config.config();
        let mut c = Self::blank();
        match c
            .capacity
            .build_into::<P>(&cfg, SqrtFn::new(M::startup_sqrt::<P>()))
        {
            Ok(()) => {
                c.set_config(cfg);
                Ok(c)
            }
            Err(e) if e.param() == "force_range_n" => {
                Err(BuildError::RangeOverflow(c.range_overflow(&cfg)))
            }
            Err(e) => Err(BuildError::Config(e)),
        }
    }

    /// Which factor makes the sensor ranges of `cfg` overflow, on this controller's grid
    /// (built up to the range check): `safety/μ` if the rest fits at 1, else the ranges if
    /// the default ranges fit, else the contact.
    fn range_overflow(&self, cfg: &ControllerConfig) -> RangeOverflow {
        use crate::controller::capacity::check_range;
        let d = ControllerConfig::default();
        let unscaled = ControllerConfig {
            mu: 1.0,
            safety: 1.0,
            ..*cfg
        };
        let ordinary = ControllerConfig {
            force_range_n: d.force_range_n,
            moment_range_nm: d.moment_range_nm,
            ..*cfg
        };
        if check_range(&unscaled, &self.capacity).is_ok() {
            RangeOverflow::SafetyOverMu
        } else if check_range(&ordinary, &self.capacity).is_ok() {
            RangeOverflow::SensorRange
        } else {
            RangeOverflow::Contact
        }
    }

    /// A controller from exported tables ([`Capacity::tables`], `host-sim tables`): no
    /// precomputation at all. The configuration is validated as by [`Controller::new`],
    /// the tables against it (see [`Capacity::from_tables`]).
    pub fn from_tables(
        config: ControllerConfig,
        tables: &Tables<'_, T>,
    ) -> Result<Self, FromTablesError> {
        let mut c = Self::blank();
        c.rebuild_from_tables(config, tables)?;
        Ok(c)
    }

    /// An unconfigured controller: a slot that [`Controller::rebuild_precomputed_in`] or
    /// [`Controller::rebuild_from_tables`] builds into (the device keeps two, so that a
    /// new configuration is built in place while the running one ticks on). Never ticked
    /// as it is.
    pub(crate) fn blank() -> Self {
        let mut c = Self::unset();
        c.set_config(ControllerConfig::default());
        c
    }

    /// [`Controller::blank`] before its configuration is set: one struct expression, so
    /// that it can be written straight into its destination.
    #[inline(always)]
    fn unset() -> Self {
        Self {
            config: ControllerConfig::default(),
            capacity: Capacity::blank(),
            inv_mu: T::one(),
            safety: T::one(),
            n_min: T::zero(),
            n_max: T::zero(),
            torsion_factor: T::one(),
            rise_step: T::zero(),
            fall_step: T::zero(),
            fault_force: T::zero(),
            force_range: T::zero(),
            moment_range: T::zero(),
            stale_ticks: 1,
            lead: Lead::new(&ControllerConfig::DEFAULT),
            actuator: ActuatorId::new(&ControllerConfig::DEFAULT),
            slip_response: SlipResponse::new(&ControllerConfig::DEFAULT),
            command: T::zero(),
            last: None,
            last_good_us: None,
            max_step_us: 0,
            period_us: 0,
            resync: None,
            time_rejections: 0,
            bad_ticks: 0,
            slip_node: 0,
            _math: PhantomData,
        }
    }

    /// Puts [`Controller::blank`] into `slot`: one struct expression into the slot, then the
    /// default configuration set in place. The firmware's compiler still assembles the
    /// struct in this frame before copying it, but once, where building, configuring and
    /// then wrapping a blank in `Some` held it twice (the stack peak:
    /// `host-sim/tests/firmware_costs.rs`). Out of line, so that the temporary stays in
    /// this short-lived frame and is gone before the precomputation that follows.
    #[inline(never)]
    pub(crate) fn blank_into(slot: &mut Option<Self>) {
        slot.insert(Self::unset())
            .set_config(ControllerConfig::default());
    }

    /// [`Controller::new_precomputed_in`] into `self`, in place: the grid is written where
    /// it lies, with no copy of it on the stack. On an error `self` is half-built and must
    /// not tick until a rebuild succeeds (the device then keeps ticking its other slot).
    pub(crate) fn rebuild_precomputed_in<P: Real>(
        &mut self,
        config: ControllerConfig,
    ) -> Result<(), ConfigError> {
        config.validate()?;
        self.capacity
            .build_into::<P>(&config, SqrtFn::new(M::startup_sqrt::<P>()))?;
        self.set_config(config);
        Ok(())
    }

    /// [`Controller::from_tables`] into `self`, in place. On an error `self` is unchanged
    /// when the configuration or the tables are refused, and half-built when the sensor
    /// ranges are (as [`Controller::rebuild_precomputed_in`]).
    pub(crate) fn rebuild_from_tables(
        &mut self,
        config: ControllerConfig,
        tables: &Tables<'_, T>,
    ) -> Result<(), FromTablesError> {
        config.validate().map_err(FromTablesError::Config)?;
        self.capacity
            .fill_from_tables(&config, tables)
            .map_err(FromTablesError::Tables)?;
        crate::controller::capacity::check_range(&config, &self.capacity)
            .map_err(FromTablesError::Config)?;
        self.set_config(config);
        Ok(())
    }

    /// Everything but the grid, from `config`, with the start-up state (command `N_min`,
    /// no history).
    fn set_config(&mut self, config: ControllerConfig) {
        let ticks = libm::ceil(config.stale_timeout_s / config.tick_period_s - 1e-9);
        self.inv_mu = T::of(1.0 / config.mu);
        self.safety = T::of(config.safety);
        self.n_min = T::of(config.n_min_n);
        self.n_max = T::of(config.n_max_n);
        self.torsion_factor = T::of(config.torsion_factor());
        self.rise_step = T::of(config.rise_rate_n_per_s * config.tick_period_s);
        self.fall_step = T::of(config.fall_rate_n_per_s * config.tick_period_s);
        self.fault_force = T::of(config.fault_force_n);
        self.force_range = T::of(config.force_range_n);
        self.moment_range = T::of(config.moment_range_nm);
        self.stale_ticks = if ticks >= u32::MAX as f64 {
            u32::MAX
        } else {
            ticks.max(1.0) as u32
        };
        self.lead = Lead::new(&config);
        self.actuator = ActuatorId::new(&config);
        self.slip_response = SlipResponse::new(&config);
        self.command = T::of(config.n_min_n);
        self.last = None;
        self.last_good_us = None;
        self.max_step_us = max_step_us(config.tick_period_s);
        self.period_us = libm::ceil(config.tick_period_s * 1e6).min(1e12) as u64;
        self.resync = None;
        self.time_rejections = 0;
        self.bad_ticks = 0;
        self.slip_node = 0;
        self.config = config;
    }

    /// Takes over a grip already applied by something else (a pre-grip, another
    /// controller, a hand closed by its user): the command starts at `normal_force_n`,
    /// clamped into `[N_min, N_max]`, instead of at `N_min`. From there the rate limits
    /// apply as on any tick, so the first command moves from the existing grip by at most
    /// one tick's rise or fall: no bump. A non-finite force leaves the command where it
    /// is. Call it before the first tick; it keeps the rest of the state. Cost: two
    /// comparisons.
    pub fn start_at(&mut self, normal_force_n: T) {
        if normal_force_n.is_finite() {
            self.command = normal_force_n.max(self.n_min).min(self.n_max);
        }
    }

    /// Takes over from the controller `previous` that this one replaces (a
    /// reconfiguration): the command continues from the previous one (clamped into this
    /// configuration's `[N_min, N_max]`) instead of restarting at `N_min`, so a running
    /// grasp is not released; the timestamp anchor carries over, and so do the slip
    /// response's `μ̂` and margin when `μ` and the tick period are unchanged. From there
    /// the rate limits apply as on any tick.
    pub fn take_over_from<M2>(&mut self, previous: &Controller<T, M2>) {
        self.command = previous.command.max(self.n_min).min(self.n_max);
        // What slip taught about this contact stays, unless the new configuration states
        // a new belief about μ (or a new tick period, which the response counts in).
        if previous.config.mu == self.config.mu
            && previous.config.tick_period_s == self.config.tick_period_s
        {
            self.slip_response = previous.slip_response.clone();
        }
        // The actuator is the same hardware: what was identified of it stays, unless the
        // tick period (which the identifier counts in) changed.
        if previous.config.tick_period_s == self.config.tick_period_s {
            self.actuator = previous.actuator.clone();
        }
        self.last_good_us = previous.last_good_us;
        self.resync = previous.resync;
        self.time_rejections = previous.time_rejections;
        if let Some(last) = previous.last {
            self.last = Some(TickOutput {
                command_n: self.command,
                ..last
            });
        }
    }
}
