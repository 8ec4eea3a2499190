//! The benchmark's text tables, its dominance checks, `bench.json` and the trials' CSV.

use super::shard::Key;
use super::stats::Row;
use super::sweep::{settings, Sweep, TrialResult, COMMON_PRACTICE_SAFETY};
use crate::sim::controllers::ControllerKind;
use softgrip::controller::ControllerConfig;
use std::fmt::Write;
use std::path::Path;

/// The text table of one family's rows: controller, knob and value (`*` marks the
/// default), drops of all trials, drops of the holdable ones, drops of those at the
/// hand's limit ([`AT_LIMIT_FRACTION`](super::stats::AT_LIMIT_FRACTION); `-` without a
/// `constant` sweep), the holdable drops that were turns rather than slides
/// ([`lost_by_turning`](super::stats::lost_by_turning)), the drop rate with its Wilson
/// interval [%] ([`wilson95`](super::stats::wilson95)), force over oracle [-], mean force
/// \[N\], mean slip \[mm\].
pub fn family_table(family: &str, rows: &[Row]) -> String {
    let mut s = String::new();
    let (trials, holdable) = rows.first().map_or((0, 0), |r| (r.trials, r.holdable));
    let limit = rows.first().and_then(|r| r.at_limit).map_or(String::new(), |l| {
        format!(
            ", {l} of them at the hand's limit (no constant grip below {:.0} % of N_max holds them)",
            100.0 * super::stats::AT_LIMIT_FRACTION
        )
    });
    let _ = writeln!(
        s,
        "family {family}: {trials} trials, {holdable} holdable (constant at N_max holds them){limit}"
    );
    let _ = writeln!(
        s,
        "{:<15} {:<8} {:>7}  {:>7}  {:>12}  {:>11}  {:>8}  {:>19}  {:>9}  {:>10}  {:>9}",
        "controller",
        "knob",
        "value",
        "drops",
        "drops (hold.)",
        "(at limit)",
        "(turns)",
        "drop rate [95% CI]",
        "N/oracle",
        "mean N [N]",
        "slip [mm]"
    );
    let _ = writeln!(s, "{}", "-".repeat(136));
    for r in rows {
        let value = format!("{}{}", r.knob_value, if r.default { "*" } else { "" });
        let at_limit = match (r.drops_at_limit, r.at_limit) {
            (Some(d), Some(l)) => format!("{d}/{l}"),
            _ => "-".to_string(),
        };
        let _ = writeln!(
            s,
            "{:<15} {:<8} {:>7}  {:>7}  {:>12}  {:>11}  {:>8}  {:>5.1} % [{:>4.1}, {:>4.1}]  {:>9.3}  {:>10.3}  {:>9.3}",
            r.controller,
            r.knob,
            value,
            format!("{}/{}", r.drops, r.trials),
            format!("{}/{}", r.drops_holdable, r.holdable),
            at_limit,
            r.drops_turned,
            100.0 * r.drop_rate,
            100.0 * r.drop_rate_ci95[0],
            100.0 * r.drop_rate_ci95[1],
            r.force_over_oracle,
            r.mean_force_n,
            1e3 * r.slip_distance_m,
        );
    }
    s
}

/// One line per family: of each controller's holdable drops over every setting of its
/// knob, how many were turns ([`lost_by_turning`](super::stats::lost_by_turning)), in
/// the order of `rows`; empty when no controller dropped a holdable trial.
pub fn turn_line(family: &str, rows: &[Row]) -> String {
    let mut tally: Vec<(&str, usize, usize)> = Vec::new();
    for r in rows {
        match tally.iter_mut().find(|t| t.0 == r.controller) {
            Some(t) => {
                t.1 += r.drops_turned;
                t.2 += r.drops_holdable;
            }
            None => tally.push((&r.controller, r.drops_turned, r.drops_holdable)),
        }
    }
    if tally.iter().all(|t| t.2 == 0) {
        return String::new();
    }
    let cells: Vec<String> = tally
        .iter()
        .map(|(c, turned, dropped)| format!("{c} {turned}/{dropped}"))
        .collect();
    format!(
        "{family}: holdable drops that were turns past {} rad, not slides, over every setting: {}\n",
        crate::sim::run::DROP_ROTATION_RAD,
        cells.join(", ")
    )
}

/// What `bench.json` holds.
pub struct JsonParts<'a> {
    /// The build that made the run.
    pub provenance: &'a crate::provenance::Provenance,
    /// The run's options.
    pub key: &'a Key,
    /// The rows pooled over the seeds.
    pub rows: &'a [Row],
    /// The rows of each seed.
    pub per_seed: &'a [Row],
    /// The dominance checks.
    pub dominance: &'a [Dominance],
    /// softgrip's default as the run would choose it (`null` without all five families
    /// and both softgrip modes).
    pub default_choice: Option<&'a super::default_choice::Choice>,
    /// Each baseline's default by the same rule, over its own knob.
    pub baseline_default_choices: &'a [super::default_choice::Choice],
    /// Each family's clairvoyant constant grip, a reference.
    pub clairvoyant_constant: &'a [super::stats::Clairvoyant],
}

/// Writes `bench.json`: the build that made it (`provenance`: commit, configuration,
/// constants and their digest), the run's options (`key`: plant, seeds, trials, families,
/// sweeps, link...), the `rows` pooled over the seeds, the `per_seed` rows, the
/// `dominance` checks, the `default_choice`, the `baseline_default_choices` and each
/// family's `clairvoyant_constant` reference.
pub fn write_json(path: &Path, parts: &JsonParts) -> std::io::Result<()> {
    let v = serde_json::json!({
        "provenance": parts.provenance,
        "key": parts.key,
        "rows": parts.rows,
        "per_seed": parts.per_seed,
        "dominance": parts.dominance,
        "default_choice": parts.default_choice,
        "baseline_default_choices": parts.baseline_default_choices,
        "clairvoyant_constant": parts.clairvoyant_constant,
    });
    let text = serde_json::to_string_pretty(&v).map_err(std::io::Error::other)?;
    std::fs::write(path, text + "\n")
}

/// Writes `trials-FAMILY.csv`: one line per seed, trial, controller and knob value, with
/// the trial's true μ [-] and its ratio to the measured one [-], whether it lists the
/// slip sensor, whether it is holdable and its oracle force \[N\], then the run's drop,
/// slip events, slip distance \[m\], mean and peak force \[N\].
pub fn write_trials_csv(
    path: &Path,
    sweeps: &[Sweep],
    by_seed: &[(u64, &[TrialResult])],
) -> std::io::Result<()> {
    let mut s = String::from(
        "seed,trial,true_mu,mu_ratio,slip_sensor,holdable,oracle_mean_n,controller,knob_value,\
         dropped,slip_events,slip_distance_m,mean_force_n,peak_force_n\n",
    );
    for (seed, results) in by_seed {
        for (i, r) in results.iter().enumerate() {
            for (col, sw, v) in settings(sweeps) {
                let run = &r.runs[col];
                let _ = writeln!(
                    s,
                    "{seed},{i},{},{},{},{},{},{},{v},{},{},{},{},{}",
                    r.true_mu,
                    r.mu_ratio,
                    r.sensor,
                    r.holdable,
                    r.oracle_mean_n,
                    sw.controller.name(),
                    run.dropped,
                    run.slip_events,
                    run.slip_distance_m,
                    run.mean_force_n,
                    run.peak_force_n
                );
            }
        }
    }
    std::fs::write(path, s)
}

/// Force over the oracle a softgrip setting must stay under, as a fraction of the one
/// it beats [-].
pub const FORCE_MARGIN: f64 = 0.98;

/// Baseline settings that drop more than this are not compared.
pub const DOMINANCE_MAX_DROP_RATE: f64 = 0.05;

/// Whether `a` beats `b`: a drop rate whose Wilson upper bound
/// ([`wilson95`](super::stats::wilson95)) is no higher, and force over the oracle at most
/// [`FORCE_MARGIN`] of `b`'s.
pub fn beats(a: &Row, b: &Row) -> bool {
    a.drop_rate_ci95[1] <= b.drop_rate_ci95[1]
        && a.force_over_oracle <= FORCE_MARGIN * b.force_over_oracle
}

/// One baseline setting in a dominance check.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Contest {
    /// `controller@knob_value`.
    pub baseline: String,
    /// Its drops and trials.
    pub drops: [usize; 2],
    /// Its force over the oracle.
    pub force_over_oracle: f64,
    /// The cheapest setting of one softgrip mode that beats it, `controller@knob_value`,
    /// with its force over the oracle; `None` when none does.
    pub beaten_by: Option<(String, f64)>,
}

/// The dominance checks of one family.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Dominance {
    /// The family.
    pub family: String,
    /// The drop-rate limit of the baseline settings compared.
    pub max_drop_rate: f64,
    /// Every baseline setting that drops at most `max_drop_rate`, by force, and whether
    /// (by which setting of a single softgrip mode) it is beaten.
    pub contests: Vec<Contest>,
    /// The baselines whose default setting beats softgrip's default (the default of the
    /// configuration's mode), as `controller@knob_value`.
    pub defaults_beaten_by: Vec<String>,
    /// The baselines with a safety factor that, at the margin of common practice
    /// ([`COMMON_PRACTICE_SAFETY`], their default before the rule chose them), beat
    /// softgrip's default, as `controller@knob_value`.
    pub common_practice_beaten_by: Vec<String>,
    /// softgrip's default, `controller@knob_value`.
    pub softgrip_default: String,
}

fn name(r: &Row) -> String {
    format!("{}@{}", r.controller, r.knob_value)
}

/// The checks of [`Dominance`] over one family's rows: each baseline setting that drops
/// at most `max_drop_rate`, and each baseline's default, against softgrip, mode by mode
/// (the modes are never pooled), by [`beats`].
pub fn dominance(family: &str, rows: &[Row], max_drop_rate: f64) -> Dominance {
    let softgrip = |r: &Row| ControllerKind::name_is_softgrip(&r.controller);
    let mut theirs: Vec<&Row> = rows
        .iter()
        .filter(|r| !softgrip(r) && r.drop_rate <= max_drop_rate)
        .collect();
    theirs.sort_by(|a, b| a.force_over_oracle.total_cmp(&b.force_over_oracle));
    let modes: Vec<&str> = {
        let mut m: Vec<&str> = rows
            .iter()
            .filter(|r| softgrip(r))
            .map(|r| r.controller.as_str())
            .collect();
        m.dedup();
        m
    };
    let contests = theirs
        .iter()
        .map(|b| {
            let best = modes
                .iter()
                .filter_map(|m| {
                    rows.iter()
                        .filter(|s| s.controller == *m && beats(s, b))
                        .min_by(|x, y| x.force_over_oracle.total_cmp(&y.force_over_oracle))
                })
                .min_by(|x, y| x.force_over_oracle.total_cmp(&y.force_over_oracle));
            Contest {
                baseline: name(b),
                drops: [b.drops, b.trials],
                force_over_oracle: b.force_over_oracle,
                beaten_by: best.map(|s| (name(s), s.force_over_oracle)),
            }
        })
        .collect();
    let ours = softgrip_default(rows);
    let beating = |pick: &dyn Fn(&Row) -> bool| match ours {
        Some(o) => rows
            .iter()
            .filter(|r| !softgrip(r) && pick(r) && beats(r, o))
            .map(name)
            .collect(),
        None => Vec::new(),
    };
    let defaults_beaten_by = beating(&|r| r.default);
    let common_practice_beaten_by =
        beating(&|r| r.knob == "safety" && r.knob_value == COMMON_PRACTICE_SAFETY);
    Dominance {
        family: family.to_string(),
        max_drop_rate,
        contests,
        defaults_beaten_by,
        common_practice_beaten_by,
        softgrip_default: ours.map(name).unwrap_or_default(),
    }
}

/// softgrip's default row: the default setting of the default configuration's mode.
pub fn softgrip_default(rows: &[Row]) -> Option<&Row> {
    let kind = ControllerKind::of_mode(ControllerConfig::DEFAULT.mode);
    rows.iter()
        .find(|r| r.controller == kind.name() && r.default)
}

/// The checks' lines for people.
pub fn dominance_lines(d: &Dominance) -> String {
    let open: Vec<&Contest> = d
        .contests
        .iter()
        .filter(|c| c.beaten_by.is_none())
        .collect();
    let pct = 100.0 * d.max_drop_rate;
    let mut s = if open.is_empty() {
        format!(
            "{}: every one of the {} baseline settings that drop at most {pct:.0} % is beaten \
             by a setting of one softgrip mode",
            d.family,
            d.contests.len()
        )
    } else {
        let names: Vec<&str> = open.iter().map(|c| c.baseline.as_str()).collect();
        format!(
            "{}: NOT beaten by any setting of one softgrip mode: {} (of {} baseline settings \
             that drop at most {pct:.0} %)",
            d.family,
            names.join(", "),
            d.contests.len()
        )
    };
    if d.softgrip_default.is_empty() {
        // softgrip's default mode did not run.
    } else if d.defaults_beaten_by.is_empty() {
        let _ = write!(
            s,
            "\n{}: no baseline's default beats softgrip's default ({})",
            d.family, d.softgrip_default
        );
    } else {
        let _ = write!(
            s,
            "\n{}: softgrip's default ({}) is beaten by the default of {}",
            d.family,
            d.softgrip_default,
            d.defaults_beaten_by.join(", ")
        );
    }
    if !d.common_practice_beaten_by.is_empty() {
        let _ = write!(
            s,
            "\n{}: at the margin of common practice ({COMMON_PRACTICE_SAFETY}), {} beats \
             softgrip's default",
            d.family,
            d.common_practice_beaten_by.join(", ")
        );
    }
    s
}
