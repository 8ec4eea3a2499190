//! The benchmark's text tables and `bench.json`.

use super::sweep::Row;
use crate::sim::controllers::ControllerKind;
use std::fmt::Write;
use std::path::Path;

/// The text table of one family's rows: controller, knob and value (`*` marks the
/// default), drops of all trials, drops of the holdable ones, the drop rate with its
/// Wilson 95 % interval [%], force over oracle [-], mean force [N], mean slip [mm].
pub fn family_table(family: &str, rows: &[Row]) -> String {
    let mut s = String::new();
    let (trials, holdable) = rows.first().map_or((0, 0), |r| (r.trials, r.holdable));
    let _ = writeln!(
        s,
        "family {family}: {trials} trials, {holdable} holdable (constant at N_max holds them)"
    );
    let _ = writeln!(
        s,
        "{:<15} {:<8} {:>7}  {:>7}  {:>12}  {:>19}  {:>9}  {:>10}  {:>9}",
        "controller",
        "knob",
        "value",
        "drops",
        "drops (hold.)",
        "drop rate [95% CI]",
        "N/oracle",
        "mean N [N]",
        "slip [mm]"
    );
    let _ = writeln!(s, "{}", "-".repeat(113));
    for r in rows {
        let value = format!("{}{}", r.knob_value, if r.default { "*" } else { "" });
        let _ = writeln!(
            s,
            "{:<15} {:<8} {:>7}  {:>7}  {:>12}  {:>5.1} % [{:>4.1}, {:>4.1}]  {:>9.3}  {:>10.3}  {:>9.3}",
            r.controller,
            r.knob,
            value,
            format!("{}/{}", r.drops, r.trials),
            format!("{}/{}", r.drops_holdable, r.holdable),
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

/// Writes `bench.json`: `{"seed", "trials", "link", "rows": [...], "dominance": [...]}`.
pub fn write_json(
    path: &Path,
    seed: u64,
    trials: usize,
    link: &str,
    rows: &[Row],
    dominance: &[Dominance],
) -> std::io::Result<()> {
    let v = serde_json::json!({
        "seed": seed,
        "trials": trials,
        "link": link,
        "rows": rows,
        "dominance": dominance,
    });
    let text = serde_json::to_string_pretty(&v).map_err(std::io::Error::other)?;
    std::fs::write(path, text + "\n")
}

/// Writes `trials-FAMILY.csv`: one line per trial, controller and knob value, with the
/// trial's true μ [-] and its ratio to the measured one [-], whether it lists the slip sensor, whether it is holdable and its
/// oracle force [N], then the run's drop, slip events, slip distance [m], mean and peak
/// force [N].
pub fn write_trials_csv(
    path: &Path,
    sweeps: &[super::sweep::Sweep],
    results: &[super::sweep::TrialResult],
) -> std::io::Result<()> {
    let mut s = String::from(
        "trial,true_mu,mu_ratio,slip_sensor,holdable,oracle_mean_n,controller,knob_value,dropped,\
         slip_events,slip_distance_m,mean_force_n,peak_force_n\n",
    );
    for (i, r) in results.iter().enumerate() {
        let (mu, ratio, sensor) = (r.true_mu, r.mu_ratio, r.sensor);
        let mut col = 0;
        for sw in sweeps {
            for &v in sw.values {
                let run = &r.runs[col];
                col += 1;
                let _ = writeln!(
                    s,
                    "{i},{mu},{ratio},{sensor},{},{},{},{v},{},{},{},{},{}",
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

/// The claim the benchmark tests, for one family: for each baseline setting that drops at
/// most [`DOMINANCE_MAX_DROP_RATE`] of the trials, a softgrip setting (either mode, any
/// safety factor) with a drop rate no higher and a force over the oracle strictly lower.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Dominance {
    /// The family.
    pub family: String,
    /// Baseline settings considered (those at or under the drop-rate limit).
    pub baselines: usize,
    /// Those that no softgrip setting beats, as `controller@knob_value`.
    pub undominated: Vec<String>,
}

/// Baseline settings that drop more than this are not compared.
pub const DOMINANCE_MAX_DROP_RATE: f64 = 0.10;

/// The dominance check of [`Dominance`] over one family's rows.
pub fn dominance(family: &str, rows: &[Row]) -> Dominance {
    let softgrip = |r: &&Row| ControllerKind::name_is_softgrip(&r.controller);
    let ours: Vec<&Row> = rows.iter().filter(softgrip).collect();
    let theirs: Vec<&Row> = rows
        .iter()
        .filter(|r| !softgrip(r) && r.drop_rate <= DOMINANCE_MAX_DROP_RATE)
        .collect();
    let undominated = theirs
        .iter()
        .filter(|b| {
            !ours
                .iter()
                .any(|s| s.drop_rate <= b.drop_rate && s.force_over_oracle < b.force_over_oracle)
        })
        .map(|b| format!("{}@{}", b.controller, b.knob_value))
        .collect();
    Dominance {
        family: family.to_string(),
        baselines: theirs.len(),
        undominated,
    }
}

/// One line for people.
pub fn dominance_line(d: &Dominance) -> String {
    if d.undominated.is_empty() {
        format!(
            "{}: softgrip dominates all {} baseline settings that drop at most {:.0} %",
            d.family,
            d.baselines,
            100.0 * DOMINANCE_MAX_DROP_RATE
        )
    } else {
        format!(
            "{}: NOT dominated by any softgrip setting: {} (of {} baseline settings that drop \
             at most {:.0} %)",
            d.family,
            d.undominated.join(", "),
            d.baselines,
            100.0 * DOMINANCE_MAX_DROP_RATE
        )
    }
}
