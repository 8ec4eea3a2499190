//! The board build (`scripts/firmware-build.sh board`: clocks, USART1 pins and baud rate
//! set at start-up, TIM2 counting core cycles at the 16 MHz reset clock, a reset where the
//! emulator build exits) boots in QEMU, whose RCC and GPIO ignore the set-up writes: it
//! answers exactly as the controller does on the host, reports its costs in cycles, and
//! after `Shutdown` resets and comes back waiting for a `Hello`, as a board does.
//!
//! Needs `scripts/firmware-setup.sh` and `scripts/firmware-build.sh board`; compiled as
//! ignored without them (`host-sim/build.rs`) unless `SOFTGRIP_REQUIRE_QEMU=1`.

mod common;

use host_sim::link::qemu::QemuLink;
use host_sim::link::Link;
use softgrip::controller::{Controller, ControllerConfig, Libm, Measurement};
use softgrip::protocol::{CostUnit, Reply, Request, SensorFrame};

#[test]
#[cfg_attr(
    no_qemu_board,
    ignore = "needs QEMU and the board firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh board"
)]
fn the_board_build_boots_in_qemu_matches_the_host_and_resets_on_shutdown() {
    let Some((qemu, elf)) = common::qemu_and_firmware("board") else {
        return;
    };
    let mut link = QemuLink::boot(&qemu, &elf).unwrap();
    let cfg = ControllerConfig::default();
    assert_eq!(
        link.exchange(&Request::Configure(cfg)).unwrap(),
        Reply::Configured(Ok(()))
    );
    let mut direct = Controller::<f32, Libm>::new(cfg).unwrap();
    for i in 0..100u32 {
        let p = i as f32 * 0.07;
        let f = SensorFrame {
            seq: i,
            timestamp_us: 1000 * u64::from(i) + 1,
            tangential_force_n: [2.0 * p.sin().abs(), 0.4 * p.cos()],
            torsional_moment_nm: 0.008 * (0.9 * p).sin(),
            normal_force_n: 3.0 + p.cos(),
            slip: Default::default(),
        };
        let Reply::Command(cmd) = link.exchange(&Request::Sensor(f)).unwrap() else {
            panic!("no command at tick {i}")
        };
        let want = direct.tick(&Measurement::from(&f));
        assert_eq!(
            cmd.normal_force_n.to_bits(),
            want.command_n.to_bits(),
            "tick {i}"
        );
        assert_eq!(cmd.status, want.status, "tick {i}");
    }
    let Reply::Stats(s) = link.exchange(&Request::GetStats).unwrap() else {
        panic!("no stats")
    };
    assert_eq!(s.cost_unit, CostUnit::Cycles);
    // Shutdown: the board answers, resets, and a new session starts with a Hello.
    assert!(matches!(
        link.exchange(&Request::Shutdown { code: 3 }).unwrap(),
        Reply::ShuttingDown { .. }
    ));
    let mut hello = None;
    for _ in 0..50 {
        match link.exchange(&Request::hello()) {
            Ok(reply @ Reply::Hello { .. }) => {
                hello = Some(reply);
                break;
            }
            _ => std::thread::sleep(std::time::Duration::from_millis(100)),
        }
    }
    assert!(
        hello.is_some(),
        "the board did not come back after its reset"
    );
    let Reply::Stats(s) = link.exchange(&Request::GetStats).unwrap() else {
        panic!("no stats after the reset")
    };
    assert_eq!(
        s.ticks, 0,
        "a reset board starts with fresh counters: {s:?}"
    );
}
