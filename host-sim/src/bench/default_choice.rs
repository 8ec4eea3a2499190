//! softgrip's default mode and safety factor, chosen from a bench run on the front of
//! drops against force, safety first.
//!
//! The rule, over every setting (mode, safety factor) of the softgrip controllers in a
//! run of all five families:
//!
//! 1. **Drops.** A setting's drops are the holdable trials it drops, in every family:
//!    `mu-mismatch` trials without a slip sensor count too. The aims leave those
//!    out (without a sensor a wrong μ is beyond what any margin is promised to cover),
//!    but the default is what a user gets who has not tuned it, a hand without a sensor
//!    included, and a rule that counted the aims alone walked a safer front down to a
//!    factor that gave up that cover (docs/decisions/default-choice-rule.md). `n` is
//!    the number of holdable trials, the same for every setting.
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
//! The rule reads nothing but the pooled rows of `bench.json` ([`Row`]: each family's
//! `holdable`, `drops_holdable`, `at_limit`, `drops_at_limit` and `force_over_oracle`),
//! so a written run can be judged again without its trials (`host-sim bench rejudge`).
//! Each setting also carries its drops family by family and at the hand's limit, and the
//! outcome carries the same rule's choice without the trials at the hand's limit (when
//! the run has the `constant` sweep that finds them): what sets the choice apart from
//! trials no grip below [`AT_LIMIT_FRACTION`](stats::AT_LIMIT_FRACTION) of `N_max` holds.
//! Cost: one look-up of five rows per setting.

use super::stats::{self, wilson95, Row};
use super::sweep::Sweep;
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
    /// Its drops: holdable trials dropped, in every family.
    pub drops: usize,
    /// Of those, the drops in each family, in the order of [`FAMILIES`].
    pub drops_per_family: [usize; 5],
    /// Of those, the drops of trials at the hand's limit
    /// ([`stats::at_limit`]); `None` when the run has no
    /// `constant` sweep to judge them by.
    pub drops_at_limit: Option<usize>,
    /// The geometric mean over the families of the mean force over the oracle's.
    pub force_over_oracle: f64,
}

/// The rule's outcome without the trials at the hand's limit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WithoutLimit {
    /// The holdable trials short of the hand's limit.
    pub aim_trials: usize,
    /// The fewest drops on them of any setting.
    pub safest_drops: usize,
    /// The most drops that count as safe.
    pub safe_drops_max: f64,
    /// The setting the rule chooses on them (its `drops` still those of every holdable
    /// trial).
    pub chosen: Candidate,
}

/// The rule's outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Choice {
    /// The holdable trials the rule counts, `n`.
    pub aim_trials: usize,
    /// The fewest drops of any setting, `d₀`.
    pub safest_drops: usize,
    /// The most drops that count as safe: `n` times the Wilson upper bound of `d₀/n`.
    pub safe_drops_max: f64,
    /// The chosen setting.
    pub chosen: Candidate,
    /// Every setting, in the sweeps' order.
    pub candidates: Vec<Candidate>,
    /// The same rule without the trials at the hand's limit, which no grip below 95 % of
    /// `N_max` holds even from the start (docs/decisions/twist-hand-limit.md):
    /// what sets the choice apart from them. `None` when the run has no `constant` sweep
    /// to find them.
    pub without_limit: Option<WithoutLimit>,
}

/// The rows pooled over the seeds of `groups`, family by family, as `bench.json` holds
/// them.
pub fn pooled_rows(sweeps: &[Sweep], groups: &[FamilyResults]) -> Vec<Row> {
    FAMILIES
        .iter()
        .filter(|family| groups.iter().any(|g| g.family == **family))
        .flat_map(|family| {
            let results: Vec<_> = groups
                .iter()
                .filter(|g| g.family == *family)
                .flat_map(|g| g.results.iter())
                .collect();
            stats::rows(family, None, sweeps, &results)
        })
        .collect()
}

/// softgrip's default: the rule over the settings of the softgrip modes the run swept
/// (both, or one: a candidate judged in table mode alone gets its choice from the bench
/// itself), or `None` when the run lacks a family or any softgrip mode.
pub fn choose(sweeps: &[Sweep], groups: &[FamilyResults]) -> Option<Choice> {
    choose_on_rows(&pooled_rows(sweeps, groups))
}

/// [`choose`] on a run's pooled rows.
pub fn choose_on_rows(rows: &[Row]) -> Option<Choice> {
    let modes = named(rows, |k| {
        matches!(
            k,
            ControllerKind::SoftgripEllipse | ControllerKind::SoftgripTable
        )
    });
    // With no mode there are no candidates, and `choose_among` gives `None`.
    choose_among(rows, &modes)
}

/// Each baseline's default: the same rule over that baseline's own settings, for every
/// baseline the run swept (none without all five families).
pub fn baseline_choices(sweeps: &[Sweep], groups: &[FamilyResults]) -> Vec<Choice> {
    baseline_choices_on_rows(&pooled_rows(sweeps, groups))
}

/// [`baseline_choices`] on a run's pooled rows.
pub fn baseline_choices_on_rows(rows: &[Row]) -> Vec<Choice> {
    named(rows, |k| !k.is_softgrip())
        .into_iter()
        .filter_map(|b| choose_among(rows, &[b]))
        .collect()
}

/// The controllers of `rows` that `pick` takes, each once, in the rows' order.
fn named(rows: &[Row], pick: impl Fn(ControllerKind) -> bool) -> Vec<&str> {
    let mut names: Vec<&str> = Vec::new();
    for r in rows {
        let name = r.controller.as_str();
        if ControllerKind::from_name(name).is_some_and(&pick) && !names.contains(&name) {
            names.push(name);
        }
    }
    names
}

/// The rule over the settings of the controllers named `controllers`, from a run's
/// pooled rows, or `None` when the rows lack a family or one of them.
pub fn choose_among(rows: &[Row], controllers: &[&str]) -> Option<Choice> {
    let settings: Vec<&Row> = rows
        .iter()
        .filter(|r| r.family == FAMILIES[0] && controllers.contains(&r.controller.as_str()))
        .collect();
    if !controllers
        .iter()
        .all(|c| settings.iter().any(|r| r.controller == *c))
    {
        return None;
    }
    let family_rows: Vec<[&Row; 5]> = settings
        .iter()
        .map(|s| of_setting(rows, s))
        .collect::<Option<_>>()?;
    let candidates: Vec<Candidate> = family_rows.iter().map(candidate).collect();
    // Every setting runs the same trials: the first's rows count them.
    let first = family_rows.first()?;
    let n: usize = first.iter().map(|r| r.holdable).sum();
    let (safest_drops, safe_drops_max, chosen) = cheapest_safe(&candidates, n, |c| Some(c.drops))?;
    let at_limit: Option<usize> = first.iter().map(|r| r.at_limit).sum();
    let without_limit = at_limit.and_then(|l| {
        cheapest_safe(&candidates, n - l, |c| Some(c.drops - c.drops_at_limit?)).map(
            |(safest_drops, safe_drops_max, chosen)| WithoutLimit {
                aim_trials: n - l,
                safest_drops,
                safe_drops_max,
                chosen,
            },
        )
    });
    Some(Choice {
        aim_trials: n,
        safest_drops,
        safe_drops_max,
        chosen,
        candidates,
        without_limit,
    })
}

/// The five families' pooled rows of the setting of `s` (its controller and knob value),
/// or `None` when one is missing.
fn of_setting<'a>(rows: &'a [Row], s: &Row) -> Option<[&'a Row; 5]> {
    let find = |family: &str| {
        rows.iter().find(|r| {
            r.family == family
                && r.seed.is_none()
                && r.controller == s.controller
                && r.knob_value == s.knob_value
        })
    };
    Some([
        find(FAMILIES[0])?,
        find(FAMILIES[1])?,
        find(FAMILIES[2])?,
        find(FAMILIES[3])?,
        find(FAMILIES[4])?,
    ])
}

/// The rule's steps 2 and 3 over `candidates` with `drops` of each on `n` trials: the
/// fewest drops, the most that count as safe, and the cheapest safe candidate.
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

/// One setting from its five families' pooled rows.
fn candidate(rows: &[&Row; 5]) -> Candidate {
    let drops_per_family = rows.map(|r| r.drops_holdable);
    let log_sum: f64 = rows.iter().map(|r| r.force_over_oracle.ln()).sum();
    Candidate {
        controller: rows[0].controller.clone(),
        knob_value: rows[0].knob_value,
        drops: drops_per_family.iter().sum(),
        drops_per_family,
        drops_at_limit: rows.iter().map(|r| r.drops_at_limit).sum(),
        force_over_oracle: (log_sum / FAMILIES.len() as f64).exp(),
    }
}

/// The rule's lines for people.
pub fn lines(c: &Choice) -> String {
    let mut out = format!(
        "default choice (safety first on the front): the fewest drops of holdable trials are \
         {} of {}; settings within {:.1} drops count as safe; the cheapest of them is {}@{} \
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
        "{}'s default by the same rule: {}@{} ({} drops of holdable trials, the fewest {}, \
         safe within {:.1}; {:.3} x the oracle's force)",
        c.chosen.controller,
        c.chosen.controller,
        c.chosen.knob_value,
        c.chosen.drops,
        c.safest_drops,
        c.safe_drops_max,
        c.chosen.force_over_oracle
    )
}

/// Judges a written `bench.json` (or `summary.json`) again by this build's rule: rewrites its
/// `default_choice` and `baseline_default_choices` from its pooled `rows`, leaving every
/// other byte as it was, and returns the rule's lines. Cost: one read and one write of
/// the file.
pub fn rejudge(path: &std::path::Path) -> Result<String, String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let text = std::fs::read_to_string(path).map_err(|e| at(&e))?;
    let mut v: serde_json::Value = serde_json::from_str(&text).map_err(|e| at(&e))?;
    let rows: Vec<Row> = serde_json::from_value(v["rows"].clone()).map_err(|e| at(&e))?;
    let choice = choose_on_rows(&rows);
    let baselines = baseline_choices_on_rows(&rows);
    v["default_choice"] = serde_json::to_value(&choice).map_err(|e| at(&e))?;
    v["baseline_default_choices"] = serde_json::to_value(&baselines).map_err(|e| at(&e))?;
    if v.get("per_seed_defaults").is_some() {
        super::summary::write(path, &v)?;
    } else {
        let out = serde_json::to_string_pretty(&v).map_err(|e| at(&e))?;
        std::fs::write(path, out + "\n").map_err(|e| at(&e))?;
    }
    let mut lines: Vec<String> = choice.iter().map(self::lines).collect();
    lines.extend(baselines.iter().map(baseline_line));
    Ok(lines.join("\n"))
}
