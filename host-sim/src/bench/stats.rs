//! The summary rows of a bench: per family, controller and knob value, the drops (with
//! a Wilson 95 % interval, `host-sim/tests/bench.rs::the_wilson_interval_brackets_the_rate`),
//! force over the oracle and slip, over the trials of one seed or of every seed pooled.

use super::families::N_MAX_N;
use super::sweep::{settings, RunRow, Sweep, TrialResult};
use crate::sim::controllers::ControllerKind;
use crate::sim::run::DROP_DISTANCE_M;
use serde::{Deserialize, Serialize};

/// One row of `bench.json`: one family, controller and knob value over all trials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Family.
    pub family: String,
    /// The seed of the trials, or `None` for the rows pooled over every seed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// Controller.
    pub controller: String,
    /// The knob's name.
    pub knob: String,
    /// The knob's value (safety factor [-], force \[N\] or floor force \[N\]).
    pub knob_value: f64,
    /// Whether this is the controller's default.
    pub default: bool,
    /// Trials run.
    pub trials: usize,
    /// Trials that `constant` at `N_max` holds.
    pub holdable: usize,
    /// Trials dropped.
    pub drops: usize,
    /// Holdable trials dropped.
    pub drops_holdable: usize,
    /// Holdable trials dropped by a turn ([`lost_by_turning`]): the object turned past
    /// [`DROP_ROTATION_RAD`](crate::sim::run::DROP_ROTATION_RAD) before it slid
    /// [`DROP_DISTANCE_M`].
    pub drops_turned: usize,
    /// Holdable trials at the hand's limit ([`at_limit`]); `None` when the run has no
    /// `constant` sweep to tell.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_limit: Option<usize>,
    /// Holdable trials at the hand's limit that were dropped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drops_at_limit: Option<usize>,
    /// `drops/trials`.
    pub drop_rate: f64,
    /// Wilson score interval of the drop rate, `[low, high]` ([`wilson95`]).
    pub drop_rate_ci95: [f64; 2],
    /// Mean over trials of (time-averaged force / oracle's time-averaged force) [-].
    pub force_over_oracle: f64,
    /// Mean over trials of the time-averaged normal force \[N\].
    pub mean_force_n: f64,
    /// Mean over trials of the peak normal force \[N\].
    pub peak_force_n: f64,
    /// Mean over trials of the slip distance \[m\].
    pub slip_distance_m: f64,
    /// Mean over trials of the slip episodes.
    pub slip_events: f64,
}

/// The Wilson score interval at 95 % for `k` successes in `n` trials
/// (`host-sim/tests/bench.rs::the_wilson_interval_brackets_the_rate`).
pub fn wilson95(k: usize, n: usize) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let z = 1.959_963_984_540_054_f64;
    let (n, p) = (n as f64, k as f64 / n as f64);
    let denom = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denom;
    let half = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt() / denom;
    [(centre - half).max(0.0), (centre + half).min(1.0)]
}

/// A holdable trial is **at the hand's limit** when no constant grip of the grid below
/// this fraction of `N_max` holds it, even one applied from the trial's start [-]
/// (`host-sim/tests/bench.rs::a_trial_is_at_the_hands_limit_when_no_grip_below_95_percent_of_it_holds`).
/// The 5 % left is about the spread of the lab's calibration of μ (docs/bench-fingers.md).
/// The tables count the drops on these trials apart; every other count keeps them.
pub const AT_LIMIT_FRACTION: f64 = 0.95;

/// The columns of the `constant` sweep's settings, in increasing force.
fn constant_grid(sweeps: &[Sweep]) -> Vec<(usize, f64)> {
    settings(sweeps)
        .filter(|(_, sw, _)| sw.controller == ControllerKind::Constant)
        .map(|(col, _, v)| (col, v))
        .collect()
}

/// The least constant grip of `grid` (from [`constant_grid`]) that holds trial `r`: its
/// column and force [N], or `None` when none does. The grid's values increase, so its
/// first setting that holds is the least grip.
fn least_holding(grid: &[(usize, f64)], r: &TrialResult) -> Option<(usize, f64)> {
    grid.iter().copied().find(|(col, _)| !r.runs[*col].dropped)
}

/// [`at_limit`] on a non-empty `grid` (from [`constant_grid`]).
fn at_limit_on(grid: &[(usize, f64)], r: &TrialResult, n_max_n: f64) -> bool {
    r.holdable
        && least_holding(grid, r).is_none_or(|(_, least)| least >= AT_LIMIT_FRACTION * n_max_n)
}

/// Whether trial `r` is holdable and at the hand's limit ([`AT_LIMIT_FRACTION`]) for a
/// hand of `n_max_n` \[N\], judged by the `constant` sweep of `sweeps`; `None` when there is
/// none.
pub fn at_limit(sweeps: &[Sweep], r: &TrialResult, n_max_n: f64) -> Option<bool> {
    let grid = constant_grid(sweeps);
    (!grid.is_empty()).then(|| at_limit_on(&grid, r, n_max_n))
}

/// Whether a dropped run was lost by turning: the drop
/// ([`is_drop`](crate::sim::run::is_drop)) is a slide past [`DROP_DISTANCE_M`] or a turn
/// past [`DROP_ROTATION_RAD`](crate::sim::run::DROP_ROTATION_RAD), and slip stops
/// accumulating at the drop, so a drop with no more than [`DROP_DISTANCE_M`] of slide is
/// a turn. `false` for a run that held.
pub fn lost_by_turning(run: &RunRow) -> bool {
    run.dropped && run.slip_distance_m <= DROP_DISTANCE_M
}

/// The rows of one family from its trials' results (of one seed, `seed`, or of every seed
/// pooled, `None`), in the order of `sweeps`.
pub fn rows(
    family: &str,
    seed: Option<u64>,
    sweeps: &[Sweep],
    results: &[&TrialResult],
) -> Vec<Row> {
    let mut out = Vec::new();
    let n = results.len();
    let holdable = results.iter().filter(|r| r.holdable).count();
    let grid = constant_grid(sweeps);
    let limit: Vec<bool> = results
        .iter()
        .map(|r| !grid.is_empty() && at_limit_on(&grid, r, N_MAX_N))
        .collect();
    let at_limit_trials = (!grid.is_empty()).then(|| limit.iter().filter(|x| **x).count());
    for (col, sw, v) in settings(sweeps) {
        let (mut drops, mut drops_h, mut drops_t, mut drops_l) = (0, 0, 0, 0);
        let (mut ratio, mut force, mut peak, mut slip, mut events) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (r, limit) in results.iter().zip(&limit) {
            let run = &r.runs[col];
            if run.dropped {
                drops += 1;
                if r.holdable {
                    drops_h += 1;
                    drops_t += usize::from(lost_by_turning(run));
                }
                if *limit {
                    drops_l += 1;
                }
            }
            ratio += run.mean_force_n / r.oracle_mean_n;
            force += run.mean_force_n;
            peak += run.peak_force_n;
            slip += run.slip_distance_m;
            events += run.slip_events as f64;
        }
        let mean = |x: f64| if n > 0 { x / n as f64 } else { 0.0 };
        out.push(Row {
            family: family.to_string(),
            seed,
            controller: sw.controller.name().to_string(),
            knob: sw.knob.to_string(),
            knob_value: v,
            default: v == sw.default,
            trials: n,
            holdable,
            drops,
            drops_holdable: drops_h,
            drops_turned: drops_t,
            at_limit: at_limit_trials,
            drops_at_limit: at_limit_trials.map(|_| drops_l),
            drop_rate: mean(drops as f64),
            drop_rate_ci95: wilson95(drops, n),
            force_over_oracle: mean(ratio),
            mean_force_n: mean(force),
            peak_force_n: mean(peak),
            slip_distance_m: mean(slip),
            slip_events: mean(events),
        });
    }
    out
}

/// A reference, not a controller: for each holdable trial, the least constant grip of
/// the run's grid that holds it, chosen knowing the trial in advance. No causal
/// controller can choose so (it would have to know the trial's peak load and its plant's
/// creep before they come); the figure says how far the oracle, which follows the load
/// tick by tick with no lag, lies from any steady grip; it is high by at most one step of
/// the grid per trial
/// (`host-sim/tests/bench.rs::the_clairvoyant_constant_is_the_least_holding_grip_of_each_holdable_trial`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Clairvoyant {
    /// Family.
    pub family: String,
    /// The holdable trials (each is held by some constant of the grid, `N_max` at least).
    pub trials: usize,
    /// The mean over those trials of that grip's mean force over the oracle's [-].
    pub mean_force_over_oracle: f64,
    /// Their median [-].
    pub median_force_over_oracle: f64,
}

/// [`Clairvoyant`] over `results`, or `None` when the run has no `constant` sweep or no
/// holdable trial. Cost: one pass over the constant grips' runs.
pub fn clairvoyant_constant(
    family: &str,
    sweeps: &[Sweep],
    results: &[&TrialResult],
) -> Option<Clairvoyant> {
    let grid = constant_grid(sweeps);
    if grid.is_empty() {
        return None;
    }
    let mut ratios: Vec<f64> = results
        .iter()
        .filter(|r| r.holdable)
        .filter_map(|r| {
            least_holding(&grid, r).map(|(col, _)| r.runs[col].mean_force_n / r.oracle_mean_n)
        })
        .collect();
    if ratios.is_empty() {
        return None;
    }
    ratios.sort_by(f64::total_cmp);
    let n = ratios.len();
    let median = if n % 2 == 1 {
        ratios[n / 2]
    } else {
        0.5 * (ratios[n / 2 - 1] + ratios[n / 2])
    };
    Some(Clairvoyant {
        family: family.to_string(),
        trials: n,
        mean_force_over_oracle: ratios.iter().sum::<f64>() / n as f64,
        median_force_over_oracle: median,
    })
}
