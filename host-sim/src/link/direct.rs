//! The direct link: the same firmware loop ([`Device`]) and the same encoded frames as
//! the pty link, but through an in-memory byte stream on the calling thread. Each
//! exchange encodes the request, feeds its bytes to [`Device::poll`] over an in-memory
//! [`embedded_io`] port, and decodes the reply the device wrote: no pseudo-terminal, no
//! thread, no system call. The answers are bit-identical to the pty link's (the device
//! sees the same bytes); only the wall time differs.

use super::handed::Handed;
use super::pty::HostClock;
use super::{Link, LinkError};
use softgrip::controller::TickMath;
use softgrip::device::{Device, NoActuator};
use softgrip::protocol::{
    encode, DecoderCounters, DefaultFrameDecoder, Reply, Request, MAX_FRAME_LEN,
};
use std::collections::VecDeque;
use std::convert::Infallible;
use std::time::Instant;

/// Both directions of the in-memory line.
#[derive(Debug, Default)]
struct MemoryPort {
    /// Plant to device.
    to_device: VecDeque<u8>,
    /// Device to plant.
    to_plant: Vec<u8>,
}

impl embedded_io::ErrorType for MemoryPort {
    type Error = Infallible;
}

impl embedded_io::Read for MemoryPort {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        let n = buf.len().min(self.to_device.len());
        for (dst, src) in buf.iter_mut().zip(self.to_device.drain(..n)) {
            *dst = src;
        }
        Ok(n)
    }
}

impl embedded_io::Write for MemoryPort {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        self.to_plant.extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}

/// A [`Device`] served on the calling thread through an in-memory byte stream.
pub struct DirectLink<M: TickMath<f32> + Send + 'static> {
    device: Box<Device<M, Handed<M>>>,
    port: MemoryPort,
    clock: HostClock,
    decoder: DefaultFrameDecoder,
    tx: [u8; MAX_FRAME_LEN],
}

impl<M: TickMath<f32> + Send + 'static> std::fmt::Debug for DirectLink<M> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("DirectLink").finish_non_exhaustive()
    }
}

impl<M: TickMath<f32> + Send + 'static> DirectLink<M> {
    /// A fresh device (not configured yet), after the protocol handshake.
    pub fn new() -> Result<Self, LinkError> {
        let mut link = Self {
            device: Box::new(Device::with_source(Handed::new())),
            port: MemoryPort::default(),
            clock: HostClock::new(Instant::now()),
            decoder: DefaultFrameDecoder::new(),
            tx: [0; MAX_FRAME_LEN],
        };
        link.handshake()?;
        Ok(link)
    }

    /// Lets the device read everything on the line.
    fn serve(&mut self) {
        while !self.port.to_device.is_empty() {
            let Ok(n) = self
                .device
                .poll(&mut self.port, &mut NoActuator, &mut self.clock);
            if n == 0 {
                break;
            }
        }
    }
}

impl<M: TickMath<f32> + Send + 'static> Link for DirectLink<M> {
    fn exchange(&mut self, request: &Request) -> Result<Reply, LinkError> {
        let len = encode(request, &mut self.tx)
            .map_err(|e| LinkError::Io(std::io::Error::other(e.to_string())))?;
        self.port.to_device.extend(&self.tx[..len]);
        self.serve();
        // Lockstep: the first reply to decode is ours; anything after it stays queued.
        let mut used = 0;
        let mut reply = None;
        for &b in &self.port.to_plant {
            used += 1;
            if let Some(Ok(r)) = self.decoder.push::<Reply>(b) {
                reply = Some(r);
                break;
            }
        }
        self.port.to_plant.drain(..used);
        reply.ok_or(LinkError::Timeout)
    }

    fn counters(&self) -> DecoderCounters {
        self.decoder.counters()
    }

    fn inject(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        self.port.to_device.extend(bytes);
        self.serve();
        Ok(())
    }
}
