//! The costs a configuration is ranked by, and which Pareto fronts (error against cost)
//! each configuration is on.

use super::*;

/// A cost a configuration can be ranked by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cost {
    /// Host time per tick.
    HostTick,
    /// Host time of the start-up (grid configurations only).
    HostStartup,
    /// Instructions per tick on the emulated M4F (median; `--target`).
    TargetTick,
    /// Instructions of the start-up on the emulated M4F (`--target`).
    TargetStartup,
}

impl Cost {
    /// Every cost, in the order of [`Fronts`].
    pub const ALL: [Cost; 4] = [
        Cost::HostTick,
        Cost::HostStartup,
        Cost::TargetTick,
        Cost::TargetStartup,
    ];

    /// The name of its front.
    pub fn name(self) -> &'static str {
        match self {
            Cost::HostTick => "tick",
            Cost::HostStartup => "start-up",
            Cost::TargetTick => "M4F tick",
            Cost::TargetStartup => "M4F start-up",
        }
    }

    /// The axis label of its plot.
    pub(super) fn axis(self) -> &'static str {
        match self {
            Cost::HostTick => "host tick [ns]",
            Cost::HostStartup => "host start-up [µs]",
            Cost::TargetTick => "M4F tick, median [instructions]",
            Cost::TargetStartup => "M4F start-up [instructions]",
        }
    }

    /// The configuration's cost, if it has one.
    pub fn of(self, results: &Results, v: &Variant, m: &Measured) -> Option<f64> {
        let grid = !matches!(v.engine, Engine::Exact);
        match self {
            Cost::HostTick => Some(m.tick_ns),
            Cost::HostStartup => grid.then_some(m.precompute_us),
            Cost::TargetTick => target_cost(results, v).map(|c| c.tick_median),
            Cost::TargetStartup => target_cost(results, v).map(|c| c.startup),
        }
    }

    /// Costs within this factor count as equal: host times are noisy, instruction counts
    /// are not.
    pub(super) fn tolerance(self) -> f64 {
        match self {
            Cost::HostTick | Cost::HostStartup => TIME_TOLERANCE,
            Cost::TargetTick | Cost::TargetStartup => 1.0,
        }
    }
}

/// Which fronts a configuration is on, in the order of [`Cost::ALL`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Fronts(pub [bool; 4]);

impl Fronts {
    /// Whether it is on the front of `cost`.
    pub fn on(self, cost: Cost) -> bool {
        Cost::ALL
            .iter()
            .position(|&c| c == cost)
            .is_some_and(|i| self.0[i])
    }

    pub(super) fn any(self) -> bool {
        self.0.iter().any(|&b| b)
    }

    pub(super) fn mark(self) -> String {
        let names: Vec<&str> = Cost::ALL
            .iter()
            .filter(|&&c| self.on(c))
            .map(|c| c.name())
            .collect();
        if names.is_empty() {
            "—".into()
        } else {
            names.join(" + ")
        }
    }
}

/// Whether `(e1, c1)` dominates `(e0, c0)`: no worse in both, better in one, costs within
/// `tol` of each other counting as equal.
pub(super) fn dominates(e1: f64, c1: f64, e0: f64, c0: f64, tol: f64) -> bool {
    (e1 < e0 && c1 <= c0 * tol) || (e1 <= e0 && c1 * tol < c0)
}

/// The Pareto fronts over every measured configuration: for each [`Cost`], the
/// configurations that have it and that no other is at least as accurate and as cheap as.
pub fn fronts(results: &Results) -> Vec<(Variant, Measured, Fronts)> {
    let all: Vec<(Variant, Measured)> = results.measured.iter().map(|(v, m)| (*v, *m)).collect();
    all.iter()
        .map(|&(v, m)| {
            let mut f = Fronts::default();
            for (i, cost) in Cost::ALL.iter().enumerate() {
                let Some(c0) = cost.of(results, &v, &m) else {
                    continue;
                };
                f.0[i] = !all.iter().any(|(ov, o)| {
                    cost.of(results, ov, o)
                        .is_some_and(|c1| dominates(o.error(), c1, m.error(), c0, cost.tolerance()))
                });
            }
            (v, m, f)
        })
        .collect()
}

pub(super) fn front_of(results: &Results, v: &Variant) -> Fronts {
    fronts(results)
        .into_iter()
        .find(|(w, _, _)| w == v)
        .map_or(Fronts::default(), |(_, _, f)| f)
}
