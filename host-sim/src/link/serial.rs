//! A link over any serial port: a board's USB-serial adapter (`/dev/ttyUSB0`,
//! `/dev/ttyACM0`) or a pseudo-terminal such as QEMU's (`-serial pty`). The firmware's own
//! path; QEMU's link ([`super::qemu`]) is this link on the pty QEMU names.

use super::{Framed, Link, LinkError};
use serialport::TTYPort;
use softgrip::protocol::{DecoderCounters, Pacing, Request};
use std::path::Path;
use std::time::Duration;

/// The firmware's USART speed (docs/firmware.md): 115 200 baud, 8N1.
pub const DEFAULT_BAUD: u32 = 115_200;

/// An open port with a device that has answered the handshake.
#[derive(Debug)]
pub struct SerialLink {
    framed: Option<Framed<TTYPort>>,
}

fn io(e: impl std::fmt::Display) -> LinkError {
    LinkError::Io(std::io::Error::other(e.to_string()))
}

impl SerialLink {
    /// Opens `path` at `baud` (8N1, no flow control), shakes hands (retrying while the
    /// device may not be listening yet: QEMU notices an opened pty only after up to a
    /// second, a board may still be booting) and sets `pacing`. A port that cannot be
    /// opened is an error naming the path.
    pub fn open(path: &Path, baud: u32, pacing: Pacing) -> Result<Self, LinkError> {
        let name = path.to_string_lossy();
        let port = serialport::new(name.as_ref(), baud)
            .timeout(Duration::from_millis(200))
            .open_native()
            .map_err(|e| io(format!("cannot open {}: {e}", path.display())))?;
        let mut link = Self {
            framed: Some(Framed::new(port, Duration::from_millis(300))),
        };
        let mut last = LinkError::Timeout;
        for _ in 0..20 {
            match link.handshake() {
                Ok(()) => {
                    if let Some(f) = link.framed.as_mut() {
                        // Retried hellos may still be answered: let them pass.
                        f.drain(Duration::from_millis(400));
                        f.set_timeout(Duration::from_secs(30));
                    }
                    link.set_pacing(pacing)?;
                    return Ok(link);
                }
                Err(LinkError::Timeout) => last = LinkError::Timeout,
                Err(e) => return Err(e),
            }
        }
        Err(match last {
            LinkError::Timeout => io(format!(
                "no device answered on {} at {baud} baud",
                path.display()
            )),
            other => other,
        })
    }

    /// Closes the port.
    pub fn close(&mut self) {
        self.framed.take();
    }
}

impl Link for SerialLink {
    fn exchange(&mut self, request: &Request) -> Result<softgrip::protocol::Reply, LinkError> {
        match self.framed.as_mut() {
            Some(f) => f.exchange(request),
            None => Err(LinkError::Timeout),
        }
    }

    /// Writes raw bytes onto the line, outside any exchange: for fault injection.
    fn inject(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        use std::io::Write;
        let f = self.framed.as_mut().ok_or(LinkError::Timeout)?;
        f.port_mut().write_all(bytes)?;
        Ok(())
    }

    fn counters(&self) -> DecoderCounters {
        self.framed
            .as_ref()
            .map_or(DecoderCounters::default(), Framed::counters)
    }
}
