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
//! held-out run against all of them.
//!
//! Each setting also carries its drops on the aims family by family and at the hand's
//! limit, and the outcome carries the same rule's choice on aims that leave the trials
//! at the hand's limit out (when the run has the `constant` sweep that finds them): what
//! sets the choice apart from trials no grip below 95 % of `N_max` holds. Cost: one pass
//! over the trials' runs per setting, and one over the trials per `constant` setting to
//! find those at the hand's limit.

use super::families::N_MAX_N;
use super::stats::{at_limit, wilson95};
use super::sweep::{settings, Sweep, TrialResult};
use super::FamilyResults;
use crate::sim::controllers::ControllerKind;
use serde::Serialize;

/// The families the rule needs, all of them.
pub const FAMILIES: [&str; 5] = ["lift-hold", "shake", "twist", "mu-mismatch", "faults"];

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
    /// Of those, the drops in each family, in the order of [`FAMILIES`].
    pub drops_per_family: [usize; 5],
    /// Of those, the drops of trials at the hand's limit
    /// ([`stats::at_limit`](super::stats::at_limit)); `None` when the run has no
    /// `constant` sweep to judge them by.
    pub drops_at_limit: Option<usize>,
    /// The geometric mean over the families of the mean force over the oracle's.
    pub force_over_oracle: f64,
}

/// The rule's outcome on aims that leave out the trials at the hand's limit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WithoutLimit {
    /// The trials those aims count.
    pub aim_trials: usize,
    /// The fewest drops on them of any setting.
    pub safest_drops: usize,
    /// The most drops that count as safe.
    pub safe_drops_max: f64,
    /// The setting the rule chooses on them (its `drops` still those on the whole aims).
    pub chosen: Candidate,
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
    /// The same rule on aims without the trials at the hand's limit, which no grip below
    /// 95 % of `N_max` holds even from the start (docs/bench.md, "What the `twist` drops
    /// are"): what sets the choice apart from them. `None` when the run has no `constant`
    /// sweep to find them.
    pub without_limit: Option<WithoutLimit>,
}

/// Whether a trial of `family` counts toward the aims.
fn counts(family: &str, r: &TrialResult) -> bool {
    r.holdable && (family != "mu-mismatch" || r.sensor)
}

/// softgrip's default: the rule over the settings of the softgrip modes the run swept
/// (both, or one: a candidate judged in table mode alone gets its choice from the bench
/// itself), or `None` when the run lacks a family or any softgrip mode.
pub fn choose(sweeps: &[Sweep], groups: &[FamilyResults]) -> Option<Choice> {
    let modes: Vec<ControllerKind> = sweeps
        .iter()
        .map(|s| s.controller)
        .filter(|k| {
            matches!(
                k,
                ControllerKind::SoftgripEllipse | ControllerKind::SoftgripTable
            )
        })
        .collect();
    // With no mode there are no candidates, and `choose_among` gives `None`.
    choose_among(sweeps, groups, &modes)
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
    let limits = limits(sweeps, groups);
    let aim_trials = aims(groups, &limits, false);
    let candidates: Vec<Candidate> = settings(sweeps)
        .filter(|(_, sw, _)| kinds.contains(&sw.controller))
        .map(|(col, sw, v)| candidate(sw, v, col, groups, &limits))
        .collect();
    let (safest_drops, safe_drops_max, chosen) =
        cheapest_safe(&candidates, aim_trials, |c| Some(c.drops))?;
    let without_limit = limits.iter().flatten().all(Option::is_some).then(|| {
        let n = aims(groups, &limits, true);
        cheapest_safe(&candidates, n, |c| Some(c.drops - c.drops_at_limit?)).map(
            |(safest_drops, safe_drops_max, chosen)| WithoutLimit {
                aim_trials: n,
                safest_drops,
                safe_drops_max,
                chosen,
            },
        )
    });
    Some(Choice {
        aim_trials,
        safest_drops,
        safe_drops_max,
        chosen,
        candidates,
        without_limit: without_limit.flatten(),
    })
}

/// Whether each trial of each group is at the hand's limit (`None` without a `constant`
/// sweep).
fn limits(sweeps: &[Sweep], groups: &[FamilyResults]) -> Vec<Vec<Option<bool>>> {
    groups
        .iter()
        .map(|g| {
            g.results
                .iter()
                .map(|r| at_limit(sweeps, r, N_MAX_N))
                .collect()
        })
        .collect()
}

/// The trials the aims count, leaving out those at the hand's limit when `but_limit`.
fn aims(groups: &[FamilyResults], limits: &[Vec<Option<bool>>], but_limit: bool) -> usize {
    groups
        .iter()
        .zip(limits)
        .flat_map(|(g, l)| g.results.iter().zip(l).map(move |(r, l)| (g.family, r, l)))
        .filter(|(f, r, l)| counts(f, r) && !(but_limit && **l == Some(true)))
        .count()
}

/// The rule's steps 2 and 3 over `candidates` with `drops` of each on `n` aim trials:
/// the fewest drops, the most that count as safe, and the cheapest safe candidate.
fn cheapest_safe(
    candidates: &[Candidate],
    n: usize,
    drops: impl Fn(&Candidate) -> Option<usize>,
) -> Option<(usize, f64, Candidate)> {
    let safest = candidates.iter().filter_map(&drops).min()?;
    let safe_max = wilson95(safest, n)[1] * n as f64;
    let chosen = candidates
        .iter()
        .filter(|c| drops(c).is_some_and(|d| d as f64 <= safe_max))
        .min_by(|a, b| {
            a.force_over_oracle
                .total_cmp(&b.force_over_oracle)
                .then(a.knob_value.total_cmp(&b.knob_value))
        })?
        .clone();
    Some((safest, safe_max, chosen))
}

/// Setting `value` of `sw`, the runs' column `col`, over every family and seed.
fn candidate(
    sw: &Sweep,
    value: f64,
    col: usize,
    groups: &[FamilyResults],
    limits: &[Vec<Option<bool>>],
) -> Candidate {
    let mut drops_per_family = [0; 5];
    let mut drops_at_limit = Some(0);
    let mut log_sum = 0.0;
    for (i, family) in FAMILIES.iter().enumerate() {
        let (mut ratio, mut n) = (0.0, 0usize);
        for (g, l) in groups
            .iter()
            .zip(limits)
            .filter(|(g, _)| g.family == *family)
        {
            for (r, at_limit) in g.results.iter().zip(l) {
                let run = &r.runs[col];
                if run.dropped && counts(family, r) {
                    drops_per_family[i] += 1;
                    drops_at_limit = drops_at_limit
                        .zip(*at_limit)
                        .map(|(d, at)| d + usize::from(at));
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
        drops: drops_per_family.iter().sum(),
        drops_per_family,
        drops_at_limit,
        force_over_oracle: (log_sum / FAMILIES.len() as f64).exp(),
    }
}

/// The rule's lines for people.
pub fn lines(c: &Choice) -> String {
    let mut out = format!(
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
    );
    if let Some(w) = &c.without_limit {
        out += &format!(
            "\ndefault choice without the {} trials at the hand's limit: the fewest drops \
             are {} of {}; within {:.1} count as safe; the cheapest of them is {}@{} ({:.3} x)",
            c.aim_trials - w.aim_trials,
            w.safest_drops,
            w.aim_trials,
            w.safe_drops_max,
            w.chosen.controller,
            w.chosen.knob_value,
            w.chosen.force_over_oracle
        );
    }
    out
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
