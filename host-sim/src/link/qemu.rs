//! The firmware in QEMU: boots the Cortex-M4F build on the `netduinoplus2` machine with
//! its USART on a host pseudo-terminal (`-serial pty`) and instructions counted exactly
//! (`-icount shift=0`), and talks to it over that pty (docs/firmware.md) with the serial
//! link a board uses ([`SerialLink`]).

use super::serial::{SerialLink, DEFAULT_BAUD};
use super::{Link, LinkError};
use softgrip::protocol::{DecoderCounters, Pacing, Reply, Request};
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// Where `scripts/firmware-setup.sh` unpacks QEMU, and where `scripts/firmware-build.sh`
/// puts the default firmware, relative to the repository root.
pub fn default_paths() -> (PathBuf, PathBuf) {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    (root.join(".firmware/qemu"), firmware("default"))
}

/// Where `scripts/firmware-build.sh VARIANT` puts that firmware (`default`,
/// `prebuilt-tables`, `sqrt-check`, ...).
pub fn firmware(variant: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../target/firmware")
        .join(variant)
        .join("softgrip-firmware.elf")
}

/// The emulator under `qemu_dir` (where `scripts/firmware-setup.sh` unpacked it).
pub fn binary(qemu_dir: &Path) -> PathBuf {
    qemu_dir.join("usr/bin/qemu-system-arm")
}

/// Whether QEMU (in [`default_paths`]) and the firmware of every variant in `variants`
/// (see [`firmware`]) are there.
pub fn available(variants: &[&str]) -> bool {
    binary(&default_paths().0).exists() && variants.iter().all(|v| firmware(v).exists())
}

/// A running emulator and the link to its firmware.
#[derive(Debug)]
pub struct QemuLink {
    child: Child,
    serial: SerialLink,
}

fn io(e: impl std::fmt::Display) -> LinkError {
    LinkError::Io(std::io::Error::other(e.to_string()))
}

/// The QEMU command that runs `elf` on the emulated STM32F405 (`netduinoplus2`,
/// Cortex-M4) with semihosting (the firmware's exit code), its USART on `serial` (`pty`,
/// `null`, ...), and with `count_instructions` QEMU's `-icount shift=0` (one instruction
/// a nanosecond: TIM2 then counts instructions). `qemu_dir` is where
/// `scripts/firmware-setup.sh` unpacked QEMU and its libraries.
pub fn command(qemu_dir: &Path, elf: &Path, serial: &str, count_instructions: bool) -> Command {
    let libs = format!(
        "{}:{}",
        qemu_dir.join("usr/lib/x86_64-linux-gnu").display(),
        qemu_dir.join("lib/x86_64-linux-gnu").display()
    );
    let mut cmd = Command::new(binary(qemu_dir));
    cmd.env("LD_LIBRARY_PATH", libs).args([
        "-machine",
        "netduinoplus2",
        "-cpu",
        "cortex-m4",
        "-nographic",
        "-monitor",
        "none",
        "-semihosting-config",
        "enable=on,target=native",
    ]);
    if count_instructions {
        cmd.args(["-icount", "shift=0"]);
    }
    cmd.args(["-serial", serial, "-kernel"]).arg(elf);
    cmd
}

/// Starts QEMU on `elf` with its USART on a new pseudo-terminal, and returns the process
/// and the pty's path (for [`SerialLink`], or `simulate --link serial --port PATH`).
pub fn start(qemu_dir: &Path, elf: &Path) -> Result<(Child, String), LinkError> {
    let bin = binary(qemu_dir);
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
    spawn_on_pty(command(qemu_dir, elf, "pty", true))
}

/// Spawns a QEMU `cmd` whose serial port is `pty` (e.g. [`command`]'s, with arguments of
/// the caller's added) and returns the process and the pseudo-terminal QEMU names, or an
/// error (the process killed) if it names none within 10 s.
pub fn spawn_on_pty(mut cmd: Command) -> Result<(Child, String), LinkError> {
    let mut child = cmd
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
    Ok((child, path))
}

impl QemuLink {
    /// Boots `elf` in the QEMU unpacked under `qemu_dir`, shakes hands with it and sets
    /// it to lockstep ([`Pacing::Lockstep`]: what `simulate` and the comparisons with the
    /// host use, since QEMU's virtual time runs at its own pace).
    pub fn boot(qemu_dir: &Path, elf: &Path) -> Result<Self, LinkError> {
        Self::boot_paced(qemu_dir, elf, Pacing::Lockstep)
    }

    /// Boots `elf` as [`QemuLink::boot`] does, paced by `pacing`.
    pub fn boot_paced(qemu_dir: &Path, elf: &Path, pacing: Pacing) -> Result<Self, LinkError> {
        let (mut child, path) = start(qemu_dir, elf)?;
        // QEMU notices an opened pty only after a while: the serial link's handshake
        // retries.
        match SerialLink::open(Path::new(&path), DEFAULT_BAUD, pacing) {
            Ok(serial) => Ok(Self { child, serial }),
            Err(e) => {
                let _ = child.kill();
                let _ = child.wait();
                Err(e)
            }
        }
    }

    /// Asks the firmware to stop with `code` and returns QEMU's exit code.
    pub fn shutdown(mut self, code: u8) -> Result<i32, LinkError> {
        match self.exchange(&Request::Shutdown { code }) {
            Ok(Reply::ShuttingDown { .. }) => {}
            Ok(other) => return Err(LinkError::Unexpected(Box::new(other))),
            Err(e) => {
                // A closed line means QEMU has exited. The firmware answers and exits at
                // once, and QEMU closes the pty as it ends, which can drop the answer
                // before it is read: an exit with the requested code is the answer.
                std::thread::sleep(Duration::from_millis(200));
                let status = self.child.try_wait().ok().flatten();
                if let Some(exit) = status.and_then(|s| s.code()) {
                    if exit == i32::from(code) {
                        return Ok(exit);
                    }
                }
                return Err(io(format!("{e}; QEMU's exit status: {status:?}")));
            }
        }
        self.serial.close();
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
        self.serial.exchange(request)
    }

    /// Writes raw bytes onto the line, outside any exchange: for fault injection.
    fn inject(&mut self, bytes: &[u8]) -> Result<(), LinkError> {
        self.serial.inject(bytes)
    }

    fn counters(&self) -> DecoderCounters {
        self.serial.counters()
    }
}

impl Drop for QemuLink {
    fn drop(&mut self) {
        self.serial.close();
        if self.child.try_wait().ok().flatten().is_none() {
            let _ = self.child.kill();
            let _ = self.child.wait();
        }
    }
}
