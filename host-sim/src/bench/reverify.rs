//! `host-sim bench reverify`: a published run's evidence checked again on this build,
//! at the cost of one seed. It reruns, with this build, the bench a summary's `key`
//! describes on one of its seeds, and compares every row of the summary's
//! `per_seed_defaults` of that seed with the rerun's, bit for bit (the same JSON
//! number). When every row is equal it appends this build's provenance, with the seed and
//! the number of rows compared, to the summary's `provenance.reverified` and rewrites the
//! summary, every other byte as it was; on a difference it writes nothing and names the
//! first differing row and field.
//!
//! The rerun runs only what those rows read: each controller at its default alone, but
//! `constant` over its whole grid, since every row's `at_limit` and `drops_at_limit` are
//! judged on that grid ([`super::stats::at_limit`]). A trial's result depends only on its
//! family, seed and index, and a controller's runs of a trial not on the others beside it
//! ([`super::shard`]), so those rows are the ones the whole bench would give.
//!
//! What it proves is narrow: this build reproduces the published defaults' rows of the
//! rerun seed. It says nothing of the other seeds, nor of the settings other than the
//! defaults; it is meant for a change that keeps every output bit-identical (a refactor),
//! where rerunning the whole run would only spend hours to say the same.

use super::families::{self, Ranges};
use super::shard::{Key, SweepKey};
use super::stats;
use super::summary;
use super::sweep::{Sweep, TrialResult, SWEEPS};
use super::trial_finger::{BenchPlant, FingerSource};
use super::{BenchLink, BenchOptions};
use crate::experiment::FingerSpec;
use crate::provenance::{self, Provenance};
use crate::sim::controllers::ControllerKind;
use serde_json::Value;
use softgrip::controller::FingerShape;
use std::path::Path;

/// This build's sweep of the controller `k` names, refused unless its grid and its
/// default are the key's (a changed grid or default is no refactor: the summary's rows
/// would not be the ones this build's bench writes).
fn this_builds_sweep(k: &SweepKey) -> Result<Sweep, String> {
    let sw = SWEEPS
        .iter()
        .find(|s| s.controller.name() == k.controller)
        .ok_or_else(|| format!("the key's controller {} has no sweep here", k.controller))?;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<u64>>();
    if bits(sw.values) != bits(&k.values) || sw.default.to_bits() != k.default.to_bits() {
        return Err(format!(
            "{}: the key's grid {:?} with default {} is not this build's, {:?} with default \
             {}: a changed grid or default is not a bit-identical change; run the bench again",
            k.controller, k.values, k.default, sw.values, sw.default
        ));
    }
    Ok(*sw)
}

/// `sw` as the rerun runs it: `constant` whole (the rows' `at_limit` read its grid), any
/// other controller at its default alone (no value, when the grid lacks its default).
fn defaults_only(sw: Sweep) -> Sweep {
    if sw.controller == ControllerKind::Constant {
        return sw;
    }
    let grid: &'static [f64] = sw.values;
    let values = match grid.iter().position(|v| *v == sw.default) {
        Some(i) => &grid[i..=i],
        None => &grid[..0],
    };
    Sweep { values, ..sw }
}

/// The trials' fingers a key records.
fn source_of(key: &Key) -> Result<FingerSource, String> {
    if let Some([shape, mu, k, c, gamma, half_length_m]) = key.finger {
        let shape = if shape == 1.0 {
            FingerShape::Disc
        } else {
            FingerShape::Rect
        };
        return Ok(FingerSource::Fixed(FingerSpec {
            shape,
            mu,
            k,
            c,
            gamma,
            half_length_m,
            skew: None,
        }));
    }
    match key.plant.as_str() {
        "brush" => Ok(FingerSource::Drawn(BenchPlant::Brush)),
        "fls" => Ok(FingerSource::Drawn(BenchPlant::Fls)),
        other => Err(format!("the key's plant {other} is not brush or fls")),
    }
}

/// The options of the whole bench `key` describes, as this build runs it; refused
/// unless this build's key of them is `key` itself.
fn whole_options(key: &Key, out: &Path, quiet: bool) -> Result<BenchOptions, String> {
    let families = key
        .families
        .iter()
        .map(|f| {
            families::NAMES
                .iter()
                .copied()
                .find(|n| n == f)
                .ok_or_else(|| format!("the key's family {f} is not one of this build's"))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let link = match key.link.as_str() {
        "direct" => BenchLink::Direct,
        "pty" => BenchLink::Pty,
        other => return Err(format!("the key's link {other} is not direct or pty")),
    };
    let opts = BenchOptions {
        families,
        sweeps: key
            .sweeps
            .iter()
            .map(this_builds_sweep)
            .collect::<Result<_, _>>()?,
        source: source_of(key)?,
        ranges: Ranges {
            hard: key.hard,
            tell_actuator: key.tell_actuator,
        },
        trials: key.trials,
        seeds: key.seeds.clone(),
        shard: None,
        link,
        out: out.to_path_buf(),
        trace: false,
        quiet,
    };
    if Key::of(&opts) != *key {
        return Err(format!(
            "this build cannot run the bench the key describes (it would record {:?})",
            Key::of(&opts)
        ));
    }
    Ok(opts)
}

/// The options of the rerun: the bench `key` describes, on `seed` alone, each controller
/// at its default (`defaults_only`).
pub fn rerun_options(
    key: &Key,
    seed: u64,
    out: &Path,
    quiet: bool,
) -> Result<BenchOptions, String> {
    if !key.seeds.contains(&seed) {
        let seeds: Vec<String> = key.seeds.iter().map(u64::to_string).collect();
        return Err(format!(
            "--seed {seed}: not one of the run's seeds ({})",
            seeds.join(", ")
        ));
    }
    let mut opts = whole_options(key, out, quiet)?;
    opts.seeds = vec![seed];
    opts.sweeps = opts.sweeps.into_iter().map(defaults_only).collect();
    Ok(opts)
}

/// Runs `opts` (no file written) and returns its per-seed rows of each controller's
/// default, as `bench.json` writes them.
pub fn rerun_defaults(opts: &BenchOptions) -> Result<Vec<Value>, String> {
    let units = super::shard::units(opts);
    let bar = crate::progress::bar(units.len() as u64, "trials", opts.quiet);
    let results = super::run_units(opts, &units, &bar).map_err(|e| e.to_string())?;
    bar.finish_and_clear();
    let mut out = Vec::new();
    for g in super::group(opts, &units, results) {
        let trials: Vec<&TrialResult> = g.results.iter().collect();
        for row in stats::rows(g.family, Some(g.seed), &opts.sweeps, &trials) {
            if row.default {
                out.push(serde_json::to_value(row).map_err(|e| e.to_string())?);
            }
        }
    }
    Ok(out)
}

/// How a row is named in a message: `family controller (seed S)`.
fn row_name(r: &Value) -> String {
    let s = |f: &str| r[f].as_str().unwrap_or("?").to_string();
    format!("{} {} (seed {})", s("family"), s("controller"), r["seed"])
}

/// A field as the summary writes it, `-` when absent: two fields are equal when their
/// texts are (so a float is equal only to the same bits).
fn field_text(v: Option<&Value>) -> String {
    v.map_or("-".into(), |v| serde_json::to_string(v).unwrap_or_default())
}

/// Compares the published rows with the rerun's, row by row (the same family and
/// controller) and field by field: the number of rows compared, or the first difference.
pub fn compare(published: &[&Value], now: &[Value]) -> Result<usize, String> {
    let same =
        |a: &Value, b: &Value| a["family"] == b["family"] && a["controller"] == b["controller"];
    for p in published {
        let n = now.iter().find(|n| same(p, n)).ok_or_else(|| {
            format!(
                "per_seed_defaults row {}: the rerun has no such row",
                row_name(p)
            )
        })?;
        let mut fields: Vec<&String> = Vec::new();
        for o in [p.as_object(), n.as_object()].into_iter().flatten() {
            fields.extend(o.keys().filter(|k| !fields.contains(k)).collect::<Vec<_>>());
        }
        for f in fields {
            let (was, is) = (field_text(p.get(f)), field_text(n.get(f)));
            if was != is {
                return Err(format!(
                    "per_seed_defaults row {}: {f}: published {was}, now {is}",
                    row_name(p)
                ));
            }
        }
    }
    if let Some(n) = now.iter().find(|n| !published.iter().any(|p| same(p, n))) {
        return Err(format!(
            "the rerun has a default row the summary does not publish: {}",
            row_name(n)
        ));
    }
    Ok(published.len())
}

/// The summary at `path`, refused unless it is as `bench summary` writes it (so that the
/// rewrite changes no other byte).
fn read_summary(path: &Path) -> Result<Value, String> {
    let at = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let text = std::fs::read_to_string(path).map_err(|e| at(&e))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| at(&e))?;
    if summary::to_text(&v) != text {
        return Err(at(
            &"not laid out as `bench summary` writes a summary, so a rewrite \
                        would change more than its provenance; write it again first",
        ));
    }
    if !v["provenance"].is_object() {
        return Err(at(&"records no provenance"));
    }
    Ok(v)
}

/// What [`reverify`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct Reverified {
    /// The rows compared, all equal.
    pub rows_compared: usize,
    /// The entry appended to `provenance.reverified`.
    pub entry: Value,
}

/// Reverifies the summary at `path` on `seed` with this build (started in `here`, any
/// folder of the checkout): refused when the sources differ from their commit unless
/// `allow_dirty`; on equal rows, appends the entry and rewrites the summary; otherwise
/// writes nothing and returns the first difference.
pub fn reverify(
    path: &Path,
    seed: u64,
    allow_dirty: bool,
    here: &Path,
    quiet: bool,
) -> Result<Reverified, String> {
    let mut v = read_summary(path)?;
    let key: Key = serde_json::from_value(v["key"].clone())
        .map_err(|e| format!("{}: key: {e}", path.display()))?;
    let out = path.parent().unwrap_or(Path::new("."));
    let opts = rerun_options(&key, seed, out, quiet)?;
    let build: Provenance = provenance::of_this_build(here, summary::configuration());
    if build.dirty && !allow_dirty {
        return Err(format!(
            "the sources that can change a result differ from commit {} (or this is no git \
             checkout): commit them first; --allow-dirty records a dirty entry, which no \
             published run accepts",
            build.commit
        ));
    }
    let now = rerun_defaults(&opts)?;
    let published: Vec<&Value> = v["per_seed_defaults"]
        .as_array()
        .map(|rows| rows.iter().filter(|r| r["seed"] == seed).collect())
        .unwrap_or_default();
    if published.is_empty() {
        return Err(format!(
            "{}: per_seed_defaults has no row of seed {seed}",
            path.display()
        ));
    }
    let rows_compared = compare(&published, &now)?;
    let mut entry = serde_json::to_value(&build).map_err(|e| e.to_string())?;
    entry["seed"] = seed.into();
    entry["rows_compared"] = rows_compared.into();
    let list = &mut v["provenance"]["reverified"];
    if list.is_null() {
        *list = Value::Array(Vec::new());
    }
    list.as_array_mut()
        .ok_or_else(|| format!("{}: provenance.reverified is no array", path.display()))?
        .push(entry.clone());
    summary::write(path, &v)?;
    Ok(Reverified {
        rows_compared,
        entry,
    })
}
