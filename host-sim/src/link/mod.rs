//! The plant's side of the serial link to the device running the controller.
//!
//! A [`Link`] sends one [`Request`] and waits for its [`Reply`]: the simulation runs in
//! lockstep with the device, never against the wall clock. [`pty::PtyLink`] is the
//! default, "in-process" link: the firmware loop ([`softgrip::device::Device`]) runs on a
//! thread of its own behind a pseudo-terminal pair, so every frame crosses a real
//! serial device and the same decoder the firmware uses. [`direct::DirectLink`] serves
//! the same device loop with the same bytes on the calling thread, through memory: what
//! `bench` uses by default (bit-identical answers, no pty round trip).

pub mod direct;
pub mod handed;
pub mod pty;
pub mod qemu;
pub mod serial;

use softgrip::protocol::{
    encode, DecoderCounters, DefaultFrameDecoder, Pacing, Reply, Request, MAX_FRAME_LEN,
    PROTOCOL_VERSION, SCHEMA_KEY,
};
use std::fmt;
use std::io::{Read, Write};
use std::time::{Duration, Instant};

/// Why an exchange failed.
#[derive(Debug)]
pub enum LinkError {
    /// The port failed.
    Io(std::io::Error),
    /// No reply within the deadline.
    Timeout,
    /// The device speaks another protocol version or schema.
    Mismatch {
        /// The device's version.
        version: u16,
        /// The device's schema key.
        schema_key: u32,
    },
    /// A reply of the wrong kind.
    Unexpected(Box<Reply>),
}

impl fmt::Display for LinkError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LinkError::Io(e) => write!(f, "serial link: {e}"),
            LinkError::Timeout => write!(f, "serial link: no reply from the device"),
            LinkError::Mismatch {
                version,
                schema_key,
            } => write!(
                f,
                "device speaks protocol {version} (schema {schema_key:#010x}), host speaks \
                 {PROTOCOL_VERSION} ({SCHEMA_KEY:#010x})"
            ),
            LinkError::Unexpected(r) => write!(f, "serial link: unexpected reply {r:?}"),
        }
    }
}

impl std::error::Error for LinkError {}

impl From<std::io::Error> for LinkError {
    fn from(e: std::io::Error) -> Self {
        LinkError::Io(e)
    }
}

/// One request, one reply.
pub trait Link: std::fmt::Debug {
    /// Sends `request` and returns the device's reply.
    fn exchange(&mut self, request: &Request) -> Result<Reply, LinkError>;

    /// What the plant side's decoder has seen (replies received, corrupt, oversized).
    fn counters(&self) -> DecoderCounters;

    /// Writes raw bytes onto the line, outside any exchange (fault injection).
    fn inject(&mut self, bytes: &[u8]) -> Result<(), LinkError>;

    /// Sets what paces the device's controller: [`Pacing::Lockstep`] for a simulation
    /// whose plant is the clock, [`Pacing::RealTime`] (the device's own default) for a
    /// device that must act on a silent link.
    fn set_pacing(&mut self, pacing: Pacing) -> Result<(), LinkError> {
        match self.exchange(&Request::SetPacing(pacing))? {
            Reply::Paced(p) if p == pacing => Ok(()),
            other => Err(LinkError::Unexpected(Box::new(other))),
        }
    }

    /// Checks the device's protocol version and schema, retrying while the device may
    /// not be listening yet (QEMU notices an opened pty only after up to a second).
    fn handshake(&mut self) -> Result<(), LinkError> {
        let mut last = LinkError::Timeout;
        for _ in 0..10 {
            match self.exchange(&Request::hello()) {
                Ok(Reply::Hello {
                    version,
                    schema_key,
                    ..
                }) => {
                    return if version == PROTOCOL_VERSION && schema_key == SCHEMA_KEY {
                        Ok(())
                    } else {
                        Err(LinkError::Mismatch {
                            version,
                            schema_key,
                        })
                    };
                }
                // A device that refuses our protocol says which one it speaks.
                Ok(Reply::Incompatible {
                    version,
                    schema_key,
                }) => {
                    return Err(LinkError::Mismatch {
                        version,
                        schema_key,
                    })
                }
                Ok(other) => last = LinkError::Unexpected(Box::new(other)),
                Err(LinkError::Timeout) => last = LinkError::Timeout,
                Err(e) => return Err(e),
            }
        }
        Err(last)
    }
}

/// The framing half of a link over any byte port: encode, write, read until one reply
/// decodes. Corrupt replies are counted by the decoder and skipped.
#[derive(Debug)]
pub struct Framed<P> {
    port: P,
    decoder: DefaultFrameDecoder,
    tx: [u8; MAX_FRAME_LEN],
    timeout: Duration,
}

impl<P: Read + Write> Framed<P> {
    /// Frames over `port`, waiting at most `timeout` for each reply.
    pub fn new(port: P, timeout: Duration) -> Self {
        Self {
            port,
            decoder: DefaultFrameDecoder::new(),
            tx: [0; MAX_FRAME_LEN],
            timeout,
        }
    }

    /// Changes the reply deadline.
    pub fn set_timeout(&mut self, timeout: Duration) {
        self.timeout = timeout;
    }

    /// The port.
    pub fn port_mut(&mut self) -> &mut P {
        &mut self.port
    }

    /// Sends one request and reads until one reply decodes or the deadline passes.
    pub fn exchange(&mut self, request: &Request) -> Result<Reply, LinkError> {
        let len = encode(request, &mut self.tx)
            .map_err(|e| LinkError::Io(std::io::Error::other(e.to_string())))?;
        self.port.write_all(&self.tx[..len])?;
        self.port.flush()?;
        let deadline = Instant::now() + self.timeout;
        let mut rx = [0u8; 256];
        loop {
            let n = match self.port.read(&mut rx) {
                Ok(0) => return Err(LinkError::Timeout),
                Ok(n) => n,
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => 0,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => 0,
                Err(e) => return Err(e.into()),
            };
            // Lockstep: at most one reply is in flight, so the first one to decode is
            // ours; bytes after it (none in practice) would start the next frame.
            for &b in &rx[..n] {
                if let Some(Ok(reply)) = self.decoder.push::<Reply>(b) {
                    return Ok(reply);
                }
            }
            if Instant::now() >= deadline {
                return Err(LinkError::Timeout);
            }
        }
    }

    /// Reads and discards whatever arrives within `quiet` (late answers to retried
    /// requests), then clears the decoder's partial frame.
    pub fn drain(&mut self, quiet: Duration) {
        let deadline = Instant::now() + quiet;
        let mut rx = [0u8; 256];
        while Instant::now() < deadline {
            match self.port.read(&mut rx) {
                Ok(0) | Err(_) => std::thread::sleep(Duration::from_millis(10)),
                Ok(_) => {}
            }
        }
        self.decoder.clear();
    }

    /// The decoder's counters.
    pub fn counters(&self) -> DecoderCounters {
        self.decoder.counters()
    }
}
