//! The grasp simulator: scenes, effects that are built only when listed, determinism, the
//! link's accounting, softgrip's command parts in the samples, and the command line.

mod common;

use common::parts;
use host_sim::sim::controllers::LinkKind;
use host_sim::sim::record::Sample;
use host_sim::sim::run::{controller_config, run, run_on};
use host_sim::sim::scene::Scene;
use softgrip::controller::ControllerConfig;
use std::path::PathBuf;
use std::process::Command;

fn scene_path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"))
}

fn text(name: &str) -> String {
    std::fs::read_to_string(scene_path(name)).unwrap()
}

fn samples(text: &str, controller: &str) -> (Vec<Sample>, host_sim::sim::record::RunSummary) {
    let scene = Scene::parse(text).unwrap();
    let out = run(&scene, controller, None).unwrap();
    (out.samples, out.summary)
}

fn bits(s: &[Sample]) -> Vec<Vec<u64>> {
    s.iter()
        .map(|x| {
            vec![
                x.t_s.to_bits(),
                x.ft_n.to_bits(),
                x.mn_nm.to_bits(),
                x.ft_meas_n.to_bits(),
                x.mn_meas_nm.to_bits(),
                x.n_cmd_n.to_bits(),
                x.n_true_n.to_bits(),
                x.a_true_m.to_bits(),
                x.utilisation.to_bits(),
                x.slip_distance_m.to_bits(),
                u64::from(x.slipping),
            ]
            .into_iter()
            .chain(parts(x).map(|p| u64::from(p.to_bits())))
            .collect()
        })
        .collect()
}

#[test]
fn unlisted_effects_change_nothing_whatever_their_settings() {
    let base = text("lift_hold");
    // Settings for every effect the scene does not list, extreme ones included.
    let noisy = format!(
        "{base}\n[effect.disturbance]\nrate_hz = 500.0\nforce_n = 50.0\n\
         [effect.link_faults]\ndrop_prob = 0.9\n[effect.link_latency]\ndelay_ticks = 40\n\
         [effect.actuator]\ntime_constant_s = 5.0\nmax_force_n = 0.1\n\
         [effect.creep]\ntime_constant_s = 100.0\ninstant_fraction = 0.0\n\
         [effect.sensor_faults]\nnan_prob = 1.0\n[effect.skewed_pressure]\ndelta_over_a = 0.99\n"
    );
    for controller in ["softgrip", "fixed-torsion"] {
        let (a, sa) = samples(&base, controller);
        let (b, sb) = samples(&noisy, controller);
        assert_eq!(bits(&a), bits(&b), "{controller}");
        assert_eq!(sa.effects, vec!["gravity", "sensor_noise"]);
        assert_eq!(sb.effects, sa.effects);
        // Only the listed effects (and the core) appear in the cost shares.
        let keys: Vec<&str> = sb.step_cost_share.keys().map(String::as_str).collect();
        assert_eq!(keys, vec!["core", "gravity", "sensor_noise"]);
        let total: f64 = sb.step_cost_share.values().sum();
        assert!((total - 1.0).abs() < 1e-9);
    }
}

#[test]
fn a_seed_gives_the_same_run_and_another_seed_another() {
    let t = text("pull_bump");
    let (a, _) = samples(&t, "softgrip");
    let (b, _) = samples(&t, "softgrip");
    assert_eq!(bits(&a), bits(&b));
    let other = t.replace("seed = 4", "seed = 40");
    let (c, _) = samples(&other, "softgrip");
    assert_ne!(bits(&a), bits(&c));
}

#[test]
fn every_frame_on_the_faulty_link_is_accounted_for() {
    let t = text("faulty_link");
    let (s, summary) = samples(&t, "softgrip");
    let l = summary.link;
    assert!(l.frames_corrupt > 10 && l.frames_lost > 5, "{l:?}");
    // Frames still in the latency line at the end were never sent.
    assert_eq!(
        l.frames_sent,
        l.frames_received + l.frames_corrupt + l.frames_lost,
        "{l:?}"
    );
    assert_eq!(l.frames_sent + 3, summary.ticks, "{l:?}");
    assert!(s
        .iter()
        .all(|x| x.n_cmd_n.is_finite() && x.n_cmd_n >= 1.0 && x.n_cmd_n <= 20.0));
    assert_eq!(summary.slip_events, 0, "{summary:?}");
}

#[test]
fn softgrip_holds_the_basic_lift_and_every_controller_slips_in_the_overload() {
    let (_, s) = samples(&text("lift_hold"), "softgrip");
    assert_eq!(s.slip_events, 0);
    assert!(s.max_utilisation < 1.0 && s.max_utilisation > 0.5);
    assert!(s.mean_normal_force_n > 1.0 && s.mean_normal_force_n < 5.0);
    let t = text("overload");
    for c in ["softgrip", "softgrip-table", "constant", "box"] {
        let (_, s) = samples(&t, c);
        assert!(s.expected_slip);
        assert!(s.slip_events > 0, "{c}");
        assert!(s.metrics.contains_key("dropped_at_s"), "{c}");
    }
    // Ignoring torsion loses an off-centre payload.
    let (_, s) = samples(&text("twist"), "coulomb");
    assert!(s.slip_events > 0);
}

#[test]
fn softgrips_samples_say_what_its_command_is_made_of_on_both_links() {
    let scene = Scene::parse(&text("shake")).unwrap();
    let cfg = controller_config(&scene).unwrap();
    let (cyclic, n_max) = (cfg.cyclic_factor, cfg.n_max_n as f32);
    assert_eq!(cyclic, ControllerConfig::DEFAULT.cyclic_factor);
    assert_eq!(cyclic, 1.45);
    let mut seen = Vec::new();
    for link in [LinkKind::InProcess, LinkKind::Direct] {
        let out = run_on(&scene, "softgrip", &link, None).unwrap();
        // The shake runs from 1.0 to 2.5 s; the controller finds it cyclic within it.
        let shaking = out.samples.iter().filter(|s| (1.0..2.5).contains(&s.t_s));
        assert!(
            shaking
                .into_iter()
                .any(|s| s.parts.load_factor == cyclic as f32),
            "{link:?}: the load factor never reached {cyclic}"
        );
        let mut at_target = 0;
        for s in &out.samples {
            let p = parts(s);
            assert!(
                p.iter().all(|x| x.is_finite()),
                "{link:?} at {}: {p:?}",
                s.t_s
            );
            let c = &s.parts;
            let product = c.slip_margin * c.load_factor;
            assert!((c.margin - product).abs() <= 1e-6 * c.margin, "{p:?}");
            assert!(c.n_slip_n <= c.required_n, "{link:?} at {}: {p:?}", s.t_s);
            assert!(c.lead_n >= 0.0, "{p:?}");
            // The stack: the model, the safety factor, the load factor, the margin.
            assert!(
                c.n_slip_mu_n <= c.n_safety_n && c.n_load_n <= c.required_n,
                "{p:?}"
            );
            // Where the command is the target, the host's required_n is the device's.
            let target = f64::from(c.required_n.min(n_max) + c.lead_n);
            if (s.n_cmd_n - target).abs() <= 1e-6 * s.n_cmd_n {
                at_target += 1;
            }
        }
        assert!(at_target > 300, "{link:?}: {at_target} ticks at the target");
        seen.push(out.samples.iter().map(parts).collect::<Vec<_>>());
    }
    // The device answers the same bytes the same on both links.
    assert!(seen[0]
        .iter()
        .zip(&seen[1])
        .all(|(a, b)| a.map(f32::to_bits) == b.map(f32::to_bits)));
    // A baseline has no parts.
    let out = run_on(&scene, "fixed-torsion", &LinkKind::Direct, None).unwrap();
    assert!(out
        .samples
        .iter()
        .all(|s| parts(s).iter().all(|x| x.is_nan())));
}

#[test]
fn every_effect_runs_alone() {
    let base = text("lift_hold").replace(
        "effects = [\"gravity\", \"sensor_noise\"]",
        "effects = [\"gravity\", \"EFFECT\"]",
    );
    for &effect in host_sim::sim::effects::NAMES {
        if effect == "gravity" {
            continue;
        }
        let t = base.replace("EFFECT", effect);
        let (s, summary) = samples(&t, "softgrip");
        assert_eq!(
            summary.effects,
            vec!["gravity".to_string(), effect.to_string()]
        );
        assert!(summary.step_cost_share.contains_key(effect), "{effect}");
        assert!(s.iter().all(|x| x.n_cmd_n.is_finite()), "{effect}");
        if effect == "partial_slip" {
            let micro = summary.metrics["max_micro_slip_m"];
            assert!(micro > 0.0 && micro < 1e-3, "{micro}");
        }
    }
}

#[test]
fn bad_scene_files_name_the_key_and_its_line() {
    let base = text("lift_hold");
    let cases = [
        (
            base.replace("mu = 0.8", "mu = -0.8"),
            "finger.mu",
            "line 11",
        ),
        (base.replace("mu = 0.8", "mu = \"high\""), "", "line 11"),
        (
            base.replace("mu = 0.8", "mu = 0.8\nmoo = 1"),
            "moo",
            "line 12",
        ),
        (
            base.replace("gamma = 0.5", "gamma = 0.9"),
            "finger.gamma",
            "line 13",
        ),
        (
            base.replace("\"sensor_noise\"]", "\"sensor_nose\"]"),
            "sensor_nose",
            "line 6",
        ),
        (
            base.replace("force_sd_n = 0.01", "force_sd = 0.01"),
            "force_sd",
            "",
        ),
        (
            base.replace("force_sd_n = 0.01", "force_sd_n = -1.0"),
            "effect.sensor_noise.force_sd_n",
            "line",
        ),
        (
            base.replace("kind = \"hold\"", "kind = \"hover\""),
            "hover",
            "",
        ),
        (
            base.replace("duration_s = 3.0", "duration_s = 0.0"),
            "duration_s",
            "line 2",
        ),
        (
            base.replace("[object]\nmass_kg = 0.2", "[object]"),
            "mass_kg",
            "",
        ),
    ];
    for (t, key, line) in cases {
        let err = match Scene::parse(&t) {
            Ok(scene) => {
                // Anything the parse let through is checked when the pipeline is built.
                scene.pipeline().map(|_| ()).unwrap_err().to_string()
            }
            Err(e) => e.to_string(),
        };
        assert!(err.contains(key), "{key}: {err}");
        assert!(err.contains(line), "{line}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

#[test]
fn the_command_line_writes_the_four_outputs_and_rejects_bad_input() {
    let out = std::env::temp_dir().join(format!("softgrip-sim-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_host-sim"))
            .arg("simulate")
            .args(args)
            .output()
            .unwrap()
    };
    let scene = scene_path("lift_hold");
    let o = run(&[
        scene.to_str().unwrap(),
        "--controller",
        "softgrip,constant",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("held") && stdout.contains("real-time factor"),
        "{stdout}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let runs = summary["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 2);
    for key in [
        "scene",
        "controller",
        "slip_events",
        "slip_distance_m",
        "slip_rotation_rad",
        "mean_normal_force_n",
        "peak_normal_force_n",
        "expected_slip",
    ] {
        assert!(!runs[0][key].is_null(), "{key}");
    }
    assert!(out.join("timeseries_lift_hold_softgrip.csv").exists());
    assert!(out.join("surface_lift_hold.svg").exists());
    assert!(out.join("force_lift_hold.svg").exists());
    let _ = std::fs::remove_dir_all(&out);

    let bad = std::env::temp_dir().join(format!("softgrip-bad-{}.toml", std::process::id()));
    std::fs::write(&bad, text("lift_hold").replace("c = 2.5e-3", "c = -1")).unwrap();
    let o = run(&[bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("finger.c") && err.contains("line 12"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let _ = std::fs::remove_file(&bad);
    let o = run(&[scene.to_str().unwrap(), "--controller", "pid"]);
    assert_eq!(o.status.code(), Some(2));
    let o = run(&[scene.to_str().unwrap(), "--link", "carrier-pigeon"]);
    assert_eq!(o.status.code(), Some(2));
}
