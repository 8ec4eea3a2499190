//! `calibrate --friction-contact` on fingers the model does not describe: the bench's
//! brush fingers, drawn from the 24 streams of `brush_model_fit` (no bench seed uses
//! them), each measured by the bench's lab (6 forces, 2 % noise).
//!
//! - The joint fit compromises on these fingers: somewhere it asks a pure force for more
//!   than 5 % over what the finger needs, or a pure torsion for more than 5 % under.
//! - With the friction contact, table mode asks every pure force within 5 % of its onset
//!   and every pure torsion within -5 %/+6 %, at 1, 4 and 12 N.
//! - The bench's lab calibrates softgrip by the same code: the same `μ`, the same refit,
//!   and `c` and the half-length within 2 % (it fits on a shared, finer grid).
//! - On the command line: the JSON names what moved, the finger TOML carries the
//!   refitted half-length, and `--conservative` with `--friction-contact` is refused.
//!
//! `cargo test --release -p host-sim --test calibrate_friction_contact -- --nocapture`
//! prints the ratios (about 20 s on the 2-core VM).

mod common;

use host_sim::bench::families::{N_MAX_N, N_MIN_N};
use host_sim::bench::lab;
use host_sim::bench::trial_finger::{BenchPlant, FingerSource, TrialFinger};
use host_sim::experiment::Rig;
use rand::{Rng, SeedableRng};
use softgrip::controller::{Controller, ControllerConfig, FingerShape, Libm, Mode};
use softgrip_calibrate::friction_contact::Refit;
use softgrip_calibrate::lab_csv::{write_indentation, write_slip};
use softgrip_calibrate::{calibrate, Calibration, Setup};

const STREAMS: std::ops::Range<u64> = 5000..5024;
const FORCES_N: [f64; 3] = [1.0, 4.0, 12.0];

struct Case {
    finger: TrialFinger,
    rig: Box<dyn Rig>,
    data: lab::LabData,
}

fn case(stream: u64) -> Case {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(stream);
    let source = FingerSource::Drawn(BenchPlant::Brush);
    let finger = TrialFinger::draw(&source, &mut r, N_MAX_N).unwrap();
    let rig = finger.rig(N_MIN_N, N_MAX_N).unwrap();
    let data = lab::measure(rig.as_ref(), r.random());
    Case { finger, rig, data }
}

fn joint(c: &Case) -> Calibration {
    let setup = Setup {
        shape: c.finger.shape(),
        half_length_m: c.finger.half_length_m(),
    };
    calibrate(&setup, "ind", &c.data.indentation, "slip", &c.data.onsets).unwrap()
}

/// Table mode's force for the finger's pure-force and pure-torsion onsets, over the
/// onsets' normal force, at each of [`FORCES_N`].
fn pure_ratios(cal: &Calibration, c: &Case) -> Vec<(f64, f64)> {
    let ctl = Controller::<f64, Libm>::new(ControllerConfig {
        mu: cal.mu.value,
        shape: c.finger.shape(),
        k: cal.k.value,
        c_m_per_n_gamma: cal.c.value,
        gamma: cal.gamma.value,
        half_length_m: cal.half_length_m,
        n_min_n: N_MIN_N,
        n_max_n: N_MAX_N,
        mode: Mode::Table,
        ..ControllerConfig::DEFAULT
    })
    .unwrap();
    let ask = |f: f64, m: f64, n: f64| ctl.slip_force(f, m).unwrap().force_n / n;
    FORCES_N
        .iter()
        .map(|&n| {
            let f0 = c.rig.slip_onset(n, 1.0, 0.0).unwrap().0;
            let m0 = c.rig.slip_onset(n, 0.0, 1.0).unwrap().1;
            (ask(f0, 0.0, n), ask(0.0, m0, n))
        })
        .collect()
}

#[test]
fn on_brush_fingers_the_friction_contact_asks_what_pure_loads_need() {
    let (mut joint_worst, mut fc_range) = ((1.0f64, 1.0f64), (f64::INFINITY, 0.0f64));
    let mut refits = [0usize; 3];
    for stream in STREAMS {
        let c = case(stream);
        let joint = joint(&c);
        let fc = joint.with_friction_contact("slip", &c.data.onsets).unwrap();
        let how = fc.friction_contact.as_ref().unwrap().refit;
        refits[how as usize] += 1;
        for ((jf, jm), (ff, fm)) in pure_ratios(&joint, &c)
            .into_iter()
            .zip(pure_ratios(&fc, &c))
        {
            joint_worst = (joint_worst.0.max(jf), joint_worst.1.min(jm));
            fc_range = (fc_range.0.min(ff.min(fm)), fc_range.1.max(ff.max(fm)));
            let at = format!("finger {stream} ({how:?}): force {ff:.3}, torsion {fm:.3}");
            assert!((ff - 1.0).abs() < 0.05, "pure force: {at}");
            assert!((0.95..1.06).contains(&fm), "pure torsion: {at}");
        }
        // The bench's lab: the same code on its shared grid.
        let b = lab::calibrate(&c.data, c.finger.shape(), c.finger.half_length_m()).unwrap();
        assert_eq!(b.mu, fc.mu.value, "finger {stream}: mu");
        assert_eq!(b.k, fc.k.value);
        let rel = |a: f64, b: f64| (a / b - 1.0).abs();
        assert!(
            rel(b.c, fc.c.value) < 0.02,
            "finger {stream}: c {} {}",
            b.c,
            fc.c.value
        );
        assert!(
            rel(b.half_length_m, fc.half_length_m) < 0.02,
            "finger {stream}: half-length {} {}",
            b.half_length_m,
            fc.half_length_m
        );
        assert_eq!(
            b.half_length_m != c.finger.half_length_m(),
            how == Refit::HalfLength
        );
    }
    println!(
        "joint fit: pure force up to {:.3}, pure torsion down to {:.3}; friction contact: \
         {:.3}-{:.3}; refits (scale, half-length, neither): {refits:?}",
        joint_worst.0, joint_worst.1, fc_range.0, fc_range.1
    );
    assert!(
        joint_worst.0 > 1.05 || joint_worst.1 < 0.95,
        "the joint fit does not compromise on these fingers: {joint_worst:?}"
    );
    assert!(refits[0] > 0 && refits[1] > 0, "{refits:?}");
}

#[test]
fn on_the_command_line_the_refitted_half_length_reaches_the_finger_toml() {
    // The first stream whose friction contact refits the half-length.
    let (c, fc) = STREAMS
        .map(case)
        .find_map(|c| {
            let fc = joint(&c)
                .with_friction_contact("slip", &c.data.onsets)
                .unwrap();
            (fc.friction_contact.as_ref().unwrap().refit == Refit::HalfLength).then_some((c, fc))
        })
        .unwrap();
    assert_eq!(c.finger.shape(), FingerShape::Rect);
    let d = std::env::temp_dir().join(format!("softgrip-fc-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let (ind, slip, toml) = (d.join("ind.csv"), d.join("slip.csv"), d.join("finger.toml"));
    std::fs::write(&ind, write_indentation(&c.data.indentation)).unwrap();
    std::fs::write(&slip, write_slip(&c.data.onsets)).unwrap();
    let l = c.finger.half_length_m().to_string();
    let base = [
        "calibrate",
        "--indentation",
        ind.to_str().unwrap(),
        "--slip",
        slip.to_str().unwrap(),
        "--half-length",
        &l,
        "--friction-contact",
    ];
    let mut args = base.to_vec();
    args.extend(["--format", "json", "--out", toml.to_str().unwrap()]);
    let (code, out, err) = common::host_sim(&args);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["friction_contact"]["refit"], "half_length", "{out}");
    let num = |p: &serde_json::Value| p.as_f64().unwrap();
    assert_eq!(num(&v["half_length_m"]), fc.half_length_m);
    assert_eq!(num(&v["mu"]["value"]), fc.mu.value);
    assert_eq!(
        num(&v["friction_contact"]["geometric_half_length_m"]),
        c.finger.half_length_m()
    );
    let text = std::fs::read_to_string(&toml).unwrap();
    let line = format!(
        "half_length_m = {}  # friction's, refitted",
        fc.half_length_m
    );
    assert!(text.contains(&line), "{text}");
    assert!(
        text.contains("# friction contact: mu from the pure-force onsets"),
        "{text}"
    );
    // Conservative values are the joint fit's: the two flags are refused together.
    let mut args = base.to_vec();
    args.push("--conservative");
    let (code, _, err) = common::host_sim(&args);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--conservative") && err.contains("--friction-contact"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
