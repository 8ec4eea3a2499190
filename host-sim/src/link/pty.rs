//! The default link: the firmware loop on a thread of its own, over a pseudo-terminal.

use super::{Framed, Link, LinkError};
use embedded_io_adapters::std::FromStd;
use serialport::TTYPort;
use softgrip::controller::TickMath;
use softgrip::device::{CostClock, Device, NoActuator};
use softgrip::protocol::{CostUnit, DecoderCounters, Reply, Request};
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
    /// Opens the pty pair and starts the device thread with the math backend `M`.
    pub fn spawn<M: TickMath<f32> + Send + 'static>() -> Result<Self, LinkError> {
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
        Ok(link)
    }
}

fn serve<M: TickMath<f32>>(mut port: TTYPort) {
    use serialport::SerialPort;
    // Block (almost) indefinitely: the plant paces the exchange.
    let _ = port.set_timeout(Duration::from_secs(3600));
    let mut io = FromStd::new(port);
    let mut device = Device::<M>::new();
    let mut clock = HostClock(Instant::now());
    loop {
        match device.poll(&mut io, &mut NoActuator, &mut clock) {
            Ok(0) => return,
            Ok(_) => {}
            Err(e) if matches!(e.kind(), ErrorKind::TimedOut | ErrorKind::Interrupted) => {}
            // The plant closed its end (EIO on Linux): the session is over.
            Err(_) => return,
        }
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
