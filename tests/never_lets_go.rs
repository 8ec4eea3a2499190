//! A device loop that never lets go: force continuity through every input sequence and
//! every reconfiguration (a state machine checked on the core and through `Device`),
//! wrapping time with a resync rule, the handshake, and implausible tables. Each
//! finding of the attack that motivated these is a regression test here.

use proptest::prelude::*;
use softgrip::controller::blob::{encode, Blob, BlobError, BLOB_MAX_LEN};
use softgrip::controller::{
    Controller, ControllerConfig, Libm, Measurement, Mode, SlipSignal, Status, TableError,
};
use softgrip::device::{ControllerSource, Device, NoActuator, NoClock};
use softgrip::protocol::{
    Reply, Request, SensorFrame, WireConfigError, CRC, PROTOCOL_VERSION, SCHEMA_KEY,
};

fn frame(t_us: u64, f: f32, m: f32, n: f32) -> Measurement<f32> {
    Measurement {
        tangential_force_n: [0.0, f],
        torsional_moment_nm: m,
        normal_force_n: n,
        timestamp_us: t_us,
        slip: SlipSignal::None,
    }
}

/// The configurations a run switches between: the default, a stiffer rate-limited one in
/// table mode, one with a narrower force range, and one with an actuator lead.
fn pool() -> Vec<ControllerConfig> {
    let d = ControllerConfig::default();
    vec![
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
            safety: 1.9,
            ..d
        },
    ]
}

/// Controllers cloned from a pool built once (the state machine reconfigures thousands
/// of times; building costs milliseconds).
#[derive(Clone)]
struct Pool(Vec<Controller<f32>>);

impl Pool {
    fn new() -> Self {
        Self(
            pool()
                .into_iter()
                .map(|c| Controller::<f32>::new(c).unwrap())
                .collect(),
        )
    }
}

#[allow(clippy::result_large_err)]
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

#[derive(Debug, Clone)]
enum Op {
    /// A frame `dt` after the previous timestamp (wrapping), with this load.
    Frame {
        dt_us: u64,
        f: f32,
        m: f32,
        n: f32,
        slip: u8,
    },
    /// A frame with a hostile timestamp.
    Stamp(u64),
    /// A frame with a non-finite value.
    Bad,
    /// Silence for a tick.
    Idle,
    /// Reconfigure with pool entry `i`.
    Configure(usize),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        12 => (prop_oneof![Just(1000u64), 1u64..5000, 1u64..3_000_000], 0.0f32..15.0, 0.0f32..0.1,
            0.0f32..25.0, prop_oneof![20 => Just(0u8), 1 => 1u8..3])
            .prop_map(|(dt_us, f, m, n, slip)| Op::Frame { dt_us, f, m, n, slip }),
        1 => prop_oneof![Just(u64::MAX), Just(0u64), any::<u64>()].prop_map(Op::Stamp),
        1 => Just(Op::Bad),
        2 => Just(Op::Idle),
        1 => (0usize..4).prop_map(Op::Configure),
    ]
}

fn slip_of(code: u8) -> SlipSignal {
    match code {
        1 => SlipSignal::Incipient,
        2 => SlipSignal::Gross,
        _ => SlipSignal::None,
    }
}

/// What every tick must satisfy, given the command before it and the configuration.
fn continuity(
    cfg: &ControllerConfig,
    before: f32,
    after: f32,
    margin_before: f32,
    margin_after: f32,
) -> Result<(), TestCaseError> {
    let (lo, hi) = (cfg.n_min_n as f32, cfg.n_max_n as f32);
    prop_assert!(
        after.is_finite() && after >= lo && after <= hi,
        "{after} outside [{lo}, {hi}]"
    );
    let rise = (cfg.rise_rate_n_per_s * cfg.tick_period_s) as f32;
    let fall = (cfg.fall_rate_n_per_s * cfg.tick_period_s) as f32;
    let slack = 1e-5 * hi;
    // Into the new configuration's range first (a reconfiguration clamps), then the rates.
    let start = before.max(lo).min(hi);
    prop_assert!(
        after >= start - fall - slack,
        "fell {start} -> {after} (fall step {fall})"
    );
    // The documented exception: the emergency rise on a slip signal that raises the margin
    // or lowers μ̂. The callers pass `margin/μ̂`, which grows exactly then.
    if margin_after <= margin_before {
        prop_assert!(
            after <= start + rise + slack,
            "rose {start} -> {after} (rise step {rise})"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 10_000, failure_persistence: None, ..ProptestConfig::default() })]

    /// The core: any sequence of frames, timestamps, silences, reconfigurations and slip
    /// signals keeps the command continuous and in range.
    #[test]
    fn the_core_command_is_continuous_through_anything(ops in prop::collection::vec(op(), 1..40)) {
        let pool = Pool::new();
        let mut ctl = pool.0[0].clone();
        let mut t = 1000u64;
        let mut margin = 1.0f32 / 0.8;
        for op in &ops {
            let before = ctl.command_n();
            let out = match *op {
                Op::Frame { dt_us, f, m, n, slip } => {
                    t = t.wrapping_add(dt_us);
                    ctl.tick(&Measurement { slip: slip_of(slip), ..frame(t, f, m, n) })
                }
                Op::Stamp(s) => ctl.tick(&frame(s, 1.0, 0.0, 2.0)),
                Op::Bad => ctl.tick(&frame(t.wrapping_add(1), f32::NAN, 0.0, 2.0)),
                Op::Idle => ctl.idle(),
                Op::Configure(i) => {
                    let mut next = pool.0[i].clone();
                    next.take_over_from(&ctl);
                    ctl = next;
                    continuity(ctl.config(), before, ctl.command_n(), margin, margin)?;
                    margin = ctl.margin() / ctl.mu_estimate();
                    continue;
                }
            };
            let reach = out.margin / out.mu_estimate;
            continuity(ctl.config(), before, out.command_n, margin, reach)?;
            margin = reach;
        }
    }

    /// The same through `Device`, over the wire's own messages.
    #[test]
    fn the_device_command_is_continuous_through_anything(ops in prop::collection::vec(op(), 1..40)) {
        let configs = pool();
        let pool = Pool::new();
        let mut dev = Device::<Libm, Pool>::with_source(pool);
        let ok = dev.handle(Request::Configure(configs[0]), &mut NoActuator, &mut NoClock);
        prop_assert_eq!(ok, Reply::Configured(Ok(())));
        let mut t = 1000u64;
        let mut margin = 1.0f32 / 0.8;
        let mut cfg = configs[0];
        let mut seq = 0u32;
        for op in &ops {
            let before = dev.controller().unwrap().command_n();
            let mut send = |stamp: u64, f: f32, slip: SlipSignal, m: f32, n: f32| {
                seq += 1;
                dev.handle(
                    Request::Sensor(SensorFrame {
                        seq,
                        timestamp_us: stamp,
                        tangential_force_n: [0.0, f],
                        torsional_moment_nm: m,
                        normal_force_n: n,
                        slip,
                    }),
                    &mut NoActuator,
                    &mut NoClock,
                )
            };
            let reply = match *op {
                Op::Frame { dt_us, f, m, n, slip } => {
                    t = t.wrapping_add(dt_us);
                    send(t, f, slip_of(slip), m, n)
                }
                Op::Stamp(s) => send(s, 1.0, SlipSignal::None, 0.0, 2.0),
                Op::Bad => send(t.wrapping_add(1), f32::NAN, SlipSignal::None, 0.0, 2.0),
                Op::Idle => continue,
                Op::Configure(i) => {
                    let r = dev.handle(Request::Configure(configs[i]), &mut NoActuator, &mut NoClock);
                    prop_assert_eq!(r, Reply::Configured(Ok(())));
                    cfg = configs[i];
                    continuity(&cfg, before, dev.controller().unwrap().command_n(), margin, margin)?;
                    let c = dev.controller().unwrap();
                    margin = c.margin() / c.mu_estimate();
                    continue;
                }
            };
            let Reply::Command(c) = reply else {
                return Err(TestCaseError::fail(format!("{reply:?}")));
            };
            let reach = c.margin / c.mu_estimate;
            continuity(&cfg, before, c.normal_force_n, margin, reach)?;
            margin = reach;
        }
    }
}

/// Regression: `reconfigure`, even with an identical configuration, used to drop the
/// command to N_min in one step and release an object held at 8 N.
#[test]
fn a_reconfiguration_never_releases_the_grasp() {
    let cfg = ControllerConfig::default();
    let mut dev = Device::<Libm>::new();
    dev.handle(Request::Configure(cfg), &mut NoActuator, &mut NoClock);
    let mut seq = 0;
    let mut hold = |dev: &mut Device<Libm>, t: u64| {
        seq += 1;
        match dev.handle(
            Request::Sensor(SensorFrame {
                seq,
                timestamp_us: t,
                tangential_force_n: [0.0, 4.0],
                torsional_moment_nm: 0.01,
                normal_force_n: 8.0,
                slip: SlipSignal::None,
            }),
            &mut NoActuator,
            &mut NoClock,
        ) {
            Reply::Command(c) => c.normal_force_n,
            other => panic!("{other:?}"),
        }
    };
    let mut held = 0.0;
    for k in 1..200 {
        held = hold(&mut dev, k * 1000);
    }
    assert!(held > 7.0, "{held}");
    // The same configuration: a no-op, bit for bit.
    dev.handle(Request::Configure(cfg), &mut NoActuator, &mut NoClock);
    assert_eq!(dev.controller().unwrap().command_n(), held);
    // A new one: the command carries over and falls at most at the fall rate.
    let softer = ControllerConfig { safety: 1.0, ..cfg };
    dev.handle(Request::Configure(softer), &mut NoActuator, &mut NoClock);
    assert_eq!(dev.controller().unwrap().command_n(), held);
    let next = hold(&mut dev, 200 * 1000);
    assert!(next >= held - (cfg.fall_rate_n_per_s * 1e-3) as f32 - 1e-6);
}

/// Regression: one frame stamped `u64::MAX` used to latch `StaleInput` for good.
#[test]
fn one_bad_timestamp_costs_one_frame_and_is_counted() {
    let mut c = Controller::<f32>::new(ControllerConfig::default()).unwrap();
    for k in 1..50u64 {
        assert_eq!(c.tick(&frame(k * 1000, 1.0, 0.0, 2.0)).status, Status::Ok);
    }
    assert_eq!(
        c.tick(&frame(u64::MAX, 1.0, 0.0, 2.0)).status,
        Status::StaleInput
    );
    assert_eq!(c.tick(&frame(50_000, 1.0, 0.0, 2.0)).status, Status::Ok);
    assert_eq!(c.time_rejections(), 1);
    // A repeat and an older frame are refused too, and counted.
    assert_eq!(
        c.tick(&frame(50_000, 1.0, 0.0, 2.0)).status,
        Status::StaleInput
    );
    assert_eq!(
        c.tick(&frame(10_000, 1.0, 0.0, 2.0)).status,
        Status::StaleInput
    );
    assert_eq!(c.time_rejections(), 3);
    assert_eq!(c.tick(&frame(51_000, 1.0, 0.0, 2.0)).status, Status::Ok);
}

/// A sensor clock that wraps keeps working; a clock that really jumps (a restart, a long
/// silence) is re-anchored after three agreeing frames.
#[test]
fn a_wrapping_clock_works_and_a_real_jump_resyncs() {
    let mut c = Controller::<f32>::new(ControllerConfig::default()).unwrap();
    let start = u64::MAX - 5_500;
    for k in 0..20u64 {
        let t = start.wrapping_add(k * 1000);
        assert_eq!(c.tick(&frame(t, 1.0, 0.0, 2.0)).status, Status::Ok, "{k}");
    }
    let mut d = Controller::<f32>::new(ControllerConfig::default()).unwrap();
    d.tick(&frame(1000, 1.0, 0.0, 2.0));
    let jump = 3_600_000_000u64; // an hour later
    let statuses: Vec<Status> = (0..4)
        .map(|k| d.tick(&frame(jump + k * 1000, 1.0, 0.0, 2.0)).status)
        .collect();
    assert_eq!(
        statuses,
        [
            Status::StaleInput,
            Status::StaleInput,
            Status::Ok,
            Status::Ok
        ]
    );
}

/// A Hello from another protocol gets a typed answer with the device's side, and the
/// device does not run until a matching Hello.
#[test]
fn a_mismatched_hello_stops_the_device_until_a_matching_one() {
    let mut dev = Device::<Libm>::new();
    let theirs = Request::Hello {
        version: PROTOCOL_VERSION + 1,
        schema_key: SCHEMA_KEY ^ 1,
    };
    let ours = Reply::Incompatible {
        version: PROTOCOL_VERSION,
        schema_key: SCHEMA_KEY,
    };
    assert_eq!(dev.handle(theirs, &mut NoActuator, &mut NoClock), ours);
    let cfg = Request::Configure(ControllerConfig::default());
    assert_eq!(dev.handle(cfg.clone(), &mut NoActuator, &mut NoClock), ours);
    assert!(dev.controller().is_none());
    assert_eq!(
        dev.handle(Request::hello(), &mut NoActuator, &mut NoClock),
        Reply::hello()
    );
    assert_eq!(
        dev.handle(cfg, &mut NoActuator, &mut NoClock),
        Reply::Configured(Ok(()))
    );
}

fn blob() -> Vec<u8> {
    let cfg = ControllerConfig {
        mode: Mode::Table,
        ..ControllerConfig::default()
    };
    let c = Controller::<f32>::new(cfg).unwrap();
    let mut buf = [0u8; BLOB_MAX_LEN];
    let len = encode(&cfg, &c.capacity().tables(), &mut buf).unwrap();
    buf[..len].to_vec()
}

/// Replaces the body bytes `at..at + old_len` with `new`, fixing the length and the CRC:
/// a blob that is sealed correctly but lies about its contents.
fn doctor(mut b: Vec<u8>, at: usize, old_len: usize, new: &[u8]) -> Vec<u8> {
    b.splice(at..at + old_len, new.iter().copied());
    let body = (b.len() - 14) as u32;
    b[6..10].copy_from_slice(&body.to_le_bytes());
    let end = b.len() - 4;
    let crc = CRC.checksum(&b[..end]);
    b[end..].copy_from_slice(&crc.to_le_bytes());
    b
}

/// Regression: a blob with a valid CRC but a node count of 999 in its header, or arms
/// that disagree with their inverses, used to be accepted.
#[test]
fn implausible_tables_are_refused_naming_the_check() {
    let good = blob();
    assert!(Blob::parse(&good).is_ok());
    let mut scratch = [0u8; 256];
    let cfg_len = postcard::to_slice(&Blob::parse(&good).unwrap().config(), &mut scratch)
        .unwrap()
        .len();
    let nodes_at = 10 + cfg_len;
    assert_eq!(good[nodes_at], 48);
    let lying = doctor(good.clone(), nodes_at, 1, &[0xe7, 0x07]); // 999 as a varint
    match Blob::parse(&lying) {
        Err(BlobError::Implausible { check }) => assert!(check.contains("nodes"), "{check}"),
        other => panic!("{other:?}"),
    }
    // The tables themselves: an arm that disagrees with its inverse, arms that fall.
    let c = Controller::<f32>::new(ControllerConfig::default()).unwrap();
    let t = c.capacity().tables();
    let mut arms = t.arm_m.to_vec();
    arms[7] *= 1.01;
    let bad = softgrip::controller::Tables { arm_m: &arms, ..t };
    match Controller::<f32>::from_tables(*c.config(), &bad) {
        Err(softgrip::controller::FromTablesError::Tables(TableError::Inconsistent {
            check,
            index,
        })) => {
            assert!(check.contains("inv_arm"), "{check}");
            assert_eq!(index, 7);
        }
        other => panic!("{other:?}"),
    }
}
