//! Silence (issue 13, item 3): when no measurement arrives, the controller's idle ticks
//! move the command to its fault target, which is never below the last required force,
//! and `Device::idle_tick` drives the actuator there and reports it in `Stats`.
//!
//! The pty and QEMU paths are tested in `host-sim/tests/silence_link.rs`.

use softgrip::controller::{Controller, ControllerConfig, Measurement, Status};
use softgrip::device::{Device, ForceActuator, NoClock};
use softgrip::protocol::{Reply, Request, SensorFrame};

/// A load whose required force is well above `N_min`: 3 N tangential, 10 mN·m of torsion.
const LOAD: (f32, f32) = (3.0, 0.01);

fn hold(c: &mut Controller<f32>, ticks: u64) -> (f32, f32) {
    let mut out = None;
    for t in 1..=ticks {
        out = Some(c.tick(&Measurement {
            tangential_force_n: [LOAD.0, 0.0],
            torsional_moment_nm: LOAD.1,
            normal_force_n: 6.0,
            timestamp_us: t * 1000,
            slip: Default::default(),
        }));
    }
    let out = out.unwrap();
    assert_eq!(out.status, Status::Ok);
    (out.command_n, out.required_n)
}

fn stale_ticks(cfg: &ControllerConfig) -> u32 {
    (cfg.stale_timeout_s / cfg.tick_period_s).round() as u32
}

/// With a fault force below the load's requirement, silence must not lower the grip below
/// the last required force: the fault target is `max(fault_force_n, N_req)`.
#[test]
fn a_silent_link_never_lowers_the_grip_below_the_last_requirement() {
    let cfg = ControllerConfig {
        fault_force_n: 0.5,
        ..ControllerConfig::default()
    };
    let mut c = Controller::<f32>::new(cfg).unwrap();
    let (held, required) = hold(&mut c, 500);
    assert!(
        required > 2.0 * cfg.n_min_n as f32 && required > cfg.fault_force_n as f32,
        "{required}"
    );
    assert!(held >= required, "{held} < {required}");
    for i in 1..=5000u32 {
        let o = c.idle();
        assert!(
            o.command_n >= required,
            "idle tick {i}: {} < the last required {required}",
            o.command_n
        );
        assert_eq!(o.fault_active, i >= stale_ticks(&cfg), "idle tick {i}");
    }
    assert_eq!(c.command_n(), required);
    assert_eq!(c.fault_target_n(), required);
}

/// With a fault force above the requirement, the command rises to it at the rise rate
/// once the stale timeout has passed: within `stale_ticks + ceil(Δ/rise_step)` idle ticks.
#[test]
fn a_silent_link_raises_the_grip_to_the_fault_force_within_the_timeout_and_rise_time() {
    let cfg = ControllerConfig {
        fault_force_n: 15.0,
        rise_rate_n_per_s: 100.0,
        ..ControllerConfig::default()
    };
    let mut c = Controller::<f32>::new(cfg).unwrap();
    let (held, required) = hold(&mut c, 500);
    assert!(required < 15.0);
    let rise_ticks =
        ((15.0 - f64::from(held)) / (cfg.rise_rate_n_per_s * cfg.tick_period_s)).ceil() as u32;
    let bound = stale_ticks(&cfg) + rise_ticks;
    let mut reached = None;
    for i in 1..=bound + 100 {
        let o = c.idle();
        assert!(o.command_n >= held, "idle tick {i}");
        if o.command_n == 15.0 && reached.is_none() {
            reached = Some(i);
        }
    }
    let reached = reached.expect("never reached the fault force");
    assert!(reached <= bound, "{reached} idle ticks > {bound}");
}

#[derive(Default)]
struct Recorder(Vec<f32>);

impl ForceActuator for Recorder {
    fn set_force_n(&mut self, force_n: f32) {
        self.0.push(force_n);
    }
}

/// `Device::idle_tick` ticks the controller, drives the actuator with each new command and
/// reports the silence in `Stats`; a sensor frame ends it.
#[test]
fn the_device_drives_its_actuator_through_silence_and_reports_it() {
    let cfg = ControllerConfig {
        fault_force_n: 0.5,
        ..ControllerConfig::default()
    };
    let mut device = Device::<softgrip::controller::Libm>::new();
    let mut act = Recorder::default();
    let mut clock = NoClock;
    assert_eq!(device.idle_tick(&mut act), None, "no controller yet");
    assert!(act.0.is_empty());
    device.handle(Request::hello(), &mut act, &mut clock);
    assert_eq!(
        device.handle(Request::Configure(cfg), &mut act, &mut clock),
        Reply::Configured(Ok(()))
    );
    let sensor = |seq: u32| SensorFrame {
        seq,
        timestamp_us: u64::from(seq + 1) * 1000,
        tangential_force_n: [LOAD.0, 0.0],
        torsional_moment_nm: LOAD.1,
        normal_force_n: 6.0,
        slip: Default::default(),
    };
    for seq in 0..500 {
        device.handle(Request::Sensor(sensor(seq)), &mut act, &mut clock);
    }
    let required = device.controller().unwrap().fault_target_n();
    let before = act.0.len();
    for _ in 0..2000 {
        device.idle_tick(&mut act).unwrap();
    }
    assert_eq!(
        act.0.len(),
        before + 2000,
        "one actuator command per idle tick"
    );
    assert!(act.0[before..].iter().all(|&f| f >= required));
    assert_eq!(*act.0.last().unwrap(), required);
    let Reply::Stats(s) = device.handle(Request::GetStats, &mut act, &mut clock) else {
        panic!()
    };
    assert_eq!((s.ticks, s.idle_ticks), (500, 2000));
    assert_eq!(s.command_n, required);
    assert!(s.fault_active);
    let Reply::Command(c) = device.handle(Request::Sensor(sensor(600)), &mut act, &mut clock)
    else {
        panic!()
    };
    assert!(!c.fault_active);
    let Reply::Stats(s) = device.handle(Request::GetStats, &mut act, &mut clock) else {
        panic!()
    };
    assert!(!s.fault_active);
}
