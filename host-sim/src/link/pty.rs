//! The default link: the firmware loop on a thread of its own, over a pseudo-terminal.
//!
//! Two pacings ([`Pacing`]): the simulator's lockstep, where the plant's frames are the
//! device's only clock, so results do not depend on how the host is scheduled; and real
//! time, where the device thread also ticks its controller through silence on the wall
//! clock, as the firmware does on its timer.

use super::handed::Handed;
use super::{Framed, Link, LinkError};
use embedded_io_adapters::std::FromStd;
use serialport::TTYPort;
use softgrip::controller::TickMath;
use softgrip::device::{CostClock, Device, NoActuator, SilenceWatch};
use softgrip::protocol::{CostUnit, DecoderCounters, Pacing, Reply, Request};
use std::io::ErrorKind;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

/// Nanoseconds since the device thread started, for the tick cost in [`Stats`].
///
/// [`Stats`]: softgrip::protocol::Stats
#[derive(Debug)]
pub struct HostClock(Instant);

impl HostClock {
    /// A clock counting from `start`.
    pub fn new(start: Instant) -> Self {
        Self(start)
    }
}

impl CostClock for HostClock {
    const UNIT: CostUnit = CostUnit::Nanoseconds;
    fn now(&mut self) -> u32 {
        // Wrapping by design: costs are differences of two readings.
        self.0.elapsed().as_nanos() as u32
    }
}

/// The plant's end of a pseudo-terminal pair whose other end is served by a
/// [`Device`] on its own thread. Dropping the link closes the pty, which ends the thread.
#[derive(Debug)]
pub struct PtyLink {
    framed: Option<Framed<TTYPort>>,
    device: Option<JoinHandle<()>>,
}

impl PtyLink {
    /// Opens the pty pair and starts the device thread with the math backend `M`, in
    /// lockstep ([`Pacing::Lockstep`], what `simulate` and `bench` use).
    pub fn spawn<M: TickMath<f32> + Send + 'static>() -> Result<Self, LinkError> {
        Self::spawn_paced::<M>(Pacing::Lockstep)
    }

    /// Opens the pty pair, starts the device thread with the math backend `M`, shakes
    /// hands and sets `pacing` ([`Link::set_pacing`]).
    pub fn spawn_paced<M: TickMath<f32> + Send + 'static>(
        pacing: Pacing,
    ) -> Result<Self, LinkError> {
        let (mut plant, device_port) =
            TTYPort::pair().map_err(|e| LinkError::Io(std::io::Error::other(e)))?;
        plant
            .set_exclusive(false)
            .map_err(|e| LinkError::Io(std::io::Error::other(e)))?;
        let device = std::thread::Builder::new()
            .name("softgrip-device".into())
            .spawn(move || serve::<M>(device_port))?;
        let mut link = Self {
            framed: Some(Framed::new(plant, Duration::from_secs(5))),
            device: Some(device),
        };
        link.handshake()?;
        link.set_pacing(pacing)?;
        Ok(link)
    }
}

/// The device thread: the firmware's loop with the host's clock. In real time it waits
/// for bytes at most until the next idle deadline, and ticks the controller once per tick
/// period with no sensor frame ([`Device::idle_ticks_due`]), so a silent plant moves the
/// device's command to its fault target as the firmware's would; in lockstep (and before a
/// configuration) the watch is unarmed and it blocks until the plant sends.
fn serve<M: TickMath<f32> + Send + 'static>(port: TTYPort) {
    use serialport::SerialPort;
    let start = Instant::now();
    // Microseconds since the start, wrapping (every 71 minutes; the watch wraps with it).
    let now_us = || start.elapsed().as_micros() as u32;
    let mut io = FromStd::new(port);
    let mut device = Device::<M, Handed<M>>::with_source(Handed::new());
    let mut clock = HostClock(start);
    let mut watch = SilenceWatch::new(1e6);
    loop {
        // Unarmed, nothing is due: block (almost) indefinitely.
        let wait_us = watch.remaining(now_us()).unwrap_or(3_600_000_000);
        let _ = io
            .inner_mut()
            .set_timeout(Duration::from_micros(u64::from(wait_us)));
        match device.poll(&mut io, &mut NoActuator, &mut clock) {
            Ok(0) => return,
            Ok(_) => {}
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::Interrupted) => {}
            // The plant closed its end (EIO on Linux): the session is over.
            Err(_) => return,
        }
        device.idle_ticks_due(&mut watch, now_us(), &mut NoActuator);
    }
}

impl Link for PtyLink {
    fn exchange(&mut self, request: &Request) -> Result<Reply, LinkError> {
        match self.framed.as_mut() {
            Some(framed) => framed.exchange(request),
            None => Err(LinkError::Timeout),
        }
    }

    /// Writes raw bytes onto the line, outside any exchange: for fault-injection tests.
    fn inject(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        use std::io::Write;
        let framed = self.framed.as_mut().ok_or(LinkError::Timeout)?;
        framed.port_mut().write_all(bytes)?;
        Ok(())
    }

    fn counters(&self) -> DecoderCounters {
        self.framed
            .as_ref()
            .map_or(DecoderCounters::default(), Framed::counters)
    }
}

impl Drop for PtyLink {
    fn drop(&mut self) {
        // Close our end first: the device's blocked read then fails and its thread ends.
        self.framed.take();
        if let Some(handle) = self.device.take() {
            let _ = handle.join();
        }
    }
}
