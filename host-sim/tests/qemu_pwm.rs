//! The board build drives the grip actuator (`scripts/firmware-build.sh board`;
//! firmware/src/pwm.rs): every command becomes the duty cycle of TIM3's channel 1, through
//! embedded-hal's `SetDutyCycle` and the core's `device::PwmForce`. QEMU's
//! `netduinoplus2` emulates TIM3, and its compare register reads back, so this test boots
//! the board build with QEMU's machine protocol (QMP) on a Unix socket and reads the
//! timer's registers with the monitor's `xp` (physical memory, read from outside the
//! guest, which never notices):
//!
//! - before a configuration: PWM mode 1 with preload on channel 1, 800 counts a period,
//!   counting, duty 0 (no force);
//! - after each tick: `CCR1` is the commanded force's duty, `force / 20 N` of 800 counts
//!   to nearest;
//! - after silence (real-time pacing, no sensor frame, the command rising to its fault
//!   target on idle ticks): `CCR1` follows the idle ticks' command too.
//!
//! Needs `scripts/firmware-setup.sh` and `scripts/firmware-build.sh board`; compiled as
//! ignored without them (`host-sim/build.rs`) unless `SOFTGRIP_REQUIRE_QEMU=1`.

mod common;

use host_sim::link::serial::{SerialLink, DEFAULT_BAUD};
use host_sim::link::Link;
use softgrip::controller::ControllerConfig;
use softgrip::protocol::{Pacing, Reply, Request, SensorFrame, Stats};
use std::io::{BufRead, BufReader, Write};
use std::os::unix::net::UnixStream;
use std::path::{Path, PathBuf};
use std::process::Child;
use std::time::{Duration, Instant};

/// TIM3's registers on the STM32F405 (RM0090).
const TIM3: u32 = 0x4000_0400;
const CR1: u32 = TIM3;
const CCMR1: u32 = TIM3 + 0x18;
const CCER: u32 = TIM3 + 0x20;
const PSC: u32 = TIM3 + 0x28;
const ARR: u32 = TIM3 + 0x2C;
const CCR1: u32 = TIM3 + 0x34;

/// The board's PWM: 800 counts a period (20 kHz at 16 MHz), 20 N at full duty
/// (firmware/src/pwm.rs, docs/firmware.md).
const PERIOD_COUNTS: u16 = 800;
const FULL_SCALE_N: f32 = 20.0;

/// The duty a commanded force asks for: `force / full scale` of the period, to nearest,
/// within `[0, period]`.
fn duty(force_n: f32) -> u32 {
    let frac = (force_n / FULL_SCALE_N).clamp(0.0, 1.0);
    u32::from(((frac * f32::from(PERIOD_COUNTS) + 0.5) as u16).min(PERIOD_COUNTS))
}

/// QEMU, killed when the test ends however it ends.
struct Emulator(Child);

impl Drop for Emulator {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// QEMU's machine protocol on a Unix socket.
struct Qmp {
    reader: BufReader<UnixStream>,
    writer: UnixStream,
}

impl Qmp {
    /// Connects (QEMU opens the socket as it starts), reads the greeting and leaves
    /// capabilities negotiation.
    fn connect(path: &Path) -> Self {
        let start = Instant::now();
        let stream = loop {
            match UnixStream::connect(path) {
                Ok(s) => break s,
                Err(_) if start.elapsed() < Duration::from_secs(10) => {
                    std::thread::sleep(Duration::from_millis(50));
                }
                Err(e) => panic!("QMP socket {}: {e}", path.display()),
            }
        };
        stream
            .set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
        let mut qmp = Self {
            reader: BufReader::new(stream.try_clone().unwrap()),
            writer: stream,
        };
        let greeting = qmp.line();
        assert!(
            greeting.get("QMP").is_some(),
            "not a QMP greeting: {greeting}"
        );
        qmp.execute(&serde_json::json!({"execute": "qmp_capabilities"}));
        qmp
    }

    fn line(&mut self) -> serde_json::Value {
        let mut line = String::new();
        self.reader.read_line(&mut line).unwrap();
        serde_json::from_str(&line).unwrap_or_else(|e| panic!("QMP sent {line:?}: {e}"))
    }

    /// Sends `command` and returns its `return` value (events in between are skipped).
    fn execute(&mut self, command: &serde_json::Value) -> serde_json::Value {
        writeln!(self.writer, "{command}").unwrap();
        loop {
            let mut reply = self.line();
            if let Some(r) = reply.get_mut("return") {
                return r.take();
            }
            assert!(reply.get("error").is_none(), "QMP {command}: {reply}");
        }
    }

    /// The 32-bit word at physical address `addr`, through the monitor's `xp`.
    fn read_u32(&mut self, addr: u32) -> u32 {
        let line = format!("xp /1wx {addr:#x}");
        let out = self.execute(&serde_json::json!({
            "execute": "human-monitor-command",
            "arguments": {"command-line": line},
        }));
        // "0000000040000434: 0x00000190"
        let text = out.as_str().unwrap_or_default();
        let value = text
            .split_once(": 0x")
            .and_then(|(_, hex)| u32::from_str_radix(hex.trim(), 16).ok());
        value.unwrap_or_else(|| panic!("`{line}` printed {text:?}"))
    }
}

/// Boots `elf` in QEMU with its USART on a pty and QMP on a socket of its own, and
/// opens the serial link (lockstep).
fn boot(qemu: &Path, elf: &Path) -> (Emulator, SerialLink, Qmp) {
    let socket: PathBuf =
        std::env::temp_dir().join(format!("softgrip-qmp-{}.sock", std::process::id()));
    let _ = std::fs::remove_file(&socket);
    let mut cmd = host_sim::link::qemu::command(qemu, elf, "pty", true);
    cmd.arg("-qmp")
        .arg(format!("unix:{},server=on,wait=off", socket.display()));
    let (child, pty) = host_sim::link::qemu::spawn_on_pty(cmd).unwrap();
    let emulator = Emulator(child);
    let qmp = Qmp::connect(&socket);
    let link = SerialLink::open(Path::new(&pty), DEFAULT_BAUD, Pacing::Lockstep).unwrap();
    let _ = std::fs::remove_file(&socket);
    (emulator, link, qmp)
}

fn stats(link: &mut SerialLink) -> Stats {
    match link.exchange(&Request::GetStats).unwrap() {
        Reply::Stats(s) => s,
        other => panic!("no stats: {other:?}"),
    }
}

/// Set up before any configuration: PWM mode 1 with preload on channel 1, output
/// enabled, no prescaler, 800 counts a period, counting, and no force.
fn check_reset_state(qmp: &mut Qmp) {
    assert_eq!(qmp.read_u32(CCMR1) & 0xFF, 0b110 << 4 | 1 << 3, "CCMR1");
    assert_eq!(qmp.read_u32(CCER) & 0b11, 1, "CCER: CC1E, active high");
    assert_eq!(qmp.read_u32(PSC), 0, "PSC");
    assert_eq!(qmp.read_u32(ARR), u32::from(PERIOD_COUNTS) - 1, "ARR");
    assert_eq!(qmp.read_u32(CR1) & 1, 1, "CR1.CEN");
    assert_eq!(qmp.read_u32(CCR1), 0, "no force before a configuration");
}

/// Configures the device with `cfg` (whose `N_max` is the full scale) and checks the duty
/// of its first command; returns that command [N].
fn configure(link: &mut SerialLink, qmp: &mut Qmp, cfg: ControllerConfig) -> f32 {
    assert_eq!(
        f64::from(FULL_SCALE_N),
        cfg.n_max_n,
        "the full scale is the default N_max"
    );
    assert_eq!(
        link.exchange(&Request::Configure(cfg)).unwrap(),
        Reply::Configured(Ok(()))
    );
    let configured = stats(link).command_n;
    assert_eq!(qmp.read_u32(CCR1), duty(configured), "after Configure");
    configured
}

/// The sensor frame of tick `i`: a varying load for 120 ticks, then a light one.
fn load(i: u32) -> SensorFrame {
    let p = i as f32 * 0.09;
    let varying = i < 120;
    SensorFrame {
        seq: i,
        timestamp_us: 1000 * u64::from(i) + 1,
        tangential_force_n: if varying {
            [6.0 * p.sin().abs(), 1.5 * p.cos()]
        } else {
            [0.2, 0.0]
        },
        torsional_moment_nm: if varying { 0.02 * (0.7 * p).sin() } else { 0.0 },
        normal_force_n: if varying { 6.0 + 2.0 * p.cos() } else { 3.0 },
        slip: Default::default(),
    }
}

/// A varying load for 120 ticks, then a light one for 800, so that the command falls
/// (at 20 N/s, from as high as `N_max`) well below the fault force before the silence;
/// every tick's duty is its command's. Returns the distinct duties and the last command
/// [N].
fn tick_through_loads(
    link: &mut SerialLink,
    qmp: &mut Qmp,
    configured: f32,
) -> (std::collections::BTreeSet<u32>, f32) {
    let mut duties = std::collections::BTreeSet::new();
    let mut last = configured;
    for i in 0..920u32 {
        let f = load(i);
        let Reply::Command(cmd) = link.exchange(&Request::Sensor(f)).unwrap() else {
            panic!("no command at tick {i}")
        };
        // The device sets the duty before it sends the command frame.
        let ccr = qmp.read_u32(CCR1);
        assert_eq!(
            ccr,
            duty(cmd.normal_force_n),
            "tick {i}: {} N",
            cmd.normal_force_n
        );
        duties.insert(ccr);
        last = cmd.normal_force_n;
    }
    (duties, last)
}

/// Silence: paced in real time with no sensor frame, the device ticks idle and, after
/// the stale timeout, raises its command towards the fault force. Returns once it is in
/// its fault state a few idle ticks past the timeout, paced in lockstep again.
fn fall_silent_until_the_fault(link: &mut SerialLink, cfg: &ControllerConfig) {
    assert_eq!(
        link.exchange(&Request::SetPacing(Pacing::RealTime))
            .unwrap(),
        Reply::Paced(Pacing::RealTime)
    );
    let stale_ticks = (cfg.stale_timeout_s / cfg.tick_period_s).round() as u32;
    let start = Instant::now();
    loop {
        let s = stats(link);
        if s.fault_active && s.idle_ticks > stale_ticks + 5 {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "no fault after a minute of silence: {s:?}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    // Lockstep again: the idle ticks stop, so the command and the register hold still.
    assert_eq!(
        link.exchange(&Request::SetPacing(Pacing::Lockstep))
            .unwrap(),
        Reply::Paced(Pacing::Lockstep)
    );
}

#[test]
#[cfg_attr(
    no_qemu_board,
    ignore = "needs QEMU and the board firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh board"
)]
fn the_board_build_writes_each_command_into_tim3s_compare_register() {
    let Some((qemu, elf)) = common::qemu_and_firmware("board") else {
        return;
    };
    let (_emulator, mut link, mut qmp) = boot(&qemu, &elf);
    check_reset_state(&mut qmp);

    let cfg = ControllerConfig::default();
    let configured = configure(&mut link, &mut qmp, cfg);
    let (duties, last) = tick_through_loads(&mut link, &mut qmp, configured);
    assert!(
        duties.len() >= 20,
        "the loads should move the duty: {duties:?}"
    );

    assert!(
        f64::from(last) < cfg.fault_force_n,
        "the light load should leave the command below the fault force: {last} N"
    );

    // Silence: the command rises towards the fault force; the duty follows.
    fall_silent_until_the_fault(&mut link, &cfg);
    let idle = stats(&mut link).command_n;
    assert!(
        duty(idle) > duty(last),
        "the fault should have raised the duty: {last} N, then {idle} N"
    );
    assert_eq!(qmp.read_u32(CCR1), duty(idle), "after idle ticks: {idle} N");
    eprintln!(
        "{} distinct duties over the ticks; {last} N ({} counts) at the cut, {idle} N ({} \
         counts) after the fault",
        duties.len(),
        duty(last),
        duty(idle)
    );
}
