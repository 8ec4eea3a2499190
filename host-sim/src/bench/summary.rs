//! `summary.json`: what a bench run is published by. It keeps everything its docs and
//! tests read (the run's options, its provenance, the pooled rows, the defaults' rows
//! per seed, the dominance checks, the default choices, the clairvoyant references and
//! `mu-mismatch`'s drops split by slip sensor) and leaves out the per-seed rows of every
//! setting and the trials, which the same command regenerates.

use crate::provenance::{self, Provenance};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::path::Path;

/// The summary of the run written in `dir`: `dir/summary.json`, beside its `bench.json`.
pub fn path_in(dir: &Path) -> std::path::PathBuf {
    dir.join("summary.json")
}

/// One setting's `mu-mismatch` trials with or without the slip sensor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensorSplit {
    /// The controller's name.
    pub controller: String,
    /// Its knob's value.
    pub knob_value: f64,
    /// Whether these trials list the slip sensor.
    pub slip_sensor: bool,
    /// How many trials.
    pub trials: usize,
    /// How many of them dropped the object.
    pub drops: usize,
}

/// `mu-mismatch`'s trials of `trials-mu-mismatch.csv`, per setting and sensor, in the
/// order the file first names them.
pub fn sensor_split(csv: &str) -> Result<Vec<SensorSplit>, String> {
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().ok_or("empty CSV")?.split(',').collect();
    let col = |name: &str| {
        head.iter()
            .position(|h| *h == name)
            .ok_or(format!("no column {name}"))
    };
    let (c, k, s, d) = (
        col("controller")?,
        col("knob_value")?,
        col("slip_sensor")?,
        col("dropped")?,
    );
    let mut out: Vec<SensorSplit> = Vec::new();
    for (n, line) in lines.enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        let cell = |i: usize| f.get(i).copied().ok_or(format!("line {}: short", n + 2));
        let controller = cell(c)?.to_string();
        let knob_value: f64 = cell(k)?
            .parse()
            .map_err(|e| format!("line {}: knob_value: {e}", n + 2))?;
        let slip_sensor = cell(s)? == "true";
        let dropped = cell(d)? == "true";
        let at = out.iter().position(|x| {
            x.controller == controller && x.knob_value == knob_value && x.slip_sensor == slip_sensor
        });
        let entry = match at {
            Some(i) => &mut out[i],
            None => {
                out.push(SensorSplit {
                    controller,
                    knob_value,
                    slip_sensor,
                    trials: 0,
                    drops: 0,
                });
                out.last_mut().ok_or("unreachable")?
            }
        };
        entry.trials += 1;
        entry.drops += usize::from(dropped);
    }
    Ok(out)
}

/// The summary of the run written in `dir` (its `bench.json`, and
/// `trials-mu-mismatch.csv` when the run has that family). The run's own `provenance`
/// is kept; a run written before runs recorded one takes `made_at`'s.
pub fn summarize(dir: &Path, made_at: Option<Provenance>) -> Result<Value, String> {
    let path = dir.join("bench.json");
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let text = std::fs::read_to_string(&path).map_err(|e| at(&e))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| at(&e))?;
    let provenance = match (v.get("provenance"), made_at) {
        (Some(p), _) if !p.is_null() => p.clone(),
        (_, Some(p)) => serde_json::to_value(p).map_err(|e| at(&e))?,
        _ => return Err(at(&"records no provenance: give --made-at COMMIT")),
    };
    let defaults: Vec<&Value> = v["per_seed"]
        .as_array()
        .map(|rows| {
            rows.iter()
                .filter(|r| r["default"].as_bool() == Some(true))
                .collect()
        })
        .unwrap_or_default();
    let csv = dir.join("trials-mu-mismatch.csv");
    let split = match std::fs::read_to_string(&csv) {
        Ok(text) => Some(sensor_split(&text).map_err(|e| format!("{}: {e}", csv.display()))?),
        Err(_) => None,
    };
    Ok(serde_json::json!({
        "provenance": provenance,
        "key": v["key"],
        "rows": v["rows"],
        "per_seed_defaults": defaults,
        "dominance": v["dominance"],
        "default_choice": v["default_choice"],
        "baseline_default_choices": v["baseline_default_choices"],
        "clairvoyant_constant": v["clairvoyant_constant"],
        "mu_mismatch_by_sensor": split,
    }))
}

/// The default configuration of every controller the bench runs: softgrip's
/// `ControllerConfig::DEFAULT`, and each sweep's knob and default value (a baseline's
/// whole configuration is that knob, on top of what every controller is told).
pub fn configuration() -> serde_json::Value {
    let sweeps: Vec<serde_json::Value> = super::sweep::SWEEPS
        .iter()
        .map(|s| {
            serde_json::json!({
                "controller": s.controller.name(),
                "knob": s.knob,
                "default": s.default,
            })
        })
        .collect();
    serde_json::json!({
        "softgrip": softgrip::controller::ControllerConfig::DEFAULT,
        "sweep_defaults": sweeps,
    })
}

/// The provenance of a run made at `commit` of the checkout at `dir`, written before runs
/// recorded their own: refused unless that commit's constants are this build's (then
/// this build's configuration and digest are that run's too).
pub fn made_at(dir: &Path, commit: &str) -> Result<Provenance, String> {
    let then = provenance::constants_at(dir, commit)?;
    let now = provenance::this_builds_constants();
    let changed = provenance::differences(&then, &now);
    if !changed.is_empty() {
        return Err(format!(
            "the constants at {commit} are not this build's, so this build cannot vouch for \
             that run: {}",
            changed.join("; ")
        ));
    }
    let mut p = provenance::of_this_build(dir, configuration());
    p.commit = provenance::resolve(dir, commit).ok_or(format!("no commit {commit}"))?;
    p.dirty = false;
    Ok(p)
}

/// `value` as a summary file is written: an object's keys one a line, an array's items
/// one a line, each compact (a row is a line, so a rerun's diff reads row by row).
pub fn to_text(value: &Value) -> String {
    let compact = |v: &Value| serde_json::to_string(v).unwrap_or_default();
    let Some(obj) = value.as_object() else {
        return compact(value) + "\n";
    };
    let mut out = String::from("{\n");
    for (i, (k, v)) in obj.iter().enumerate() {
        let comma = if i + 1 < obj.len() { "," } else { "" };
        match v.as_array() {
            Some(items) if !items.is_empty() => {
                out.push_str(&format!("{}: [\n", compact(&Value::from(k.as_str()))));
                for (j, item) in items.iter().enumerate() {
                    let c = if j + 1 < items.len() { "," } else { "" };
                    out.push_str(&format!("  {}{c}\n", compact(item)));
                }
                out.push_str(&format!("]{comma}\n"));
            }
            _ => out.push_str(&format!(
                "{}: {}{comma}\n",
                compact(&Value::from(k.as_str())),
                compact(v)
            )),
        }
    }
    out + "}\n"
}

/// Writes `value` as `path` ([`to_text`]).
pub fn write(path: &Path, value: &Value) -> Result<(), String> {
    std::fs::write(path, to_text(value)).map_err(|e| format!("{}: {e}", path.display()))
}
