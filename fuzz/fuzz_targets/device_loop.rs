//! The device loop as a state machine: arbitrary sequences of sensor frames (any load,
//! any timestamp, slip signals), bad values, reconfigurations between four
//! configurations, and shutdown-free runs, through `Device::handle`. Asserts the
//! never-let-go invariant, not just "no panic": after every request the command is finite,
//! in the configuration's `[N_min, N_max]`, and moved at most `rise·dt` up and `fall·dt`
//! down from the previous one (clamped into a new configuration's range), except for the
//! documented emergency rise when a slip signal raised the margin or lowered μ̂. Silences
//! (runs of up to 64 idle ticks, `Device::idle_tick`, as the firmware's timer and the host's
//! device thread drive them) obey the same limits and never take the command below the
//! lesser of where it was and the fault target (no less than the last required force).
#![no_main]

use libfuzzer_sys::fuzz_target;
use softgrip::controller::{Controller, ControllerConfig, Libm, Mode, SlipSignal};
use softgrip::device::{ControllerSource, Device, NoActuator, NoClock};
use softgrip::protocol::{Reply, Request, SensorFrame, WireConfigError};
use std::sync::OnceLock;

fn configs() -> [ControllerConfig; 4] {
    let d = ControllerConfig::default();
    [
        d,
        ControllerConfig {
            mode: Mode::Table,
            rise_rate_n_per_s: 150.0,
            fall_rate_n_per_s: 5.0,
            ..d
        },
        ControllerConfig {
            n_min_n: 1.0,
            n_max_n: 8.0,
            fault_force_n: 4.0,
            ..d
        },
        ControllerConfig {
            actuator_lag_s: 0.02,
            actuator_slew_n_per_s: 300.0,
            safety: 1.6,
            mu: 0.5,
            ..d
        },
    ]
}

/// Controllers built once and cloned: building costs milliseconds.
#[derive(Clone)]
struct Pool(&'static [Controller<f32>]);

impl ControllerSource<Libm> for Pool {
    fn build_into(
        &self,
        cfg: ControllerConfig,
        slot: &mut Controller<f32>,
    ) -> Result<(), WireConfigError> {
        let c = self
            .0
            .iter()
            .find(|c| *c.config() == cfg)
            .ok_or_else(|| WireConfigError::new("pool", &"not in the pool"))?;
        slot.clone_from(c);
        Ok(())
    }
}

fn pool() -> &'static [Controller<f32>] {
    static POOL: OnceLock<Vec<Controller<f32>>> = OnceLock::new();
    POOL.get_or_init(|| {
        configs()
            .into_iter()
            .map(|c| Controller::new(c).unwrap())
            .collect()
    })
}

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> Option<u8> {
        let (&b, rest) = self.0.split_first()?;
        self.0 = rest;
        Some(b)
    }
    fn u32(&mut self) -> Option<u32> {
        let mut w = [0u8; 4];
        for x in &mut w {
            *x = self.u8()?;
        }
        Some(u32::from_le_bytes(w))
    }
    fn f32(&mut self) -> Option<f32> {
        self.u32().map(f32::from_bits)
    }
}

fuzz_target!(|data: &[u8]| {
    let cfgs = configs();
    let mut dev = Device::<Libm, Pool>::with_source(Pool(pool()));
    let mut cfg = cfgs[0];
    assert_eq!(
        dev.handle(Request::Configure(cfg), &mut NoActuator, &mut NoClock),
        Reply::Configured(Ok(()))
    );
    let mut bytes = Bytes(data);
    let mut t = 1000u64;
    let mut seq = 0u32;
    let reach = |c: &Controller<f32>| c.margin() / c.mu_estimate();
    while let Some(op) = bytes.u8() {
        let ctl = dev.controller().unwrap();
        let (before, reach_before) = (ctl.command_n(), reach(ctl));
        let request = match op % 8 {
            0..=4 => {
                // A frame: a step of 1 µs to ~4 s, a load from raw bits or a plain value.
                let Some(step) = bytes.u32() else { break };
                t = t.wrapping_add(u64::from(step % 4_000_000));
                let raw = op & 0x80 != 0;
                let mut value = |scale: f32| -> Option<f32> {
                    let b = bytes.u8()?;
                    Some(if raw {
                        bytes.f32()?
                    } else {
                        f32::from(b) / 255.0 * scale
                    })
                };
                let (Some(f), Some(m), Some(n)) = (value(15.0), value(0.1), value(25.0)) else {
                    break;
                };
                let slip = match op >> 4 & 3 {
                    1 => SlipSignal::Incipient,
                    2 => SlipSignal::Gross,
                    _ => SlipSignal::None,
                };
                seq = seq.wrapping_add(1);
                Request::Sensor(SensorFrame {
                    seq,
                    timestamp_us: t,
                    tangential_force_n: [0.0, f],
                    torsional_moment_nm: m,
                    normal_force_n: n,
                    slip,
                })
            }
            5 => {
                // A hostile timestamp.
                let (Some(a), Some(b)) = (bytes.u32(), bytes.u32()) else { break };
                seq = seq.wrapping_add(1);
                Request::Sensor(SensorFrame {
                    seq,
                    timestamp_us: u64::from(a) << 32 | u64::from(b),
                    tangential_force_n: [0.0, 1.0],
                    torsional_moment_nm: 0.0,
                    normal_force_n: 2.0,
                    slip: SlipSignal::None,
                })
            }
            7 if op & 0x80 != 0 => {
                // A silence: no frame for up to 64 tick periods.
                let Some(k) = bytes.u8() else { break };
                let (lo, hi) = (cfg.n_min_n as f32, cfg.n_max_n as f32);
                let rise = (cfg.rise_rate_n_per_s * cfg.tick_period_s) as f32;
                let fall = (cfg.fall_rate_n_per_s * cfg.tick_period_s) as f32;
                let slack = 1e-5 * hi;
                for _ in 0..=(k % 64) {
                    let prev = dev.controller().unwrap().command_n();
                    dev.idle_tick(&mut NoActuator);
                    let ctl = dev.controller().unwrap();
                    let now = ctl.command_n();
                    assert!(now.is_finite() && now >= lo && now <= hi, "idle: {now}");
                    assert!(now >= prev - fall - slack, "idle fell {prev} -> {now}");
                    assert!(now <= prev + rise + slack, "idle rose {prev} -> {now}");
                    let floor = before.min(ctl.fault_target_n()).max(lo);
                    assert!(now >= floor - slack, "silence took {now} below {floor}");
                }
                continue;
            }
            6 => {
                let Some(i) = bytes.u8() else { break };
                cfg = cfgs[usize::from(i) % cfgs.len()];
                Request::Configure(cfg)
            }
            _ => Request::GetStats,
        };
        let reply = dev.handle(request, &mut NoActuator, &mut NoClock);
        let ctl = dev.controller().unwrap();
        let after = ctl.command_n();
        let (lo, hi) = (cfg.n_min_n as f32, cfg.n_max_n as f32);
        assert!(after.is_finite() && after >= lo && after <= hi, "{after} outside [{lo}, {hi}]");
        let start = before.max(lo).min(hi);
        let rise = (cfg.rise_rate_n_per_s * cfg.tick_period_s) as f32;
        let fall = (cfg.fall_rate_n_per_s * cfg.tick_period_s) as f32;
        let slack = 1e-5 * hi;
        assert!(after >= start - fall - slack, "fell {start} -> {after}: {reply:?}");
        if reach(ctl) <= reach_before {
            assert!(after <= start + rise + slack, "rose {start} -> {after}: {reply:?}");
        }
        if let Reply::Command(c) = reply {
            assert_eq!(c.normal_force_n, after);
        }
    }
});
