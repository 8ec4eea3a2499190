//! Each controller swept over its own knob, on every trial of a family: the grids, and
//! one trial's runs ([`run_trial`]). The rows of the summary are [`super::stats`]'.

use super::families::Trial;
use super::oracle;
use crate::sim::controllers::{ControllerKind, LinkKind};
use crate::sim::report;
use crate::sim::run::{self, RunOptions};
use crate::sim::scene::Scene;
use serde::{Deserialize, Serialize};
use softgrip::controller::ControllerConfig;
use std::path::Path;

/// A controller and the knob it is swept over.
#[derive(Debug, Clone, Copy)]
pub struct Sweep {
    /// The controller (its name as `--controller` takes it and the outputs carry it).
    pub controller: ControllerKind,
    /// The knob's name.
    pub knob: &'static str,
    /// Its values, in increasing order.
    pub values: &'static [f64],
    /// The controller's default value of the knob.
    pub default: f64,
}

/// softgrip's default safety factor ([`ControllerConfig::DEFAULT`], chosen on held-out
/// seeds by [`super::default_choice`]).
const DEFAULT_SAFETY: f64 = ControllerConfig::DEFAULT.safety;
/// Each baseline's default, chosen as softgrip's is: by the same rule
/// ([`super::default_choice::baseline_choices`], safety first on the front), over that
/// baseline's own knob, on the same held-out run (docs/bench/heldout/; checked by
/// `host-sim/tests/default_choice.rs`). `constant`'s force \[N\].
pub const CONSTANT_DEFAULT_N: f64 = 20.0;
/// `coulomb`'s default safety factor (held-out choice, as [`CONSTANT_DEFAULT_N`]).
pub const COULOMB_DEFAULT_SAFETY: f64 = 3.0;
/// `box`'s default safety factor (held-out choice, as [`CONSTANT_DEFAULT_N`]).
pub const BOX_DEFAULT_SAFETY: f64 = 3.0;
/// `fixed-torsion`'s default safety factor (held-out choice, as
/// [`CONSTANT_DEFAULT_N`]).
pub const FIXED_TORSION_DEFAULT_SAFETY: f64 = 2.5;
/// `slip-servo`'s default floor \[N\] (held-out choice, as [`CONSTANT_DEFAULT_N`]).
pub const SLIP_SERVO_DEFAULT_N: f64 = 4.0;
/// The margin of common practice, at which the model-based baselines ran by default before
/// their defaults were chosen by the rule; the bench reports softgrip's default against
/// them at it too (the README's claim, `host-sim/tests/bench_claims.rs`).
pub const COMMON_PRACTICE_SAFETY: f64 = 1.3;

/// The safety factors every controller with one sweeps: fine steps up to 2, then two
/// coarse ones.
pub const SAFETY_GRID: [f64; 23] = [
    1.0, 1.05, 1.1, 1.15, 1.2, 1.25, 1.3, 1.35, 1.4, 1.45, 1.5, 1.55, 1.6, 1.65, 1.7, 1.75, 1.8,
    1.85, 1.9, 1.95, 2.0, 2.5, 3.0,
];

/// The constant grips \[N\]: even steps up to `N_max`.
pub const CONSTANT_GRID_N: [f64; 40] = [
    0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5, 7.0, 7.5, 8.0, 8.5, 9.0, 9.5,
    10.0, 10.5, 11.0, 11.5, 12.0, 12.5, 13.0, 13.5, 14.0, 14.5, 15.0, 15.5, 16.0, 16.5, 17.0, 17.5,
    18.0, 18.5, 19.0, 19.5, 20.0,
];

const fn safety_sweep(controller: ControllerKind, default: f64) -> Sweep {
    Sweep {
        controller,
        knob: "safety",
        values: &SAFETY_GRID,
        default,
    }
}

/// Every controller with its knob, in the order of the tables: each softgrip mode is a
/// controller of its own, and every controller with a safety factor sweeps the same
/// [`SAFETY_GRID`].
pub const SWEEPS: [Sweep; 7] = [
    safety_sweep(ControllerKind::SoftgripEllipse, DEFAULT_SAFETY),
    safety_sweep(ControllerKind::SoftgripTable, DEFAULT_SAFETY),
    Sweep {
        controller: ControllerKind::Constant,
        knob: "force_n",
        values: &CONSTANT_GRID_N,
        default: CONSTANT_DEFAULT_N,
    },
    safety_sweep(ControllerKind::Coulomb, COULOMB_DEFAULT_SAFETY),
    safety_sweep(ControllerKind::Box, BOX_DEFAULT_SAFETY),
    safety_sweep(ControllerKind::FixedTorsion, FIXED_TORSION_DEFAULT_SAFETY),
    // The slip servo has no model to scale: its knob is the force it relaxes to.
    Sweep {
        controller: ControllerKind::SlipServo,
        knob: "floor_n",
        values: &[0.2, 0.5, 1.0, 2.0, 4.0],
        default: SLIP_SERVO_DEFAULT_N,
    },
];

/// Every setting of `sweeps` as `(column, sweep, value)`, the column being the setting's
/// index in a trial's runs ([`TrialResult::runs`]): the sweeps in order, each over its
/// values.
pub fn settings(sweeps: &[Sweep]) -> impl Iterator<Item = (usize, &Sweep, f64)> {
    sweeps
        .iter()
        .flat_map(|sw| sw.values.iter().map(move |&v| (sw, v)))
        .enumerate()
        .map(|(col, (sw, v))| (col, sw, v))
}

/// `scene` with the controller's knob set to `value`.
pub fn with_knob(scene: &Scene, controller: ControllerKind, value: f64) -> Scene {
    let mut s = scene.clone();
    match controller {
        ControllerKind::Constant => s.controller.constant_force_n = Some(value),
        ControllerKind::SlipServo => s.controller.set("n_min_n", value),
        _ => s.controller.set("safety", value),
    }
    s
}

/// One run of one trial.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RunRow {
    /// Dropped ([`run::is_drop`]).
    pub dropped: bool,
    /// Slip episodes.
    pub slip_events: u64,
    /// Slip distance \[m\].
    pub slip_distance_m: f64,
    /// Time-averaged normal force \[N\].
    pub mean_force_n: f64,
    /// Peak normal force \[N\].
    pub peak_force_n: f64,
}

/// One trial against every controller and knob value (a shard file's unit of work:
/// serialised whole).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialResult {
    /// The finger's true static μ [-].
    pub true_mu: f64,
    /// The finger's true static μ over the one the lab measured [-].
    pub mu_ratio: f64,
    /// Whether the trial lists the slip sensor.
    pub sensor: bool,
    /// Whether `constant` at the scene's `N_max` holds it.
    pub holdable: bool,
    /// The oracle's time-averaged force \[N\].
    pub oracle_mean_n: f64,
    /// One row per (sweep, value), in [`SWEEPS`] order.
    pub runs: Vec<RunRow>,
}

/// Runs `trial` against every sweep in `sweeps` on `link`. With `trace`, the trial's
/// scene is written under that directory as `NNNN-scene.toml` (`NNNN` the trial's index;
/// `simulate` replays it) and each run's per-tick samples as
/// `NNNN-CONTROLLER-KNOBVALUE.csv` (`0004-softgrip-table-safety1.2.csv`).
pub fn run_trial(
    trial: &Trial,
    sweeps: &[Sweep],
    link: &LinkKind,
    trace: Option<&Path>,
) -> Result<TrialResult, String> {
    let scene = &trial.scene;
    let cfg = run::controller_config(scene).map_err(|e| e.to_string())?;
    let oracle_mean_n =
        oracle::mean_oracle_force_n(scene, trial.limit.as_ref(), cfg.n_min_n, cfg.n_max_n)?;
    if let Some(dir) = trace {
        let path = dir.join(format!("{:04}-scene.toml", trial.index));
        std::fs::write(&path, &trial.text).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let options = RunOptions {
        skip_samples: trace.is_none(),
        truth: Some(trial.truth.as_ref()),
        untimed: true,
    };
    let one = |s: &Scene, controller: &str, tag: &str| -> Result<RunRow, String> {
        let out = run::run_with(s, controller, link, None, options)?;
        if let Some(dir) = trace {
            let path = dir.join(format!("{:04}-{controller}-{tag}.csv", trial.index));
            report::write_csv(&path, &out.samples).map_err(|e| e.to_string())?;
        }
        let m = &out.summary;
        Ok(RunRow {
            dropped: m.dropped,
            slip_events: m.slip_events,
            slip_distance_m: m.slip_distance_m,
            mean_force_n: m.mean_normal_force_n,
            peak_force_n: m.peak_normal_force_n,
        })
    };
    let constant = ControllerKind::Constant;
    let mut runs = Vec::new();
    let mut holdable = None;
    for sw in sweeps {
        for &v in sw.values {
            let row = one(
                &with_knob(scene, sw.controller, v),
                sw.controller.name(),
                &format!("{}{v}", sw.knob),
            )?;
            if sw.controller == constant && v == cfg.n_max_n {
                holdable = Some(!row.dropped);
            }
            runs.push(row);
        }
    }
    let holdable = match holdable {
        Some(h) => h,
        None => {
            let full = with_knob(scene, constant, cfg.n_max_n);
            !one(&full, constant.name(), "holdable")?.dropped
        }
    };
    Ok(TrialResult {
        true_mu: scene.finger.mu,
        mu_ratio: trial.mu_ratio,
        sensor: trial.sensor,
        holdable,
        oracle_mean_n,
        runs,
    })
}
