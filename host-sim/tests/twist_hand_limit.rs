//! `twist` trials at the hand's limit, on the brush finger: why no controller that grips
//! only once it sees the load can be held to "no drop" on such trials. The trials are
//! 2016/10 and 2016/7 of the bench's `twist` family (a seed that no run scores, tunes or
//! chooses a default on; docs/decisions/twist-hand-limit.md). No timing
//! assertions.
//!
//! `cargo test --release -p host-sim --test twist_hand_limit -- --nocapture` prints the
//! figures docs/decisions/twist-hand-limit.md quotes.

use host_sim::bench::families::{self, Ranges};
use host_sim::bench::sweep;
use host_sim::bench::trial_finger::{BenchPlant, FingerSource};
use host_sim::sim::controllers::{ControllerKind, LinkKind};
use host_sim::sim::record::Sample;
use host_sim::sim::run::{run_with, RunOptions, DROP_ROTATION_RAD};

/// `N_max` of every bench trial \[N\].
const N_MAX_N: f64 = 20.0;

/// One run of the trial: its samples.
fn run(trial: &families::Trial, kind: ControllerKind, name: &str, knob: f64) -> Vec<Sample> {
    let scene = sweep::with_knob(&trial.scene, kind, knob);
    let options = RunOptions {
        skip_samples: false,
        truth: Some(trial.truth.as_ref()),
        untimed: true,
    };
    run_with(&scene, name, &LinkKind::Direct, None, options)
        .unwrap()
        .samples
}

/// The greatest turn of a run \[rad\].
fn greatest_turn(samples: &[Sample]) -> f64 {
    samples
        .iter()
        .map(|s| s.slip_rotation_rad.abs())
        .fold(0.0, f64::max)
}

/// The time the grip first reached `N_max` (within 10 mN) and the turn then \[s, rad\].
fn at_n_max(samples: &[Sample]) -> (f64, f64) {
    let s = samples
        .iter()
        .find(|s| s.n_true_n >= N_MAX_N - 0.01)
        .expect("the grip reaches N_max");
    (s.t_s, s.slip_rotation_rad.abs())
}

#[test]
fn a_twist_at_the_hands_limit_turns_at_n_max_whatever_came_before() {
    let brush = FingerSource::Drawn(BenchPlant::Brush);
    let trial = families::trial_on(&brush, &Ranges::default(), "twist", 2016, 10).unwrap();

    // At the hand's limit: 20 N from the start holds it, 19 N from the start does not.
    let constant = |n| greatest_turn(&run(&trial, ControllerKind::Constant, "constant", n));
    let held = constant(N_MAX_N);
    let below = constant(19.0);
    println!("constant 20 N: greatest turn {held:.4} rad; 19 N: {below:.4} rad");
    assert!(held < DROP_ROTATION_RAD && below > DROP_ROTATION_RAD);

    // The moment I·α·sin(2πx) peaks 0.25 s into the twist, which starts at 0.2 s.
    let peak_s = 0.45;
    for safety in [1.75, 3.0, 10.0] {
        let samples = run(
            &trial,
            ControllerKind::SoftgripTable,
            "softgrip-table",
            safety,
        );
        let ((t_max, before), most) = (at_n_max(&samples), greatest_turn(&samples));
        println!(
            "softgrip-table {safety}: N_max at {t_max:.3} s, turned {before:.4} rad by then, \
             {most:.5} rad at most"
        );
        // However early the grip gets there, most of the turn comes after, at N_max.
        assert!(t_max < peak_s - 0.1, "safety {safety}: N_max at {t_max} s");
        assert!(most - before > 0.6 * DROP_ROTATION_RAD, "safety {safety}");
        if safety == 10.0 {
            // A grip at N_max 0.15 s before the peak, having turned a twentieth of a drop,
            // still turns more than the constant grip that held it from the start.
            assert!(before < 0.05 * DROP_ROTATION_RAD, "{before}");
            assert!(most > held, "{most} against {held}");
        }
    }
}

#[test]
fn a_grip_at_n_max_before_the_twist_still_turns_more_than_one_there_from_the_start() {
    let brush = FingerSource::Drawn(BenchPlant::Brush);
    let trial = families::trial_on(&brush, &Ranges::default(), "twist", 2016, 7).unwrap();
    let constant = |n| greatest_turn(&run(&trial, ControllerKind::Constant, "constant", n));
    let (held, below) = (constant(N_MAX_N), constant(19.5));
    println!("trial 2016/7, constant 20 N: greatest turn {held:.5} rad; 19.5 N: {below:.5} rad");
    assert!(held < DROP_ROTATION_RAD && below > DROP_ROTATION_RAD);
    // At a safety factor of 100 the grip climbs from N_min to N_max at the rise rate under
    // the object's weight alone, 0.15 s before the twist starts.
    let samples = run(
        &trial,
        ControllerKind::SoftgripTable,
        "softgrip-table",
        100.0,
    );
    let ((t_max, before), most) = (at_n_max(&samples), greatest_turn(&samples));
    println!(
        "softgrip-table 100: N_max at {t_max:.3} s, turned {before:.5} rad by then, \
         {most:.5} rad at most"
    );
    assert!(t_max < 0.2 - 0.1 && before < 0.01 * DROP_ROTATION_RAD);
    // Those 50 ms and 2 mrad cost about ten times as much turn at the twist's peak.
    assert!(
        most > held + 0.05 * DROP_ROTATION_RAD,
        "{most} against {held}"
    );
}
