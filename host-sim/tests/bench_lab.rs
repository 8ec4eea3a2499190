//! The bench's lab and oracle on a drawn finger: every controller's beliefs come from
//! the lab's rows (close to the truth on a finger softgrip models, and never copied from
//! the plant), and the brush finger's tabulated limit agrees with its own onsets.

use host_sim::bench::families::{self, Ranges, N_MAX_N, N_MIN_N};
use host_sim::bench::lab;
use host_sim::bench::onset_table::OnsetTable;
use host_sim::bench::oracle::TrueLimit;
use host_sim::bench::trial_finger::{BenchPlant, FingerSource, TrialFinger};
use host_sim::experiment::FingerSpec;
use rand::SeedableRng;
use softgrip::controller::FingerShape;
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};

#[test]
fn the_lab_recovers_a_limit_surface_finger_within_its_noise() {
    for shape in [FingerShape::Rect, FingerShape::Disc] {
        let spec = FingerSpec {
            shape,
            mu: 0.9,
            k: 2.0,
            c: 2.5e-3,
            gamma: 0.4,
            half_length_m: 0.01,
            skew: None,
        };
        let rig = TrialFinger::Fls(spec).rig(N_MIN_N, N_MAX_N).unwrap();
        let b = lab::calibrate(&lab::measure(rig.as_ref(), 3), shape, 0.01).unwrap();
        // 2 % noise on 6 rows each: the means are good to about 1-2 %.
        assert!((b.mu / 0.9 - 1.0).abs() < 0.03, "{shape:?} mu {}", b.mu);
        assert!(
            (b.cone_mu / 0.9 - 1.0).abs() < 0.03,
            "{shape:?} {}",
            b.cone_mu
        );
        assert!((b.gamma - 0.4).abs() < 0.05, "{shape:?} gamma {}", b.gamma);
        // Its `c` fits the torsion test, so the half-length stays the geometric one.
        assert_eq!(b.half_length_m, 0.01, "{shape:?}");
        // softgrip's contact law is the one friction sees: its torsion limit
        // mu*N*a(N)*pitch(k, l/a) is the surface's, within the noise.
        let pitch = |a: f64| {
            let shape = match shape {
                FingerShape::Rect => Shape::Rect { aspect: 0.01 / a },
                FingerShape::Disc => Shape::Disc,
            };
            let order = QuadratureOrder::DEFAULT;
            let config = FlsConfig {
                shape,
                k: b.k,
                skew: None,
                order,
            };
            FlsModel::<f64>::new(config).unwrap().pitch()
        };
        for n in [0.5f64, 4.0, 16.0] {
            let a = b.c * n.powf(b.gamma);
            let model = b.mu * n * a * pitch(a);
            let truth = rig.slip_onset(n, 0.0, 1e-3).unwrap().1;
            assert!(
                (model / truth - 1.0).abs() < 0.05,
                "{shape:?} M({n}) {model} {truth}"
            );
        }
        // The fixed patch's arm is the surface's torsion arm at some force in the lab's
        // range: between the arms at its least and greatest force.
        let arm = |n: f64| rig.slip_onset(n, 0.0, 1e-3).unwrap().1 / (0.9 * n);
        let (lo, hi) = (arm(lab::LAB_FORCES_N[0]), arm(lab::LAB_FORCES_N[5]));
        assert!(
            b.torsion_arm_m > 0.97 * lo && b.torsion_arm_m < 1.03 * hi,
            "{shape:?} arm {} not in [{lo}, {hi}]",
            b.torsion_arm_m
        );
    }
}

#[test]
fn no_controller_reads_the_plant() {
    let brush = FingerSource::Drawn(BenchPlant::Brush);
    for family in ["lift-hold", "mu-mismatch"] {
        for i in 0..2 {
            let t = families::trial_on(&brush, &Ranges::default(), family, 11, i).unwrap();
            let c = &t.scene.controller;
            let b = t.beliefs;
            // What the controllers are told is the lab's calibration, not the plant's
            // parameters: its mu differs from the plant's (by the lab's noise, and the
            // surface change of mu-mismatch).
            assert_eq!(c.number("mu"), Some(b.mu));
            assert_eq!(c.number("c_m_per_n_gamma"), Some(b.c));
            assert_eq!(c.number("half_length_m"), Some(b.half_length_m));
            assert_eq!(c.baseline_mu, Some(b.cone_mu));
            assert_eq!(c.baseline_torsion_arm_m, Some(b.torsion_arm_m));
            assert_ne!(b.mu, t.scene.finger.mu, "{family} {i}");
            // The lab's mu is the finger's gross-slip onset, between its kinetic and
            // static friction (kinetic 0.75-0.95 of static), up to the lab's noise.
            let seen = b.mu * t.mu_ratio / t.scene.finger.mu;
            assert!((0.7..1.05).contains(&seen), "{family} {i}: {seen}");
            // Nothing about the actuator, unless asked.
            assert!(c.number("actuator_lag_s").is_none());
        }
    }
    let told = Ranges {
        tell_actuator: true,
        ..Ranges::default()
    };
    let t = families::trial_on(&brush, &told, "shake", 11, 0).unwrap();
    assert!(t.scene.controller.number("actuator_lag_s").unwrap() > 0.0);
    let t = families::trial_on(&brush, &Ranges::default(), "shake", 11, 0).unwrap();
    assert!(t.scene.controller.number("actuator_lag_s").is_none());
    assert!(t.scene.effects.iter().any(|e| e == "actuator"));
}

#[test]
fn the_brush_oracle_table_agrees_with_the_finger_s_own_onsets() {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let source = FingerSource::Drawn(BenchPlant::Brush);
    let mut worst: f64 = 0.0;
    for _ in 0..2 {
        let finger = TrialFinger::draw(&source, &mut r, N_MAX_N).unwrap();
        let rig = finger.rig(N_MIN_N, N_MAX_N).unwrap();
        let table = OnsetTable::build(rig.as_ref(), N_MIN_N, N_MAX_N).unwrap();
        // Off the table's nodes: forces between its nodes, directions between its angles.
        for n in [0.35, 2.7, 13.0] {
            for (ft, mn) in [(1.0, 0.0), (1.0, 2e-3), (0.2, 3e-3), (0.0, 1e-3)] {
                let (f, m) = rig.slip_onset(n, ft, mn).unwrap();
                let at = |s: f64| table.holds(s * f, s * m, n);
                // The true onset holds just inside and fails just outside, to 3 %.
                assert!(at(0.97), "{n} N, ({ft}, {mn})");
                assert!(!at(1.03), "{n} N, ({ft}, {mn})");
                // The table's own edge along this ray.
                let (mut lo, mut hi) = (0.5, 2.0);
                for _ in 0..40 {
                    let mid = 0.5 * (lo + hi);
                    if at(mid) {
                        lo = mid
                    } else {
                        hi = mid
                    }
                }
                worst = worst.max((lo - 1.0).abs());
            }
        }
        assert!(TrueLimit::holds(&table, 0.0, 0.0, N_MIN_N));
        assert!(!TrueLimit::holds(&table, f64::INFINITY, 0.0, N_MAX_N));
    }
    println!("worst relative error of the tabulated onset: {worst:.4}");
}

#[test]
fn every_trial_stream_draws_a_brush_finger_that_carries_n_max() {
    // Seed 1007's twist trial 6 found none in 32 draws, and the whole bench stopped
    // with an error; it takes more than that (and any stream finds one in 1 024).
    let source = FingerSource::Drawn(BenchPlant::Brush);
    for s in 0..500u64 {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(s);
        assert!(
            TrialFinger::draw(&source, &mut r, N_MAX_N).is_some(),
            "stream {s}"
        );
    }
    let t = families::trial_on(&source, &Ranges::default(), "twist", 1007, 6);
    assert!(t.is_ok(), "{:?}", t.err());
}
