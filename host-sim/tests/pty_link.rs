//! The default link: the firmware loop on its own thread behind a pseudo-terminal gives
//! exactly what the controller gives when called directly, and counts what it drops.

use host_sim::link::{pty::PtyLink, Link};
use softgrip::controller::{
    Controller, ControllerConfig, Libm, Measurement, Micromath, Mode, Status, TickMath,
};
use softgrip::protocol::{CostUnit, Reply, Request, SensorFrame};

fn frames() -> Vec<SensorFrame> {
    (0..400u32)
        .map(|i| {
            let p = i as f32 * 0.05;
            let mut f = SensorFrame {
                seq: i,
                timestamp_us: 1000 * u64::from(i) + 1,
                tangential_force_n: [3.0 * p.sin().abs(), 0.5 * p.cos()],
                torsional_moment_nm: 0.01 * (0.7 * p).sin(),
                normal_force_n: 3.0 + p.cos(),
                slip: Default::default(),
            };
            // Hostile frames among the good ones.
            match i % 50 {
                7 => f.tangential_force_n[0] = f32::NAN,
                8 => f.normal_force_n = f32::INFINITY,
                9 => f.timestamp_us = 0,
                _ => {}
            }
            f
        })
        .collect()
}

fn same_as_direct<M: TickMath<f32> + Send + 'static>(mode: Mode) {
    let cfg = ControllerConfig {
        mode,
        ..ControllerConfig::default()
    };
    let mut link = PtyLink::spawn::<M>().unwrap();
    assert_eq!(
        link.exchange(&Request::Configure(cfg)).unwrap(),
        Reply::Configured(Ok(()))
    );
    let mut direct = Controller::<f32, M>::new(cfg).unwrap();
    let frames = frames();
    for f in &frames {
        let reply = link.exchange(&Request::Sensor(*f)).unwrap();
        let Reply::Command(cmd) = reply else {
            panic!("{reply:?}")
        };
        let want = direct.tick(&Measurement {
            tangential_force_n: f.tangential_force_n,
            torsional_moment_nm: f.torsional_moment_nm,
            normal_force_n: f.normal_force_n,
            timestamp_us: f.timestamp_us,
            slip: Default::default(),
        });
        assert_eq!(cmd.seq, f.seq);
        assert_eq!(cmd.normal_force_n.to_bits(), want.command_n.to_bits());
        assert_eq!(cmd.n_slip_n.to_bits(), want.n_slip_n.to_bits());
        assert_eq!(cmd.utilisation.to_bits(), want.utilisation.to_bits());
        assert_eq!(cmd.status, want.status);
        assert_eq!(cmd.fault_active, want.fault_active);
        if f.seq % 50 == 7 {
            assert_eq!(cmd.status, Status::SensorFault);
        }
    }
    let Reply::Stats(stats) = link.exchange(&Request::GetStats).unwrap() else {
        panic!()
    };
    // Hello, the pacing, configure, the sensor frames, and this request.
    assert_eq!(stats.frames_received as usize, frames.len() + 4);
    assert_eq!(stats.frames_sent as usize, frames.len() + 3);
    assert_eq!(stats.ticks as usize, frames.len());
    assert_eq!(stats.crc_errors + stats.decode_errors + stats.overruns, 0);
    assert_eq!(stats.cost_unit, CostUnit::Nanoseconds);
    assert!(stats.worst_tick_cost >= stats.last_tick_cost && stats.worst_tick_cost > 0);
    assert!(stats.startup_cost > 0);
}

#[test]
fn the_pty_link_matches_the_direct_controller_bit_for_bit() {
    same_as_direct::<Libm>(Mode::Ellipse);
    same_as_direct::<Libm>(Mode::Table);
    same_as_direct::<Micromath>(Mode::Ellipse);
}

#[test]
fn a_sensor_frame_before_configuration_and_a_bad_configuration_are_answered() {
    let mut link = PtyLink::spawn::<Libm>().unwrap();
    let f = frames()[0];
    assert_eq!(
        link.exchange(&Request::Sensor(f)).unwrap(),
        Reply::NotConfigured { seq: 0 }
    );
    let bad = ControllerConfig {
        mu: -1.0,
        ..ControllerConfig::default()
    };
    let Reply::Configured(Err(e)) = link.exchange(&Request::Configure(bad)).unwrap() else {
        panic!()
    };
    assert_eq!(e.param.as_str(), "mu");
    assert!(e.message.starts_with("mu:"), "{}", e.message);
}

#[test]
fn corrupt_and_oversized_frames_are_counted_and_the_stream_resynchronises() {
    let mut link = PtyLink::spawn::<Libm>().unwrap();
    link.exchange(&Request::Configure(ControllerConfig::default()))
        .unwrap();
    // A frame with a flipped bit, a run of garbage, and 400 bytes without a delimiter,
    // each closed by a delimiter.
    let mut good = [0u8; 200];
    let len = softgrip::protocol::encode(&Request::Sensor(frames()[1]), &mut good).unwrap();
    let mut flipped = good[..len].to_vec();
    flipped[3] ^= 0x10;
    link.inject(&flipped).unwrap();
    link.inject(&[0x13, 0x37, 0xff, 0x42, 0x00]).unwrap();
    let mut long = vec![0x55u8; 400];
    long.push(0);
    link.inject(&long).unwrap();
    // The next exchange works.
    let reply = link.exchange(&Request::Sensor(frames()[2])).unwrap();
    assert!(
        matches!(reply, Reply::Command(c) if c.seq == 2),
        "{reply:?}"
    );
    let Reply::Stats(s) = link.exchange(&Request::GetStats).unwrap() else {
        panic!()
    };
    assert_eq!(s.crc_errors + s.decode_errors, 2, "{s:?}");
    assert_eq!(s.overruns, 1, "{s:?}");
    assert_eq!(s.ticks, 1);
}
