//! The oracle force: at every tick the least normal force within the scene's
//! `[N_min, N_max]` that holds that tick's true load, with no lag, no noise and no margin:
//! the plant's true limit ([`TrueLimit`]: on the limit-surface plant the exact surface
//! ([`Truth`]) with the true μ and the contact at its equilibrium size `a = c·N^γ`; on the
//! brush finger its tabulated gross-slip onsets, [`OnsetTable`]). Where even `N_max` does
//! not hold the load the oracle answers `N_max`.
//!
//! The loads come from the same task and load effects as the run (gravity,
//! disturbances), which do not depend on the controller, so the oracle is computed once
//! per trial and shared by every controller and knob value.

use super::onset_table::OnsetTable;
use crate::sim::effects::World;
use crate::sim::scene::Scene;
use crate::sim::task;
use crate::sim::truth::Truth;

/// A plant's true limit: whether a load holds at a normal force.
pub trait TrueLimit {
    /// Whether the load `(ft_n, mn_nm)` (one contact's, \[N\] and [N·m]) holds at normal
    /// force `n_n` \[N\].
    fn holds(&self, ft_n: f64, mn_nm: f64, n_n: f64) -> bool;
}

impl TrueLimit for Truth {
    fn holds(&self, ft_n: f64, mn_nm: f64, n_n: f64) -> bool {
        self.evaluate(ft_n, mn_nm, n_n, self.half_width_m(n_n))
            .utilisation
            <= 1.0
    }
}

impl TrueLimit for OnsetTable {
    fn holds(&self, ft_n: f64, mn_nm: f64, n_n: f64) -> bool {
        OnsetTable::holds(self, ft_n, mn_nm, n_n)
    }
}

/// Relative width [-] to which the least force is bracketed (the answer is the upper end,
/// which holds).
pub const REL_TOL: f64 = 1e-6;

/// The least force in `[n_min_n, n_max_n]` \[N\] at which the true load `(ft_n, mn_nm)`
/// (per contact, \[N\] and [N·m]) has a true utilisation of at most 1; `n_max_n` when none.
/// `guess` \[N\] (the previous tick's answer) only speeds the search: it is bracketed
/// close around it when it can be, then bisected to [`REL_TOL`].
pub fn least_holding_force_n(
    truth: &dyn TrueLimit,
    ft_n: f64,
    mn_nm: f64,
    n_min_n: f64,
    n_max_n: f64,
    guess: Option<f64>,
) -> f64 {
    let holds = |n: f64| truth.holds(ft_n, mn_nm, n);
    if holds(n_min_n) {
        return n_min_n;
    }
    if !holds(n_max_n) {
        return n_max_n;
    }
    // n_min does not hold and n_max does: bracket [lo, hi] with !holds(lo), holds(hi).
    let (mut lo, mut hi) = (n_min_n, n_max_n);
    if let Some(g) = guess.filter(|g| *g > n_min_n && *g < n_max_n) {
        if holds(g) {
            hi = g;
            let down = (g / 1.05).max(n_min_n);
            if !holds(down) {
                lo = down;
            }
        } else {
            lo = g;
            let up = (g * 1.05).min(n_max_n);
            if holds(up) {
                hi = up;
            }
        }
    }
    while hi - lo > REL_TOL * hi {
        let mid = 0.5 * (lo + hi);
        if holds(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The oracle's time-averaged force over a scene \[N\] (the mean of the per-tick least
/// holding forces), with the scene's force limits `[n_min_n, n_max_n]`.
pub fn mean_oracle_force_n(
    scene: &Scene,
    truth: &dyn TrueLimit,
    n_min_n: f64,
    n_max_n: f64,
) -> Result<f64, String> {
    let mut pipeline = scene.pipeline().map_err(|e| e.to_string())?;
    let dt = 1.0 / scene.tick_hz;
    let ticks = (scene.duration_s * scene.tick_hz).round() as u64;
    let mut w = World {
        dt_s: dt,
        mass_kg: scene.object.mass_kg,
        inertia_kg_m2: scene.object.inertia_kg_m2,
        com_offset_m: scene.object.com_offset_m,
        ..World::default()
    };
    let mut sum = 0.0;
    let mut last = None;
    for k in 0..ticks {
        w.t_s = k as f64 * dt;
        w.force_n = [0.0, 0.0];
        w.moment_nm = 0.0;
        w.support_fraction = task::support_fraction(&scene.task, w.t_s);
        task::apply(&scene.task, &mut w);
        pipeline.load(&mut w);
        let [fx, fy] = w.contact_force_n();
        let n = least_holding_force_n(
            truth,
            fx.hypot(fy),
            w.contact_moment_nm().abs(),
            n_min_n,
            n_max_n,
            last,
        );
        last = Some(n);
        sum += n;
    }
    Ok(if ticks > 0 { sum / ticks as f64 } else { 0.0 })
}
