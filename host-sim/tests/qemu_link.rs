//! The firmware in QEMU answers exactly as the controller does on the host, counts its
//! instructions, and exits with the code it is asked for.
//!
//! Needs `scripts/firmware-setup.sh` and `scripts/firmware-build.sh`; without them the
//! tests that need them are compiled as ignored, naming the command (`host-sim/build.rs`),
//! unless `SOFTGRIP_REQUIRE_QEMU=1` (as `.ci/run` sets it), which makes them fail instead.

use host_sim::link::qemu::{self, QemuLink};
use host_sim::link::Link;
use softgrip::controller::{Controller, ControllerConfig, Libm, Measurement, Mode};
use softgrip::protocol::{CostUnit, Reply, Request, SensorFrame};

mod common;

fn available() -> Option<(std::path::PathBuf, std::path::PathBuf)> {
    common::qemu_and_firmware("default")
}

#[test]
#[cfg_attr(
    no_qemu,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default"
)]
fn the_firmware_in_qemu_matches_the_host_controller_and_exits_cleanly() {
    let Some((qemu, elf)) = available() else {
        return;
    };
    let mut link = QemuLink::boot(&qemu, &elf).unwrap();
    let mut previous: Option<Controller<f32, Libm>> = None;
    let mut clock_us = 0u64;
    for mode in [Mode::Ellipse, Mode::Table] {
        let cfg = ControllerConfig {
            mode,
            ..ControllerConfig::default()
        };
        assert_eq!(
            link.exchange(&Request::Configure(cfg)).unwrap(),
            Reply::Configured(Ok(()))
        );
        let mut direct = Controller::<f32, Libm>::new(cfg).unwrap();
        // The device hands a running grasp over to a new configuration: so does the host.
        if let Some(p) = &previous {
            direct.take_over_from(p);
        }
        let mut costs = Vec::new();
        for i in 0..300u32 {
            let p = i as f32 * 0.05;
            let f = SensorFrame {
                seq: i,
                timestamp_us: clock_us + 1000 * u64::from(i) + 1,
                tangential_force_n: [3.0 * p.sin().abs(), 0.5 * p.cos()],
                torsional_moment_nm: 0.01 * (0.7 * p).sin(),
                normal_force_n: if i % 97 == 5 { f32::NAN } else { 3.0 + p.cos() },
                slip: Default::default(),
            };
            let Reply::Command(cmd) = link.exchange(&Request::Sensor(f)).unwrap() else {
                panic!("no command")
            };
            let want = direct.tick(&Measurement::from(&f));
            assert_eq!(
                cmd.normal_force_n.to_bits(),
                want.command_n.to_bits(),
                "tick {i}"
            );
            assert_eq!(cmd.n_slip_n.to_bits(), want.n_slip_n.to_bits(), "tick {i}");
            assert_eq!(
                cmd.utilisation.to_bits(),
                want.utilisation.to_bits(),
                "tick {i}"
            );
            assert_eq!(cmd.status, want.status);
            costs.push(cmd.tick_cost);
        }
        clock_us += 300_000;
        previous = Some(direct);
        let Reply::Stats(s) = link.exchange(&Request::GetStats).unwrap() else {
            panic!()
        };
        assert_eq!(s.cost_unit, CostUnit::Instructions);
        assert!(s.startup_cost > 10_000, "{s:?}");
        assert!(
            s.stack_peak_bytes > 256 && s.stack_peak_bytes < 64 * 1024,
            "{s:?}"
        );
        costs.sort_unstable();
        eprintln!(
            "{mode:?}: start-up {} instructions, tick min {} median {} max {}, stack peak {} B",
            s.startup_cost,
            costs[0],
            costs[costs.len() / 2],
            costs[costs.len() - 1],
            s.stack_peak_bytes
        );
        assert!(costs[0] > 20);
    }
    assert_eq!(link.shutdown(7).unwrap(), 7);
}

/// The `prebuilt-tables` firmware: tables made by `host-sim tables --format rust` (f64
/// precomputation, table mode) are linked in; configuring costs almost nothing, ticks
/// equal a host controller with the same tables, and another configuration is refused.
#[test]
#[cfg_attr(
    no_qemu_prebuilt,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default prebuilt-tables"
)]
fn the_prebuilt_tables_firmware_needs_no_precomputation() {
    let Some((qemu, _)) = available() else {
        return;
    };
    let elf = qemu::firmware("prebuilt-tables");
    if !elf.exists() {
        eprintln!("skipped: run scripts/firmware-build.sh prebuilt-tables");
        return;
    }
    let mut link = QemuLink::boot(&qemu, &elf).unwrap();
    let cfg = ControllerConfig {
        mode: Mode::Table,
        ..ControllerConfig::default()
    };
    let ellipse = ControllerConfig {
        mode: Mode::Ellipse,
        ..ControllerConfig::default()
    };
    let Reply::Configured(Err(e)) = link.exchange(&Request::Configure(ellipse)).unwrap() else {
        panic!("an ellipse-mode configuration must be refused")
    };
    assert_eq!(e.param.as_str(), "tables");
    assert_eq!(
        link.exchange(&Request::Configure(cfg)).unwrap(),
        Reply::Configured(Ok(()))
    );
    let mut direct = Controller::<f32, Libm>::new_precomputed_in::<f64>(cfg).unwrap();
    for i in 0..200u32 {
        let p = i as f32 * 0.07;
        let f = SensorFrame {
            seq: i,
            timestamp_us: 1000 * u64::from(i) + 1,
            tangential_force_n: [2.0 * p.sin().abs(), 0.4 * p.cos()],
            torsional_moment_nm: 0.012 * (0.9 * p).sin(),
            normal_force_n: 3.0,
            slip: Default::default(),
        };
        let Reply::Command(cmd) = link.exchange(&Request::Sensor(f)).unwrap() else {
            panic!()
        };
        let want = direct.tick(&Measurement::from(&f));
        assert_eq!(
            cmd.normal_force_n.to_bits(),
            want.command_n.to_bits(),
            "tick {i}"
        );
    }
    let Reply::Stats(s) = link.exchange(&Request::GetStats).unwrap() else {
        panic!()
    };
    eprintln!(
        "prebuilt: start-up {} instructions, stack peak {} B",
        s.startup_cost, s.stack_peak_bytes
    );
    assert!(s.startup_cost < 50_000, "{s:?}");
    assert_eq!(link.shutdown(0).unwrap(), 0);
}

/// `simulate --link qemu` gives the in-process link's time series bit for bit, and its
/// summary.json has the `target` object.
#[test]
#[cfg_attr(
    no_qemu,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default"
)]
fn a_scene_over_qemu_equals_the_in_process_link_and_reports_the_target() {
    if available().is_none() {
        return;
    }
    let base = std::env::temp_dir().join(format!("softgrip-qemu-sim-{}", std::process::id()));
    let (q, i) = (
        simulate("lift_hold", "qemu", &base),
        simulate("lift_hold", "inprocess", &base),
    );
    let series = |d: &std::path::Path| {
        std::fs::read_to_string(d.join("timeseries_lift_hold_softgrip.csv")).unwrap()
    };
    assert_eq!(series(&q), series(&i));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(q.join("summary.json")).unwrap()).unwrap();
    let t = &v["target"];
    assert!(t["startup_instructions"].as_f64().unwrap() > 1e5);
    let tick = &t["tick_instructions"]["ellipse"];
    for k in ["min", "median", "max"] {
        assert!(tick[k].as_f64().unwrap() > 0.0, "{k}");
    }
    assert!(t["flash_bytes"].as_u64().unwrap() > 10_000);
    assert!(t["stack_peak_bytes"].as_f64().unwrap() > 1_000.0);
    let _ = std::fs::remove_dir_all(&base);
}

/// Runs the shipped scene `name` on `link` into a folder of `base`, returns the folder.
fn simulate(name: &str, link: &str, base: &std::path::Path) -> std::path::PathBuf {
    let scene =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/{name}.toml"));
    let out = base.join(format!("{name}-{link}"));
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["simulate", scene.to_str().unwrap(), "--link", link, "--out"])
        .arg(&out)
        .args(["--controller", "softgrip,softgrip-table"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    out
}

/// The brush finger (a plant softgrip does not model) with softgrip calibrated from its
/// lab data (`scenes/brush_lift_hold.toml`): the firmware in QEMU gives the in-process
/// link's time series bit for bit, in both modes, and holds the object.
#[test]
#[cfg_attr(
    no_qemu,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default"
)]
fn the_brush_scene_over_qemu_equals_the_in_process_link() {
    if available().is_none() {
        return;
    }
    let base = std::env::temp_dir().join(format!("softgrip-qemu-brush-{}", std::process::id()));
    let (q, i) = (
        simulate("brush_lift_hold", "qemu", &base),
        simulate("brush_lift_hold", "inprocess", &base),
    );
    for c in ["softgrip", "softgrip-table"] {
        let name = format!("timeseries_brush_lift_hold_{c}.csv");
        let read = |d: &std::path::Path| std::fs::read_to_string(d.join(&name)).unwrap();
        assert_eq!(read(&q), read(&i), "{name}");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(q.join("summary.json")).unwrap()).unwrap();
    let runs = v["runs"].as_array().expect("summary.json has runs");
    assert_eq!(runs.len(), 2);
    for r in runs {
        assert_eq!(r["dropped"], serde_json::Value::Bool(false), "{r}");
    }
    let _ = std::fs::remove_dir_all(&base);
}

/// `simulate --link serial --port PATH` over the QEMU firmware's UART, opened as any
/// serial port (as a board's would be): the in-process link's time series bit for bit.
#[test]
#[cfg_attr(
    no_qemu,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default"
)]
fn a_scene_over_a_serial_port_equals_the_in_process_link() {
    let Some((qemu, elf)) = available() else {
        return;
    };
    let (mut child, pty) = host_sim::link::qemu::start(&qemu, &elf).unwrap();
    let scene = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/lift_hold.toml");
    let base = std::env::temp_dir().join(format!("softgrip-serial-sim-{}", std::process::id()));
    let run = |link: &str, extra: &[&str]| {
        let out = base.join(link);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(["simulate", scene.to_str().unwrap(), "--link", link])
            .args(extra)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(out.join("timeseries_lift_hold_softgrip.csv")).unwrap()
    };
    let serial = run("serial", &["--port", &pty, "--baud", "115200"]);
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(serial, run("inprocess", &[]));
    let _ = std::fs::remove_dir_all(&base);
}

/// A serial port that is missing, or that cannot be opened, is an error naming the flag
/// and the path.
#[test]
fn a_missing_or_unopenable_serial_port_names_the_flag_and_the_path() {
    let scene = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/lift_hold.toml");
    let out = std::env::temp_dir().join(format!("softgrip-serial-err-{}", std::process::id()));
    for (port, what) in [
        ("/dev/softgrip-no-such-port", "does not exist"),
        // A file that exists but is no serial port.
        (env!("CARGO_MANIFEST_DIR"), "cannot open"),
    ] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .args(["simulate", scene.to_str().unwrap(), "--link", "serial"])
            .args(["--port", port, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("--port") && err.contains(port) && err.contains(what),
            "{err}"
        );
    }
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(["simulate", scene.to_str().unwrap(), "--link", "serial"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("--link serial needs --port"));
    let _ = std::fs::remove_dir_all(&out);
}
