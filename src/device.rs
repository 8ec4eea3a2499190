//! The device side of the link: the firmware loop that serves the [`protocol`](crate::protocol) over any
//! byte stream and drives the grip actuator.
//!
//! [`Device`] owns the controller (built from a [`Request::Configure`]), the frame decoder
//! and the counters of [`Stats`]. It is the same code on the Cortex-M4F (over a USART) and
//! in `host-sim` (over a pseudo-terminal, on a thread of its own), so the two links give
//! the same answers. The loop is generic over
//! - the stream: [`embedded_io::Read`] + [`embedded_io::Write`];
//! - the actuator: any [`ForceActuator`], for example [`PwmForce`] over an
//!   `embedded-hal` `SetDutyCycle` channel (the firmware's `board` build drives TIM3's
//!   channel 1 through it);
//! - the cost clock: a [`CostClock`] that reads a cycle or instruction counter (TIM2 under
//!   QEMU) or a host clock, to account for each tick's cost.
//!
//! The tick runs in f32 (the M4F's hardware precision) with the math backend `M`. Where
//! the controller's tables come from is `S`, a [`ControllerSource`]: precomputed at
//! start-up in f32 ([`Precompute`], the default) or f64, or prebuilt on the host and
//! linked into flash ([`Prebuilt`], no start-up cost, and none of the limit-surface code
//! in the binary).
//!
//! **Silence.** A sensor frame ticks the controller; so must the lack of one, or a dead
//! link would hold the last command for ever. The loop calls [`Device::idle_tick`] once
//! for every tick period that passes with no sensor frame, timed on its own clock by a
//! [`SilenceWatch`] (the firmware on TIM2, the host's device thread on `Instant`). After
//! `stale_timeout_s` of silence the controller moves its command, at its rate limit, to
//! the fault target (never below the last required force: see
//! [`crate::controller::Controller`]), and the actuator follows. A host that
//! comes back sees it in [`Stats`]: `idle_ticks`, `command_n`, `fault_active`. Only sensor
//! frames count: `GetStats` and the like do not feed the controller. A lockstep simulation
//! turns this off with [`Request::SetPacing`]`(`[`Pacing::Lockstep`]`)`: its frames are
//! then the device's only clock.

mod pwm;
mod silence;
mod source;

pub use pwm::PwmForce;
pub use silence::SilenceWatch;
pub use source::{ControllerSource, Prebuilt, Precompute};

use crate::controller::{Controller, ControllerConfig, Libm, Measurement, TickMath};
use crate::protocol::{
    encode, CommandFrame, CostUnit, DefaultFrameDecoder, Pacing, Reply, Request, SensorFrame,
    Stats, WireConfigError, MAX_FRAME_LEN, PROTOCOL_VERSION, SCHEMA_KEY,
};
use crate::real::Real;

/// Where the commanded normal force goes.
pub trait ForceActuator {
    /// Applies the commanded normal force \[N\] (finite, within `[N_min, N_max]`).
    fn set_force_n(&mut self, force_n: f32);
}

/// No actuator: the command only travels back over the link.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoActuator;

impl ForceActuator for NoActuator {
    fn set_force_n(&mut self, _force_n: f32) {}
}

/// A free-running counter for cost accounting.
pub trait CostClock {
    /// What one count is.
    const UNIT: CostUnit;
    /// The present count (wrapping).
    fn now(&mut self) -> u32;
}

/// No clock: every cost reads 0.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoClock;

impl CostClock for NoClock {
    const UNIT: CostUnit = CostUnit::Cycles;
    fn now(&mut self) -> u32 {
        0
    }
}

/// The device: controller, decoder and counters. See the module docs.
#[derive(Debug)]
pub struct Device<M = Libm, S = Precompute<f32>> {
    // Two slots: a new configuration is built into the one not running, so a refused
    // configuration leaves the running controller untouched, and neither is ever copied.
    slots: [Option<Controller<f32, M>>; 2],
    active: Option<usize>,
    source: S,
    #[cfg(feature = "stack-probe")]
    stack_probe: fn() -> u32,
    shutdown: Option<u8>,
    incompatible: bool,
    pacing: Pacing,
    decoder: DefaultFrameDecoder,
    frames_sent: u32,
    ticks: u32,
    idle_ticks: u32,
    worst_tick_cost: u32,
    last_tick_cost: u32,
    startup_cost: u32,
    tx: [u8; MAX_FRAME_LEN],
}

impl<M: TickMath<f32>, P: Real> Default for Device<M, Precompute<P>> {
    fn default() -> Self {
        Self::new()
    }
}

/// `a == b`, out of line: inlined into the device loop, each of the configuration's f64
/// comparisons (a soft-float call) spilled the loop's FPU registers around it, about
/// 60 bytes of flash a field (docs/decisions/firmware-size-levers.md).
#[inline(never)]
fn same_config(a: &ControllerConfig, b: &ControllerConfig) -> bool {
    a == b
}

#[cfg(feature = "stack-probe")]
fn no_stack_probe() -> u32 {
    0
}

impl<M: TickMath<f32>, P: Real> Device<M, Precompute<P>> {
    /// An unconfigured device that precomputes its tables in `P`: it answers sensor
    /// frames with [`Reply::NotConfigured`] until a configuration is accepted.
    #[inline(always)]
    pub fn new() -> Self {
        Self::with_source(Precompute::default())
    }
}

impl<M: TickMath<f32>, S: ControllerSource<M>> Device<M, S> {
    /// An unconfigured device whose controllers come from `source`.
    #[inline(always)]
    pub fn with_source(source: S) -> Self {
        Self {
            slots: [None, None],
            active: None,
            source,
            #[cfg(feature = "stack-probe")]
            stack_probe: no_stack_probe,
            shutdown: None,
            incompatible: false,
            pacing: Pacing::RealTime,
            decoder: DefaultFrameDecoder::new(),
            frames_sent: 0,
            ticks: 0,
            idle_ticks: 0,
            worst_tick_cost: 0,
            last_tick_cost: 0,
            startup_cost: 0,
            tx: [0; MAX_FRAME_LEN],
        }
    }

    /// Reports the stack's high-water mark in [`Stats::stack_peak_bytes`] with `probe`
    /// (the firmware paints its stack at start-up and scans it). Only with the feature
    /// `stack-probe`, which the firmware alone enables: without it the field is 0 (a host
    /// thread's stack is not the device's). Set in place: a device is several KB, and a
    /// microcontroller's start-up should not move it.
    #[cfg(feature = "stack-probe")]
    pub fn set_stack_probe(&mut self, probe: fn() -> u32) {
        self.stack_probe = probe;
    }

    /// The exit code of a [`Request::Shutdown`], once one has been answered.
    pub fn shutdown_requested(&self) -> Option<u8> {
        self.shutdown
    }

    /// The controller, once configured.
    pub fn controller(&self) -> Option<&Controller<f32, M>> {
        self.active.and_then(|i| self.slots.get(i)?.as_ref())
    }

    fn controller_mut(&mut self) -> Option<&mut Controller<f32, M>> {
        self.active.and_then(|i| self.slots.get_mut(i)?.as_mut())
    }

    /// The counters, as [`Request::GetStats`] reports them.
    pub fn stats<C: CostClock>(&self) -> Stats {
        let c = self.decoder.counters();
        Stats {
            frames_received: c.frames_received,
            crc_errors: c.crc_errors,
            decode_errors: c.decode_errors,
            overruns: c.overruns,
            frames_sent: self.frames_sent,
            ticks: self.ticks,
            worst_tick_cost: self.worst_tick_cost,
            last_tick_cost: self.last_tick_cost,
            startup_cost: self.startup_cost,
            #[cfg(feature = "stack-probe")]
            stack_peak_bytes: (self.stack_probe)(),
            #[cfg(not(feature = "stack-probe"))]
            stack_peak_bytes: 0,
            cost_unit: C::UNIT,
            stale_frames: self.controller().map_or(0, Controller::time_rejections),
            idle_ticks: self.idle_ticks,
            command_n: self.controller().map_or(0.0, Controller::command_n),
            fault_active: self.controller().is_some_and(Controller::fault_active),
        }
    }

    /// Sensor frames ticked so far (saturating; what [`Stats::ticks`] reports). A loop
    /// hands it to [`SilenceWatch::due`] to tell frames from silence.
    pub fn ticks(&self) -> u32 {
        self.ticks
    }

    /// What paces the controller ([`Request::SetPacing`]; [`Pacing::RealTime`] from the
    /// start).
    pub fn pacing(&self) -> Pacing {
        self.pacing
    }

    /// The tick period of the running configuration \[s\], `None` before one is accepted.
    pub fn tick_period_s(&self) -> Option<f64> {
        self.controller().map(|c| c.config().tick_period_s)
    }

    /// One tick period passed with no sensor frame: ticks the controller with no
    /// measurement ([`Controller::idle`](crate::controller::Controller::idle)) and drives
    /// `actuator` with the resulting command, which after the stale timeout heads for the
    /// fault target. Counted in [`Stats::idle_ticks`]. Returns the command \[N\], or `None`
    /// (and does nothing) before a configuration. Cost: a few comparisons.
    pub fn idle_tick<A: ForceActuator>(&mut self, actuator: &mut A) -> Option<f32> {
        let ctl = self.controller_mut()?;
        let out = ctl.idle();
        actuator.set_force_n(out.command_n);
        self.idle_ticks = self.idle_ticks.saturating_add(1);
        #[cfg(feature = "defmt")]
        if out.fault_active {
            defmt::trace!("idle tick: {=f32} N, fault", out.command_n);
        }
        Some(out.command_n)
    }

    /// Answers one request, driving `actuator` on sensor frames. Never fails: a bad
    /// configuration is answered with the error and leaves the previous controller (if
    /// any) in place.
    pub fn handle<A: ForceActuator, C: CostClock>(
        &mut self,
        request: Request,
        actuator: &mut A,
        clock: &mut C,
    ) -> Reply {
        let incompatible = Reply::Incompatible {
            version: PROTOCOL_VERSION,
            schema_key: SCHEMA_KEY,
        };
        match request {
            Request::Hello {
                version,
                schema_key,
            } => {
                self.incompatible = version != PROTOCOL_VERSION || schema_key != SCHEMA_KEY;
                if self.incompatible {
                    #[cfg(feature = "defmt")]
                    defmt::warn!("incompatible host: protocol {=u16}", version);
                    incompatible
                } else {
                    Reply::hello()
                }
            }
            Request::Configure(_) | Request::Sensor(_) if self.incompatible => incompatible,
            Request::Configure(cfg)
                if self
                    .controller()
                    .is_some_and(|c| same_config(c.config(), &cfg)) =>
            {
                // The same configuration again: nothing to rebuild, nothing changes.
                Reply::Configured(Ok(()))
            }
            Request::Configure(cfg) => self.configure(cfg, actuator, clock),
            Request::Sensor(frame) => self.tick(frame, actuator, clock),
            Request::Shutdown { code } => {
                self.shutdown = Some(code);
                Reply::ShuttingDown { code }
            }
            Request::GetStats => Reply::Stats(self.stats::<C>()),
            Request::SetPacing(pacing) => {
                self.pacing = pacing;
                Reply::Paced(pacing)
            }
            Request::ResetStats => {
                self.decoder.reset_counters();
                self.frames_sent = 0;
                self.ticks = 0;
                self.idle_ticks = 0;
                self.worst_tick_cost = 0;
                self.last_tick_cost = 0;
                Reply::Stats(self.stats::<C>())
            }
        }
    }

    /// Builds the controller for `cfg` (a new configuration) into the slot that is not
    /// running and, if it is accepted, hands the running grasp over to it. Out of line:
    /// inlined into [`Device::poll`], the precomputation's temporaries would sit in the
    /// loop's stack frame for good, not only while configuring.
    #[inline(never)]
    fn configure<A: ForceActuator, C: CostClock>(
        &mut self,
        cfg: ControllerConfig,
        actuator: &mut A,
        clock: &mut C,
    ) -> Reply {
        let next = match self.active {
            Some(0) => 1,
            _ => 0,
        };
        let [first, second] = &mut self.slots;
        let (slot, running) = if next == 0 {
            (first, second)
        } else {
            (second, first)
        };
        let start = clock.now();
        if slot.is_none() {
            Controller::blank_into(slot);
        }
        let Some(slot) = slot.as_mut() else {
            return Reply::Configured(Err(WireConfigError::text("device", "no controller slot")));
        };
        let built = self.source.build_into(cfg, slot);
        let cost = clock.now().wrapping_sub(start);
        match built {
            Ok(()) => {
                // A running grasp is handed over, not released.
                if let Some(running) = running.as_ref().filter(|_| self.active.is_some()) {
                    slot.take_over_from(running);
                }
                actuator.set_force_n(slot.command_n());
                self.active = Some(next);
                self.startup_cost = cost;
                #[cfg(feature = "defmt")]
                defmt::info!("configured: start-up cost {=u32}", cost);
                Reply::Configured(Ok(()))
            }
            Err(e) => {
                #[cfg(feature = "defmt")]
                defmt::warn!("configuration refused: {=str}", e.param.as_str());
                Reply::Configured(Err(e))
            }
        }
    }

    fn tick<A: ForceActuator, C: CostClock>(
        &mut self,
        frame: SensorFrame,
        actuator: &mut A,
        clock: &mut C,
    ) -> Reply {
        let Some(ctl) = self.controller_mut() else {
            return Reply::NotConfigured { seq: frame.seq };
        };
        let m = Measurement::from(&frame);
        let start = clock.now();
        let out = ctl.tick(&m);
        let cost = clock.now().wrapping_sub(start);
        actuator.set_force_n(out.command_n);
        self.ticks = self.ticks.saturating_add(1);
        self.last_tick_cost = cost;
        self.worst_tick_cost = self.worst_tick_cost.max(cost);
        #[cfg(feature = "defmt")]
        defmt::trace!(
            "tick {=u32}: {=f32} N, {}",
            frame.seq,
            out.command_n,
            out.status
        );
        Reply::Command(CommandFrame {
            seq: frame.seq,
            normal_force_n: out.command_n,
            n_slip_n: out.n_slip_n,
            utilisation: out.utilisation,
            status: out.status,
            fault_active: out.fault_active,
            tick_cost: cost,
            mu_estimate: out.mu_estimate,
            margin: out.margin,
            load_factor: out.load_factor,
            lead_n: out.lead_n,
        })
    }

    /// Reads once from `io` (blocking until at least one byte arrives, as
    /// [`embedded_io::Read`] does), answers every complete request in what arrived, and
    /// writes the replies. Returns the number of bytes read (0 at the end of the stream).
    /// Corrupt frames are counted by the decoder and get no reply.
    pub fn poll<IO, A, C>(
        &mut self,
        io: &mut IO,
        actuator: &mut A,
        clock: &mut C,
    ) -> Result<usize, IO::Error>
    where
        IO: embedded_io::Read + embedded_io::Write,
        A: ForceActuator,
        C: CostClock,
    {
        let mut rx = [0u8; 64];
        let n = io.read(&mut rx)?;
        let bytes = rx.get(..n).unwrap_or_default();
        for &byte in bytes {
            let Some(Ok(request)) = self.decoder.push::<Request>(byte) else {
                continue;
            };
            let reply = self.handle(request, actuator, clock);
            if let Ok(len) = encode(&reply, &mut self.tx) {
                io.write_all(self.tx.get(..len).unwrap_or_default())?;
                io.flush()?;
                self.frames_sent = self.frames_sent.saturating_add(1);
            }
            if self.shutdown.is_some() {
                // Whatever follows a shutdown is not read.
                break;
            }
        }
        Ok(n)
    }

    /// Serves `io` until the stream ends (a read of 0 bytes), fails, or a
    /// [`Request::Shutdown`] has been answered.
    pub fn run<IO, A, C>(
        &mut self,
        io: &mut IO,
        actuator: &mut A,
        clock: &mut C,
    ) -> Result<(), IO::Error>
    where
        IO: embedded_io::Read + embedded_io::Write,
        A: ForceActuator,
        C: CostClock,
    {
        while self.poll(io, actuator, clock)? > 0 && self.shutdown.is_none() {}
        Ok(())
    }
}
