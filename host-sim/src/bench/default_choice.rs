//! softgrip's default mode and safety factor, chosen from a bench run on the front of
//! drops against force, safety first.
//!
//! The rule, over every setting (mode, safety factor) of the two softgrip controllers in
//! a run of all five families:
//!
//! 1. **Drops on the aims.** A setting's drops are those the aims count: the
//!    holdable trials it drops in `lift-hold`, `shake`, `twist` and `faults`, and the
//!    holdable `mu-mismatch` trials that list the slip sensor (without a sensor a wrong
//!    μ is beyond what any margin is promised to cover). `n` is the number of such
//!    trials, the same for every setting.
//! 2. **As safe as the safest.** The safest setting drops the fewest, `d₀`. A setting
//!    counts as safe when its drops are within the Wilson 95 % upper bound of `d₀` in
//!    `n` (a run of a few hundred trials cannot tell such settings apart).
//! 3. **The cheapest of those**: the least geometric mean, over the five families, of
//!    the mean force over the oracle's (a lower safety factor first on a tie).
//!
//! Run on held-out seeds (never the scoring seeds), this chooses
//! [`ControllerConfig::DEFAULT`](softgrip::controller::ControllerConfig)'s mode and
//! safety. Every baseline enters on the same terms: the same rule, over its own knob
//! alone ([`baseline_choices`]), chooses the default the bench marks for it
//! ([`super::sweep::SWEEPS`]). `host-sim/tests/default_choice.rs` checks the committed
//! held-out run against all of them. Cost: one pass over the trials' runs per
//! controller.

use super::stats::wilson95;
use super::sweep::{settings, Sweep, TrialResult};
use super::FamilyResults;
use crate::sim::controllers::ControllerKind;
use serde::Serialize;

/// The families the rule needs, all of them.
const FAMILIES: [&str; 5] = ["lift-hold", "shake", "twist", "mu-mismatch", "faults"];

/// One setting of a controller, as the rule sees it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// The controller (`softgrip-ellipse`, `softgrip-table` or a baseline).
    pub controller: String,
    /// Its knob's value (the safety factor; the force for `constant`, the floor for
    /// `slip-servo`).
    pub knob_value: f64,
    /// Its drops on the aims.
    pub drops: usize,
    /// The geometric mean over the families of the mean force over the oracle's.
    pub force_over_oracle: f64,
}

/// The rule's outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Choice {
    /// The trials the aims count, `n`.
    pub aim_trials: usize,
    /// The fewest drops of any setting, `d₀`.
    pub safest_drops: usize,
    /// The most drops that count as safe: `n` times the Wilson upper bound of `d₀/n`.
    pub safe_drops_max: f64,
    /// The chosen setting.
    pub chosen: Candidate,
    /// Every setting, in the sweeps' order.
    pub candidates: Vec<Candidate>,
}

/// Whether a trial of `family` counts toward the aims.
fn counts(family: &str, r: &TrialResult) -> bool {
    r.holdable && (family != "mu-mismatch" || r.sensor)
}

/// softgrip's default: the rule over the settings of both modes, or `None` when the run
/// lacks a family or either softgrip controller.
pub fn choose(sweeps: &[Sweep], groups: &[FamilyResults]) -> Option<Choice> {
    choose_among(
        sweeps,
        groups,
        &[
            ControllerKind::SoftgripEllipse,
            ControllerKind::SoftgripTable,
        ],
    )
}

/// Each baseline's default: the same rule over that baseline's own settings, for every
/// baseline the run swept (none without all five families).
pub fn baseline_choices(sweeps: &[Sweep], groups: &[FamilyResults]) -> Vec<Choice> {
    sweeps
        .iter()
        .filter(|s| !s.controller.is_softgrip())
        .filter_map(|s| choose_among(sweeps, groups, &[s.controller]))
        .collect()
}

/// The rule over the settings of the controllers `kinds`, or `None` when the run lacks a
/// family or one of them.
pub fn choose_among(
    sweeps: &[Sweep],
    groups: &[FamilyResults],
    kinds: &[ControllerKind],
) -> Option<Choice> {
    if !FAMILIES
        .iter()
        .all(|f| groups.iter().any(|g| g.family == *f))
        || !kinds
            .iter()
            .all(|k| sweeps.iter().any(|s| s.controller == *k))
    {
        return None;
    }
    let aim_trials = groups
        .iter()
        .flat_map(|g| g.results.iter().map(move |r| counts(g.family, r)))
        .filter(|c| *c)
        .count();
    let candidates: Vec<Candidate> = settings(sweeps)
        .filter(|(_, sw, _)| kinds.contains(&sw.controller))
        .map(|(col, sw, v)| candidate(sw, v, col, groups))
        .collect();
    let safest_drops = candidates.iter().map(|c| c.drops).min()?;
    let safe_drops_max = wilson95(safest_drops, aim_trials)[1] * aim_trials as f64;
    let chosen = candidates
        .iter()
        .filter(|c| c.drops as f64 <= safe_drops_max)
        .min_by(|a, b| {
            a.force_over_oracle
                .total_cmp(&b.force_over_oracle)
                .then(a.knob_value.total_cmp(&b.knob_value))
        })?
        .clone();
    Some(Choice {
        aim_trials,
        safest_drops,
        safe_drops_max,
        chosen,
        candidates,
    })
}

/// Setting `value` of `sw`, the runs' column `col`, over every family and seed.
fn candidate(sw: &Sweep, value: f64, col: usize, groups: &[FamilyResults]) -> Candidate {
    let mut drops = 0;
    let mut log_sum = 0.0;
    for family in FAMILIES {
        let (mut ratio, mut n) = (0.0, 0usize);
        for g in groups.iter().filter(|g| g.family == family) {
            for r in &g.results {
                let run = &r.runs[col];
                if run.dropped && counts(family, r) {
                    drops += 1;
                }
                ratio += run.mean_force_n / r.oracle_mean_n;
                n += 1;
            }
        }
        // The family's mean force over the oracle's, as its table row gives it.
        log_sum += (ratio / n.max(1) as f64).ln();
    }
    Candidate {
        controller: sw.controller.name().to_string(),
        knob_value: value,
        drops,
        force_over_oracle: (log_sum / FAMILIES.len() as f64).exp(),
    }
}

/// The rule's lines for people.
pub fn lines(c: &Choice) -> String {
    format!(
        "default choice (safety first on the front): the fewest drops on the aims are {} of \
         {}; settings within {:.1} drops count as safe; the cheapest of them is {}@{} \
         ({} drops, {:.3} x the oracle's force, geometric mean over the families)",
        c.safest_drops,
        c.aim_trials,
        c.safe_drops_max,
        c.chosen.controller,
        c.chosen.knob_value,
        c.chosen.drops,
        c.chosen.force_over_oracle
    )
}

/// One line for a baseline's choice.
pub fn baseline_line(c: &Choice) -> String {
    format!(
        "{}'s default by the same rule: {}@{} ({} drops on the aims, the fewest {}, safe \
         within {:.1}; {:.3} x the oracle's force)",
        c.chosen.controller,
        c.chosen.controller,
        c.chosen.knob_value,
        c.chosen.drops,
        c.safest_drops,
        c.safe_drops_max,
        c.chosen.force_over_oracle
    )
}
