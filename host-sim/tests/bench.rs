//! The benchmark and what it rests on: reproducible trials, the oracle, the drop
//! definition, the slip sensor, the direct link, belief apart from truth. No timing
//! assertions.

use host_sim::bench::families::{self, Ranges};
use host_sim::bench::oracle::{least_holding_force_n, mean_oracle_force_n};
use host_sim::bench::stats;
use host_sim::bench::sweep::{self, SWEEPS};
use host_sim::bench::trial_finger::{BenchPlant, FingerSource};
use host_sim::sim::controllers::LinkKind;
use host_sim::sim::effects::slip_sensor::SlipSensor;
use host_sim::sim::effects::{self, Effect, EffectSettings, World};
use host_sim::sim::record::Sample;
use host_sim::sim::run::{
    self, build_truth, controller_config, is_drop, run_with, RunOptions, DROP_DISTANCE_M,
    DROP_ROTATION_RAD,
};
use host_sim::sim::scene::Scene;
use indicatif::ProgressBar;
use softgrip::protocol::{SensorFrame, SlipSignal};
use std::path::PathBuf;

fn scene_text(name: &str) -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"));
    std::fs::read_to_string(p).unwrap()
}

/// Trials on the limit-surface plant (cheap to draw: its lab and oracle are table
/// lookups).
const FLS: FingerSource = FingerSource::Drawn(BenchPlant::Fls);

fn trial(family: &str, seed: u64, index: usize) -> families::Trial {
    families::trial_on(&FLS, &Ranges::default(), family, seed, index).unwrap()
}

fn small_sweeps() -> Vec<sweep::Sweep> {
    SWEEPS
        .iter()
        .filter(|s| {
            matches!(
                s.controller.name(),
                "softgrip-ellipse" | "constant" | "fixed-torsion"
            )
        })
        .copied()
        .collect()
}

#[test]
fn the_same_seed_gives_the_same_rows_and_another_seed_other_trials() {
    let sweeps = small_sweeps();
    let bar = ProgressBar::hidden();
    let rows = |seed| {
        let r = host_sim::bench::run_family(
            &FLS,
            &Ranges::default(),
            "mu-mismatch",
            seed,
            4,
            &sweeps,
            &LinkKind::Direct,
            &bar,
        )
        .unwrap();
        let r: Vec<&sweep::TrialResult> = r.iter().collect();
        serde_json::to_string(&stats::rows("mu-mismatch", Some(seed), &sweeps, &r)).unwrap()
    };
    let a = rows(7);
    assert_eq!(a, rows(7));
    assert_ne!(a, rows(8));
    for family in families::NAMES {
        let t = |seed, i| trial(family, seed, i).text;
        assert_eq!(t(7, 3), t(7, 3), "{family}");
        assert_ne!(t(7, 3), t(8, 3), "{family}");
        assert_ne!(t(7, 3), t(7, 4), "{family}");
    }
}

/// Least holding force by plain bisection over the truth's utilisation (60 halvings).
fn brute_force(truth: &host_sim::sim::truth::Truth, ft: f64, mn: f64, lo: f64, hi: f64) -> f64 {
    let holds = |n: f64| truth.evaluate(ft, mn, n, truth.half_width_m(n)).utilisation <= 1.0;
    if holds(lo) {
        return lo;
    }
    if !holds(hi) {
        return hi;
    }
    let (mut lo, mut hi) = (lo, hi);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[test]
fn the_oracle_is_the_least_holding_force() {
    let trial = trial("twist", 3, 0);
    let truth = build_truth(&trial.scene).unwrap();
    let cfg = controller_config(&trial.scene).unwrap();
    let (lo, hi) = (cfg.n_min_n, cfg.n_max_n);
    let loads = [
        (0.0, 0.0),
        (0.3, 0.0),
        (1.0, 0.002),
        (0.5, 0.01),
        (2.0, 0.004),
        (0.05, 0.03),
        (50.0, 0.0),
    ];
    let mut previous = None;
    for (ft, mn) in loads {
        let want = brute_force(&truth, ft, mn, lo, hi);
        for guess in [
            None,
            previous,
            Some(0.5 * want),
            Some(1.01 * want),
            Some(hi),
        ] {
            let got = least_holding_force_n(&truth, ft, mn, lo, hi, guess);
            assert!(
                (got - want).abs() <= 2e-6 * want,
                "load ({ft}, {mn}), guess {guess:?}: {got} against {want}"
            );
            let u = truth
                .evaluate(ft, mn, got, truth.half_width_m(got))
                .utilisation;
            assert!(u <= 1.0 || got == hi, "{u}");
        }
        previous = Some(want);
    }
    assert_eq!(least_holding_force_n(&truth, 0.0, 0.0, lo, hi, None), lo);
    assert_eq!(least_holding_force_n(&truth, 50.0, 0.0, lo, hi, None), hi);
    // The time average never exceeds N_max and is at least N_min.
    let m = mean_oracle_force_n(&trial.scene, &truth, lo, hi).unwrap();
    assert!(m >= lo && m <= hi, "{m}");
}

#[test]
fn a_drop_is_more_than_10_mm_or_0_2_rad() {
    assert_eq!(DROP_DISTANCE_M, 0.01);
    assert_eq!(DROP_ROTATION_RAD, 0.2);
    assert!(!is_drop(0.0, 0.0));
    assert!(!is_drop(0.01, 0.2));
    assert!(is_drop(0.010_001, 0.0));
    assert!(is_drop(0.0, 0.200_001));
    assert!(is_drop(0.0, -0.3));
    // The overload scene drops; the lift is held with no drop.
    let t = scene_text("overload");
    let s = Scene::parse(&t).unwrap();
    let out = run::run(&s, "constant", None).unwrap();
    assert!(out.summary.dropped);
    assert!(is_drop(
        out.summary.slip_distance_m,
        out.summary.slip_rotation_rad
    ));
    let t = scene_text("lift_hold");
    let s = Scene::parse(&t).unwrap();
    assert!(!run::run(&s, "softgrip", None).unwrap().summary.dropped);
}

fn sensor(settings: &str) -> SlipSensor {
    let t = format!(
        "{}\n[effect.slip_sensor]\n{settings}\n",
        scene_text("lift_hold").replace(
            "effects = [\"gravity\", \"sensor_noise\"]",
            "effects = [\"gravity\", \"slip_sensor\"]"
        )
    );
    let scene = Scene::parse(&t).unwrap();
    let Some(EffectSettings::SlipSensor(s)) = scene.effect_settings.last() else {
        panic!("no slip sensor in {:?}", scene.effect_settings);
    };
    SlipSensor::new(s, effects::rng(scene.seed, "slip_sensor"))
}

fn frame() -> SensorFrame {
    SensorFrame {
        seq: 0,
        timestamp_us: 0,
        tangential_force_n: [0.0; 2],
        torsional_moment_nm: 0.0,
        normal_force_n: 1.0,
        slip: SlipSignal::None,
    }
}

/// Drives the sensor with episodes of `len` ticks (incipient for the first half, then
/// sliding) every `period` ticks, `n` times; returns the reported signals.
fn drive(s: &mut SlipSensor, n: usize, period: usize, len: usize) -> Vec<SlipSignal> {
    let mut w = World {
        dt_s: 1e-3,
        ..World::default()
    };
    let mut out = Vec::new();
    for k in 0..n * period {
        let phase = k % period;
        w.true_utilisation = if phase < len { 0.95 } else { 0.5 };
        w.sliding = phase >= len / 2 && phase < len;
        let mut f = frame();
        s.sense(&w, &mut f);
        out.push(f.slip);
    }
    out
}

#[test]
fn the_slip_sensor_reports_late_misses_and_false_alarms_at_their_rates() {
    // Latency: 5 ms at 1 kHz, no misses, no false alarms. In a run the world the sensor
    // reads is already the previous tick's, so the sensor adds 4 ticks to it: 5 in all.
    let mut s = sensor("miss_probability = 0.0\nfalse_alarm_rate_hz = 0.0");
    let got = drive(&mut s, 10, 100, 20);
    for (k, g) in got.iter().enumerate() {
        let phase = (k + 100 - 4) % 100;
        let want = if k < 4 || phase >= 20 {
            SlipSignal::None
        } else if phase < 10 {
            SlipSignal::Incipient
        } else {
            SlipSignal::Gross
        };
        assert_eq!(*g, want, "tick {k}");
    }
    // Misses, per episode: 3000 episodes at 0.3.
    let mut s = sensor("miss_probability = 0.3\nfalse_alarm_rate_hz = 0.0\nlatency_s = 0.001");
    let got = drive(&mut s, 3000, 50, 20);
    let mut missed = 0;
    for e in got.chunks(50) {
        let reported = e.iter().filter(|x| **x != SlipSignal::None).count();
        assert!(reported == 0 || reported == 20, "{reported}");
        missed += usize::from(reported == 0);
    }
    let p = missed as f64 / 3000.0;
    assert!(
        (p - 0.3).abs() < 4.0 * (0.3f64 * 0.7 / 3000.0).sqrt(),
        "{p}"
    );
    // False alarms: 5 Hz over 1000 s of a quiet contact.
    let mut s = sensor("miss_probability = 0.0\nfalse_alarm_rate_hz = 5.0");
    let got = drive(&mut s, 1000, 1000, 0);
    let alarms = got.iter().filter(|x| **x == SlipSignal::Incipient).count() as f64;
    assert!((alarms - 5000.0).abs() < 4.0 * 5000f64.sqrt(), "{alarms}");
    assert!(got.iter().all(|x| *x != SlipSignal::Gross));
}

fn bits(s: &[Sample]) -> Vec<[u64; 4]> {
    s.iter()
        .map(|x| {
            [
                x.n_cmd_n.to_bits(),
                x.n_true_n.to_bits(),
                x.utilisation.to_bits(),
                x.slip_distance_m.to_bits(),
            ]
        })
        .collect()
}

#[test]
fn an_unlisted_slip_sensor_changes_nothing() {
    let base = scene_text("shake");
    let other = format!(
        "{base}\n[effect.slip_sensor]\nmiss_probability = 1.0\nfalse_alarm_rate_hz = 900.0\n"
    );
    for t in [&base, &other] {
        let s = Scene::parse(t).unwrap();
        assert!(!s.effects.iter().any(|e| e == "slip_sensor"));
    }
    let a = run::run(&Scene::parse(&base).unwrap(), "softgrip", None).unwrap();
    let b = run::run(&Scene::parse(&other).unwrap(), "softgrip", None).unwrap();
    assert_eq!(bits(&a.samples), bits(&b.samples));
    assert_eq!(
        a.summary.mean_normal_force_n.to_bits(),
        b.summary.mean_normal_force_n.to_bits()
    );
}

#[test]
fn the_direct_link_equals_the_pty_link() {
    for (name, controller) in [("lift_hold", "softgrip"), ("faulty_link", "softgrip-table")] {
        let t = scene_text(name);
        let s = Scene::parse(&t).unwrap();
        let go = |link| run_with(&s, controller, &link, None, RunOptions::default()).unwrap();
        let pty = go(LinkKind::InProcess);
        let direct = go(LinkKind::Direct);
        assert_eq!(bits(&pty.samples), bits(&direct.samples), "{name}");
        let (p, d) = (&pty.summary, &direct.summary);
        assert_eq!(p.slip_events, d.slip_events);
        assert_eq!(p.dropped, d.dropped);
        assert_eq!(
            p.mean_normal_force_n.to_bits(),
            d.mean_normal_force_n.to_bits()
        );
        assert_eq!(
            p.peak_normal_force_n.to_bits(),
            d.peak_normal_force_n.to_bits()
        );
        assert_eq!(p.slip_distance_m.to_bits(), d.slip_distance_m.to_bits());
        assert_eq!(p.link.frames_received, d.link.frames_received, "{name}");
        assert_eq!(p.link.frames_corrupt, d.link.frames_corrupt, "{name}");
    }
}

#[test]
fn the_controller_believes_its_own_mu() {
    let t = scene_text("lift_hold").replace("[controller]", "[controller]\nmu = 0.6");
    let s = Scene::parse(&t).unwrap();
    assert_eq!(s.finger.mu, 0.8);
    assert_eq!(controller_config(&s).unwrap().mu, 0.6);
    assert_eq!(build_truth(&s).unwrap().mu(), 0.8);
    // Without it the controller believes the finger's.
    let s = Scene::parse(&scene_text("lift_hold")).unwrap();
    assert_eq!(controller_config(&s).unwrap().mu, s.finger.mu);
    // The measured actuator reaches the configuration.
    let t = scene_text("lift_hold").replace(
        "[controller]",
        "[controller]\nactuator_lag_s = 0.02\nactuator_slew_n_per_s = 250.0",
    );
    let cfg = controller_config(&Scene::parse(&t).unwrap()).unwrap();
    assert_eq!(cfg.actuator_lag_s, 0.02);
    assert_eq!(cfg.actuator_slew_n_per_s, 250.0);
}

/// Runs `host-sim bench ARGS --quiet --out OUT`.
fn bench_cli(args: &[&str], out: &std::path::Path) -> std::process::ExitStatus {
    std::process::Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .arg("bench")
        .args(args)
        .args(["--quiet", "--out"])
        .arg(out)
        .status()
        .unwrap()
}

#[test]
fn the_command_writes_json_and_both_plots() {
    let out = std::env::temp_dir().join(format!("softgrip-bench-{}", std::process::id()));
    let exe = env!("CARGO_BIN_EXE_host-sim");
    let args = [
        "--family",
        "twist",
        "--trials",
        "3",
        "--controller",
        "constant",
    ];
    assert!(bench_cli(&args, &out).success());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("bench.json")).unwrap()).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), sweep::CONSTANT_GRID_N.len());
    for key in [
        "family",
        "controller",
        "knob",
        "knob_value",
        "default",
        "trials",
        "holdable",
        "drops",
        "drops_holdable",
        "drop_rate",
        "drop_rate_ci95",
        "force_over_oracle",
        "mean_force_n",
        "slip_distance_m",
    ] {
        assert!(rows[0].get(key).is_some(), "{key}");
    }
    assert_eq!(rows.iter().filter(|r| r["default"] == true).count(), 1);
    assert!(
        std::fs::metadata(out.join("pareto-twist.svg"))
            .unwrap()
            .len()
            > 1000
    );
    let png = std::fs::read(out.join("pareto-twist.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let bad = std::process::Command::new(exe)
        .args(["bench", "--family", "nope", "--quiet"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn the_wilson_interval_brackets_the_rate() {
    let [lo, hi] = stats::wilson95(0, 200);
    assert!(lo < 1e-12);
    assert!((hi - 0.01884).abs() < 1e-4, "{hi}");
    let [lo, hi] = stats::wilson95(10, 20);
    assert!((lo - 0.2993).abs() < 1e-3 && (hi - 0.7007).abs() < 1e-3);
}

/// A softgrip sweep (safety 1 and 2) beside a constant grip of 1, 2 and 3 N, for the
/// clairvoyant constant's tests.
fn softgrip_and_constant_sweeps() -> [sweep::Sweep; 2] {
    use host_sim::sim::controllers::ControllerKind;
    [
        sweep::Sweep {
            controller: ControllerKind::SoftgripTable,
            knob: "safety",
            values: &[1.0, 2.0],
            default: 1.0,
        },
        sweep::Sweep {
            controller: ControllerKind::Constant,
            knob: "force_n",
            values: &[1.0, 2.0, 3.0],
            default: 3.0,
        },
    ]
}

/// A hand-made trial of [`softgrip_and_constant_sweeps`]: holdable or not, its oracle's
/// mean force, and whether each of the three constant grips drops it; softgrip's two runs
/// hold at 0.5 N.
fn hand_made_trial(holdable: bool, oracle: f64, drops: [bool; 3]) -> sweep::TrialResult {
    let run = |dropped: bool, mean: f64| sweep::RunRow {
        dropped,
        slip_events: 0,
        slip_distance_m: 0.0,
        mean_force_n: mean,
        peak_force_n: mean,
    };
    sweep::TrialResult {
        true_mu: 1.0,
        mu_ratio: 1.0,
        sensor: false,
        holdable,
        oracle_mean_n: oracle,
        // softgrip's runs hold at 0.5 N: never a constant grip's.
        runs: [run(false, 0.5), run(false, 0.5)]
            .into_iter()
            .chain(drops.iter().zip([1.0, 2.0, 3.0]).map(|(d, n)| run(*d, n)))
            .collect(),
    }
}

/// Three holdable hand-made trials, held from 1 N (oracle 1 N), from 2 N (oracle 1 N) and
/// from 3 N (oracle 2 N), and one not holdable.
fn hand_made_trials() -> [sweep::TrialResult; 4] {
    [
        hand_made_trial(true, 1.0, [false, false, false]), // 1 N holds: 1.0
        hand_made_trial(true, 1.0, [true, false, false]),  // 2 N: 2.0
        hand_made_trial(true, 2.0, [true, true, false]),   // 3 N over 2 N: 1.5
        hand_made_trial(false, 1.0, [true, true, true]),   // not holdable: left out
    ]
}

/// The clairvoyant constant grip: per holdable trial, the least constant of the grid that
/// holds it (a reference), here on three hand-made trials against a grid of 1, 2 and 3 N
/// beside a softgrip sweep whose columns it must skip.
#[test]
fn the_clairvoyant_constant_is_the_least_holding_grip_of_each_holdable_trial() {
    let sweeps = softgrip_and_constant_sweeps();
    let results = hand_made_trials();
    let refs: Vec<&sweep::TrialResult> = results.iter().collect();
    let c = stats::clairvoyant_constant("lift-hold", &sweeps, &refs).unwrap();
    assert_eq!(c.trials, 3);
    assert!((c.mean_force_over_oracle - 1.5).abs() < 1e-12, "{c:?}");
    assert!((c.median_force_over_oracle - 1.5).abs() < 1e-12, "{c:?}");
    assert!(stats::clairvoyant_constant("lift-hold", &sweeps[..1], &refs).is_none());
}

/// At the hand's limit with N_max = 3 N: only a trial that no grip below 95 % of it
/// (2.85 N) holds; for a 2.1 N hand (1.995 N), the 2 N trial is one too (the trials of
/// the clairvoyant constant's test).
#[test]
fn a_trial_is_at_the_hands_limit_when_no_grip_below_95_percent_of_it_holds() {
    let sweeps = softgrip_and_constant_sweeps();
    let results = hand_made_trials();
    let refs: Vec<&sweep::TrialResult> = results.iter().collect();
    let limit = |n_max: f64| -> Vec<Option<bool>> {
        refs.iter()
            .map(|r| stats::at_limit(&sweeps, r, n_max))
            .collect()
    };
    assert_eq!(
        limit(3.0),
        [Some(false), Some(false), Some(true), Some(false)]
    );
    assert_eq!(
        limit(2.1),
        [Some(false), Some(true), Some(true), Some(false)]
    );
    assert_eq!(stats::at_limit(&sweeps[..1], refs[2], 3.0), None);
}

/// The rows count the trials at the hand's limit, for the bench's hand (N_max = 20 N) and
/// a grid of 1, 19 and 20 N: trials held from 1 N, from 19 N (95 % of N_max: at the
/// limit), only at 20 N (at the limit), and none; softgrip's first setting drops the
/// first two.
#[test]
fn the_rows_count_the_trials_and_drops_at_the_hands_limit() {
    let [softgrip, constant] = softgrip_and_constant_sweeps();
    let sweeps = [
        softgrip,
        sweep::Sweep {
            values: &[1.0, 19.0, 20.0],
            ..constant
        },
    ];
    let mut results = [
        hand_made_trial(true, 1.0, [false, false, false]),
        hand_made_trial(true, 1.0, [true, false, false]),
        hand_made_trial(true, 1.0, [true, true, false]),
        hand_made_trial(false, 1.0, [true, true, true]),
    ];
    results[0].runs[0].dropped = true;
    results[1].runs[0].dropped = true;
    let refs: Vec<&sweep::TrialResult> = results.iter().collect();
    let rows = stats::rows("twist", None, &sweeps, &refs);
    assert_eq!(rows[0].at_limit, Some(2));
    assert_eq!(
        (rows[0].drops_holdable, rows[0].drops_at_limit),
        (2, Some(1))
    );
    assert_eq!(rows[1].drops_at_limit, Some(0));
    assert_eq!(
        stats::rows("twist", None, &sweeps[..1], &refs)[0].at_limit,
        None
    );
}

/// A drop is a slide past 10 mm or a turn past 0.2 rad, and slip stops accumulating at
/// the drop: the rows count the holdable drops with at most 10 mm of slide as turns, and
/// the family's turn line sums them per controller over its settings.
#[test]
fn a_drop_with_less_than_a_slides_distance_is_counted_as_a_turn() {
    use host_sim::bench::report;
    use host_sim::bench::sweep::{RunRow, Sweep, TrialResult};
    use host_sim::sim::controllers::ControllerKind;
    use host_sim::sim::run::DROP_DISTANCE_M;
    let sweeps = [Sweep {
        controller: ControllerKind::SoftgripTable,
        knob: "safety",
        values: &[1.0, 2.0],
        default: 2.0,
    }];
    let run = |dropped: bool, slide_m: f64| RunRow {
        dropped,
        slip_events: 1,
        slip_distance_m: slide_m,
        mean_force_n: 1.0,
        peak_force_n: 1.0,
    };
    let trial = |holdable: bool, runs: [RunRow; 2]| TrialResult {
        true_mu: 1.0,
        mu_ratio: 1.0,
        sensor: false,
        holdable,
        oracle_mean_n: 1.0,
        runs: runs.to_vec(),
    };
    let results = [
        // Lost by sliding 10 mm (it may have turned too): a slide.
        trial(true, [run(true, 1.5 * DROP_DISTANCE_M), run(false, 0.0)]),
        // Lost with 3 mm of slide: only the turn can have dropped it.
        trial(true, [run(true, 0.003), run(true, DROP_DISTANCE_M)]),
        // Slid 4 mm and held: no drop, no turn.
        trial(true, [run(false, 0.004), run(false, 0.004)]),
        // Not holdable: counted in the drops, not in the holdable ones nor the turns.
        trial(false, [run(true, 0.001), run(true, 0.001)]),
    ];
    let refs: Vec<&TrialResult> = results.iter().collect();
    let rows = stats::rows("twist", None, &sweeps, &refs);
    let counts: Vec<_> = rows
        .iter()
        .map(|r| (r.drops, r.drops_holdable, r.drops_turned))
        .collect();
    assert_eq!(counts, [(3, 2, 1), (2, 1, 1)]);
    assert!(!stats::lost_by_turning(&run(false, 0.0)));
    assert_eq!(
        report::turn_line("twist", &rows),
        "twist: holdable drops that were turns past 0.2 rad, not slides, over every \
         setting: softgrip-table 2/3\n"
    );
    let held = [trial(true, [run(false, 0.0), run(false, 0.0)])];
    let refs: Vec<&TrialResult> = held.iter().collect();
    assert_eq!(
        report::turn_line("twist", &stats::rows("twist", None, &sweeps, &refs)),
        ""
    );
}

/// `bench --trace` keeps each seed's trials apart (a trial's index repeats across seeds)
/// and writes each trial's scene beside its traces, and the scene replays a traced run
/// sample for sample.
#[test]
fn a_trace_keeps_seeds_apart_and_its_scene_replays_the_run() {
    let out = std::env::temp_dir().join(format!("softgrip-trace-{}", std::process::id()));
    let args = ["--family", "lift-hold", "--seeds", "5,6", "--trials", "1"];
    let args = [&args[..], &["--controller", "fixed-torsion", "--trace"]].concat();
    assert!(bench_cli(&args, &out).success());
    let mut scenes = Vec::new();
    for seed in ["5", "6"] {
        let dir = out.join("trace").join("lift-hold").join(seed);
        let text = std::fs::read_to_string(dir.join("0000-scene.toml")).unwrap();
        let scene = Scene::parse(&text).unwrap();
        let knob = sweep::with_knob(
            &scene,
            host_sim::sim::controllers::ControllerKind::FixedTorsion,
            1.3,
        );
        let options = RunOptions {
            skip_samples: false,
            truth: None,
            untimed: true,
        };
        let replay = run_with(&knob, "fixed-torsion", &LinkKind::Direct, None, options).unwrap();
        let path = out.join(format!("replay-{seed}.csv"));
        host_sim::sim::report::write_csv(&path, &replay.samples).unwrap();
        let traced = std::fs::read(dir.join("0000-fixed-torsion-safety1.3.csv")).unwrap();
        assert!(traced.len() > 1000, "seed {seed}");
        assert!(
            std::fs::read(&path).unwrap() == traced,
            "seed {seed}: the replay differs"
        );
        scenes.push(text);
    }
    assert_ne!(
        scenes[0], scenes[1],
        "the two seeds' trial 0 must be two trials"
    );
    let _ = std::fs::remove_dir_all(&out);
}
