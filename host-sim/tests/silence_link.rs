//! Silence on the real paths (issue 13, item 3): cut the link mid-hold and the device
//! moves its command on its own, at its rate limit, to the fault target — never below the
//! last required force — within the stale timeout plus the rate-limited travel.
//!
//! Both the host's device thread behind the pty (paced in real time, as the firmware is)
//! and the firmware in QEMU. After the cut
//! the plant sends no sensor frame; it reads the device's command with `GetStats` (which
//! does not feed the controller) every few milliseconds, and once with nothing at all
//! sent for a while.
//!
//! How time is measured: in the device's own tick periods, `Stats::idle_ticks` — each is
//! one tick period of the device's timer that passed with no sensor frame (the host's
//! `Instant` for the pty; TIM2 under QEMU, which with `-icount shift=0` counts executed
//! instructions as virtual nanoseconds, so QEMU's virtual time runs at its own pace, not
//! the wall clock's). The bound is on idle ticks: `stale_ticks + ceil(travel / step)`.
//! Wall time is printed, and bounded (generously) only on the pty, whose clock is the
//! wall clock.
//!
//! The QEMU test needs `scripts/firmware-setup.sh` and `scripts/firmware-build.sh`;
//! without them it is compiled as ignored (`host-sim/build.rs`), unless
//! `SOFTGRIP_REQUIRE_QEMU=1` (as `.ci/run` sets it).

use host_sim::link::pty::PtyLink;
use host_sim::link::qemu::QemuLink;

mod common;
use host_sim::link::Link;
use softgrip::controller::{Controller, ControllerConfig, Libm, Measurement};
use softgrip::protocol::{Pacing, Reply, Request, SensorFrame, Stats};
use std::time::{Duration, Instant};

fn stats(link: &mut dyn Link) -> Stats {
    match link.exchange(&Request::GetStats).unwrap() {
        Reply::Stats(s) => s,
        other => panic!("{other:?}"),
    }
}

/// A hold: 400 frames of a heavy load, then 40 of a lighter one, so the command is above
/// the last requirement and falling at the cut.
fn frame(i: u32) -> SensorFrame {
    let (f, m) = if i < 400 { (3.0, 0.01) } else { (2.0, 0.006) };
    SensorFrame {
        seq: i,
        timestamp_us: 1000 * u64::from(i) + 1,
        tangential_force_n: [f, 0.0],
        torsional_moment_nm: m,
        normal_force_n: 6.0,
        slip: Default::default(),
    }
}

/// What the cut showed.
struct Cut {
    /// The command at the cut and where it went [N].
    at_cut: f32,
    safe: f32,
    /// Idle ticks when the plant first saw the command at the safe value (it may look
    /// late: the bound is checked at every observation in `follow`), and the bound
    /// (`stale_ticks + ceil(travel / step) + 1`).
    reached_after: u32,
    bound: u32,
    wall: Duration,
    bound_s: f64,
}

/// The hold before the cut.
struct Hold {
    /// The host's own controller on the same frames: it says what the device must reach.
    host: Controller<f32, Libm>,
    /// The device's last command and the last requirement [N].
    at_cut: f32,
    required: f32,
    /// The device's counters just before the last frame.
    before: Stats,
}

/// Configures the device with `cfg` and holds (`frame`), checking every command against
/// the host's own controller.
fn hold(link: &mut dyn Link, cfg: ControllerConfig) -> Hold {
    assert_eq!(
        link.exchange(&Request::Configure(cfg)).unwrap(),
        Reply::Configured(Ok(()))
    );
    // The host's own controller on the same frames says what the device must reach.
    let mut host = Controller::<f32, Libm>::new(cfg).unwrap();
    let mut at_cut = 0.0;
    let mut required = 0.0;
    // Idle ticks are counted from a snapshot just before the last frame; those that fall
    // between the snapshot and that frame (`slack`, usually 0) are not silence.
    let mut before = stats(link);
    for i in 0..440 {
        if i == 439 {
            before = stats(link);
        }
        let f = frame(i);
        let Reply::Command(c) = link.exchange(&Request::Sensor(f)).unwrap() else {
            panic!("no command")
        };
        let want = host.tick(&Measurement {
            tangential_force_n: f.tangential_force_n,
            torsional_moment_nm: f.torsional_moment_nm,
            normal_force_n: f.normal_force_n,
            timestamp_us: f.timestamp_us,
            slip: Default::default(),
        });
        assert_eq!(c.normal_force_n.to_bits(), want.command_n.to_bits());
        at_cut = c.normal_force_n;
        required = want.required_n;
    }
    Hold {
        host,
        at_cut,
        required,
        before,
    }
}

/// The way from the command at the cut to the safe value, and the bound on its idle ticks.
struct Travel {
    safe: f32,
    stale_ticks: u32,
    /// One rate-limited step [N] and the distance to go [N].
    step: f64,
    travel: f64,
    /// `stale_ticks + ceil(travel / step) + 1`.
    bound: u32,
}

impl Travel {
    fn new(cfg: &ControllerConfig, at_cut: f32, safe: f32) -> Self {
        let stale_ticks = (cfg.stale_timeout_s / cfg.tick_period_s).round() as u32;
        let step = if safe > at_cut {
            cfg.rise_rate_n_per_s
        } else {
            cfg.fall_rate_n_per_s
        } * cfg.tick_period_s;
        let travel = f64::from((safe - at_cut).abs());
        // One tick of slack for the tick that arms the deadline.
        let bound = stale_ticks + (travel / step).ceil() as u32 + 1;
        Self {
            safe,
            stale_ticks,
            step,
            travel,
            bound,
        }
    }
}

/// Polls the device every `poll` after the cut (at `cut`, its counters then `after`) until
/// its command reaches the safe value, checking at every observation that it holds, then
/// moves at the rate limit, never below the last requirement; returns the idle ticks and
/// the wall time it took.
fn follow(
    link: &mut dyn Link,
    held: &Hold,
    after: &Stats,
    way: &Travel,
    poll: Duration,
    cut: Instant,
) -> (u32, Duration) {
    let (before, at_cut, required, safe) = (&held.before, held.at_cut, held.required, way.safe);
    let slack = after.idle_ticks - before.idle_ticks;
    let deadline = cut + Duration::from_secs(30);
    while Instant::now() < deadline {
        std::thread::sleep(poll);
        let s = stats(link);
        let idle = s.idle_ticks - before.idle_ticks;
        assert_eq!(s.ticks, after.ticks, "no sensor frame after the cut");
        assert!(
            s.command_n >= required,
            "after {idle} idle ticks the command {} N is below the last requirement {required} N",
            s.command_n
        );
        if idle < way.stale_ticks {
            assert_eq!(s.command_n, at_cut, "held before the stale timeout");
        }
        // At least as far along as `idle - slack` idle ticks allow: held for the stale
        // timeout, then one rate-limited step per tick (this holds however late the
        // plant looks, so the bound is checked in device time, not observation time).
        let moved = (idle.saturating_sub(slack) + 1).saturating_sub(way.stale_ticks);
        let left = (way.travel - way.step * f64::from(moved)).max(0.0);
        assert!(
            f64::from((safe - s.command_n).abs()) <= left + 1e-3,
            "after {idle} idle ticks (slack {slack}) the command {} N is {} N from {safe} N, \
             more than the rate limit leaves ({left} N)",
            s.command_n,
            (safe - s.command_n).abs()
        );
        if s.command_n == safe {
            assert!(s.fault_active);
            return (idle - slack.min(idle), cut.elapsed());
        }
    }
    let s = stats(link);
    panic!(
        "the command never reached {safe} N: {} N after {} idle ticks (held {at_cut} N)",
        s.command_n,
        s.idle_ticks - before.idle_ticks
    );
}

/// Holds, cuts the link, and follows the device's command until it reaches the safe
/// value. `fault_force_n` chooses whether the safe value is the fault force (above the
/// requirement) or the last requirement itself.
fn cut_mid_hold(link: &mut dyn Link, fault_force_n: f64, poll: Duration) -> Cut {
    let cfg = ControllerConfig {
        fault_force_n,
        ..ControllerConfig::default()
    };
    let held = hold(link, cfg);
    let cut = Instant::now();
    let after = stats(link);
    assert!(!after.fault_active);
    assert_eq!(after.ticks, held.before.ticks + 1);
    let (at_cut, required) = (held.at_cut, held.required);
    let safe = held.host.fault_target_n();
    assert!(safe >= required && required > 4.0 * cfg.n_min_n as f32);
    assert!(at_cut > required, "the command is falling at the cut");
    let way = Travel::new(&cfg, at_cut, safe);
    let (reached_after, wall) = follow(link, &held, &after, &way, poll, cut);
    Cut {
        at_cut,
        safe,
        reached_after,
        bound: way.bound,
        wall,
        bound_s: f64::from(way.bound) * cfg.tick_period_s,
    }
}

/// A good frame after the fault ends it; then nothing at all is sent for a while, and the
/// device has still gone to the safe value on its own.
fn silent_then_ask(link: &mut dyn Link, wait: Duration) -> Stats {
    let mut i = 440;
    let mut ticks = stats(link).ticks;
    // Recover (the clock re-anchors after a plausible step) and hold again.
    while i < 480 {
        let mut f = frame(i);
        f.timestamp_us += 10_000_000;
        let Reply::Command(_) = link.exchange(&Request::Sensor(f)).unwrap() else {
            panic!("no command")
        };
        i += 1;
        ticks += 1;
    }
    let s = stats(link);
    assert_eq!(s.ticks, ticks);
    assert!(!s.fault_active, "a good frame ends the fault");
    std::thread::sleep(wait);
    stats(link)
}

fn report(label: &str, c: &Cut) {
    eprintln!(
        "{label}: {} N at the cut -> {} N, seen after {} idle ticks (bound {}, {:.3} s of \
         device time), {:.3} s of wall time",
        c.at_cut,
        c.safe,
        c.reached_after,
        c.bound,
        c.bound_s,
        c.wall.as_secs_f64()
    );
}

#[test]
fn a_cut_pty_link_moves_the_grip_to_its_safe_value_within_the_timeout() {
    let mut link = PtyLink::spawn_paced::<Libm>(Pacing::RealTime).unwrap();
    // The fault force above the requirement: the grip rises to it.
    let up = cut_mid_hold(&mut link, 12.0, Duration::from_millis(2));
    report("pty, fault force 12 N", &up);
    assert_eq!(up.safe, 12.0);
    // The pty's clock is the wall clock: the device gets there in about the bound's time
    // (a loaded machine may be late by scheduling; the idle ticks catch up).
    assert!(up.wall.as_secs_f64() < up.bound_s + 2.0, "{:?}", up.wall);
    // Nothing sent at all for ten times the bound: the device went there on its own.
    let s = silent_then_ask(&mut link, Duration::from_secs_f64(10.0 * up.bound_s));
    assert!(s.fault_active);
    assert_eq!(s.command_n, 12.0);

    // The fault force below the requirement: the grip falls to the last requirement and
    // stays there, never lower.
    let mut link = PtyLink::spawn_paced::<Libm>(Pacing::RealTime).unwrap();
    let down = cut_mid_hold(&mut link, 0.5, Duration::from_millis(2));
    report("pty, fault force 0.5 N", &down);
    assert!(down.safe > 0.5);
    assert!(
        down.wall.as_secs_f64() < down.bound_s + 2.0,
        "{:?}",
        down.wall
    );
    // Long after: still at the requirement, not at the fault force.
    std::thread::sleep(Duration::from_millis(200));
    let s = stats(&mut link);
    assert_eq!(s.command_n, down.safe);
}

#[test]
#[cfg_attr(
    no_qemu,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default"
)]
fn a_cut_uart_moves_the_firmware_grip_to_its_safe_value_within_the_timeout() {
    let Some((qemu_dir, elf)) = common::qemu_and_firmware("default") else {
        return;
    };
    let mut link = QemuLink::boot_paced(&qemu_dir, &elf, Pacing::RealTime).unwrap();
    let up = cut_mid_hold(&mut link, 12.0, Duration::from_millis(5));
    report("QEMU, fault force 12 N", &up);
    assert_eq!(up.safe, 12.0);
    // Nothing sent at all: virtual time runs at QEMU's pace, so wait until the device
    // has counted three times the bound in idle ticks, asking rarely.
    let mut s = silent_then_ask(&mut link, Duration::from_millis(500));
    let start = s.idle_ticks;
    let t0 = Instant::now();
    while s.idle_ticks - start < 3 * up.bound && t0.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(500));
        s = stats(&mut link);
    }
    assert!(s.fault_active);
    assert_eq!(s.command_n, 12.0);

    assert_eq!(link.shutdown(0).unwrap(), 0);

    let mut link = QemuLink::boot_paced(&qemu_dir, &elf, Pacing::RealTime).unwrap();
    let down = cut_mid_hold(&mut link, 0.5, Duration::from_millis(5));
    report("QEMU, fault force 0.5 N", &down);
    assert!(down.safe > 0.5);
    assert_eq!(link.shutdown(0).unwrap(), 0);
}
