//! The firmware in QEMU: boots the Cortex-M4F build on the `netduinoplus2` machine with
//! its USART on a host pseudo-terminal (`-serial pty`) and instructions counted exactly
//! (`-icount shift=0`), and talks to it over that pty (docs/firmware.md).

use super::{Framed, Link, LinkError};
use serialport::TTYPort;
use softgrip::protocol::{DecoderCounters, Reply, Request};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// Where `scripts/firmware-setup.sh` unpacks QEMU, and where `scripts/firmware-build.sh`
/// puts the default firmware, relative to the repository root.
pub fn default_paths() -> (PathBuf, PathBuf) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    (
        root.join(".firmware/qemu"),
        root.join("target/firmware/default/softgrip-firmware.elf"),
    )
}

/// A running emulator and the link to its firmware.
#[derive(Debug)]
pub struct QemuLink {
    child: Child,
    framed: Option<Framed<TTYPort>>,
}

fn io(e: impl std::fmt::Display) -> LinkError {
    LinkError::Io(std::io::Error::other(e.to_string()))
}

impl QemuLink {
    /// Boots `elf` in the QEMU unpacked under `qemu_dir` and shakes hands with it.
    pub fn boot(qemu_dir: &Path, elf: &Path) -> Result<Self, LinkError> {
        let bin = qemu_dir.join("usr/bin/qemu-system-arm");
        if !bin.exists() {
            return Err(io(format!(
                "{} not found: run scripts/firmware-setup.sh",
                bin.display()
            )));
        }
        if !elf.exists() {
            return Err(io(format!(
                "{} not found: run scripts/firmware-build.sh",
                elf.display()
            )));
        }
        let libs = format!(
            "{}:{}",
            qemu_dir.join("usr/lib/x86_64-linux-gnu").display(),
            qemu_dir.join("lib/x86_64-linux-gnu").display()
        );
        let mut child = Command::new(&bin)
            .env("LD_LIBRARY_PATH", libs)
            .args([
                "-machine",
                "netduinoplus2",
                "-cpu",
                "cortex-m4",
                "-nographic",
                "-monitor",
                "none",
                "-semihosting-config",
                "enable=on,target=native",
                "-icount",
                "shift=0",
                "-serial",
                "pty",
                "-kernel",
            ])
            .arg(elf)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()?;
        // QEMU names the pty on stderr (older versions) or stdout.
        let (tx, rx) = std::sync::mpsc::channel();
        for stream in [
            child
                .stdout
                .take()
                .map(|s| Box::new(s) as Box<dyn std::io::Read + Send>),
            child
                .stderr
                .take()
                .map(|s| Box::new(s) as Box<dyn std::io::Read + Send>),
        ]
        .into_iter()
        .flatten()
        {
            let tx = tx.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(stream).lines().map_while(Result::ok) {
                    if let Some(i) = line.find("/dev/pts/") {
                        let path: String = line[i..]
                            .chars()
                            .take_while(|c| !c.is_whitespace() && *c != ')')
                            .collect();
                        let _ = tx.send(path);
                    }
                }
            });
        }
        let path = match rx.recv_timeout(Duration::from_secs(10)) {
            Ok(p) => p,
            Err(_) => {
                let _ = child.kill();
                return Err(io("QEMU did not report its pseudo-terminal"));
            }
        };
        let port = serialport::new(&path, 115_200)
            .timeout(Duration::from_millis(200))
            .open_native()
            .map_err(io)?;
        let mut link = Self {
            child,
            framed: Some(Framed::new(port, Duration::from_millis(300))),
        };
        // QEMU notices the opened pty only after a while: the handshake retries.
        let mut last = LinkError::Timeout;
        for _ in 0..20 {
            match link.handshake() {
                Ok(()) => {
                    if let Some(f) = link.framed.as_mut() {
                        // Retried hellos may still be answered: let them pass.
                        f.drain(Duration::from_millis(400));
                        f.set_timeout(Duration::from_secs(30));
                    }
                    return Ok(link);
                }
                Err(LinkError::Timeout) => last = LinkError::Timeout,
                Err(e) => return Err(e),
            }
        }
        Err(last)
    }

    /// Asks the firmware to stop with `code` and returns QEMU's exit code.
    pub fn shutdown(mut self, code: u8) -> Result<i32, LinkError> {
        match self.exchange(&Request::Shutdown { code }) {
            Ok(Reply::ShuttingDown { .. }) => {}
            Ok(other) => return Err(LinkError::Unexpected(Box::new(other))),
            Err(e) => {
                // Say how QEMU ended, if it did: a closed line means it has exited.
                std::thread::sleep(Duration::from_millis(200));
                let status = self.child.try_wait().ok().flatten();
                return Err(io(format!("{e}; QEMU's exit status: {status:?}")));
            }
        }
        self.framed.take();
        for _ in 0..100 {
            if let Some(status) = self.child.try_wait()? {
                return Ok(status.code().unwrap_or(-1));
            }
            std::thread::sleep(Duration::from_millis(50));
        }
        Err(io("QEMU did not exit after the shutdown request"))
    }
}

impl Link for QemuLink {
    fn exchange(&mut self, request: &Request) -> Result<Reply, LinkError> {
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

impl Drop for QemuLink {
    fn drop(&mut self) {
        self.framed.take();
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}
