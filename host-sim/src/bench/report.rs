//! The benchmark's text tables and `bench.json`.

use super::sweep::Row;
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

/// Writes `bench.json`: `{"seed", "trials", "link", "rows": [...]}`.
pub fn write_json(
    path: &Path,
    seed: u64,
    trials: usize,
    link: &str,
    rows: &[Row],
) -> std::io::Result<()> {
    let v = serde_json::json!({
        "seed": seed,
        "trials": trials,
        "link": link,
        "rows": rows,
    });
    let text = serde_json::to_string_pretty(&v).map_err(std::io::Error::other)?;
    std::fs::write(path, text + "\n")
}
