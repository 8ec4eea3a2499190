//! softgrip's default mode and safety factor, and every baseline's default knob, are the
//! ones the rule of `bench::default_choice` picks from the committed held-out run
//! (docs/bench/heldout/), whose seeds the published run does not score on; and the rule
//! itself picks, on a small hand-made run, what it says it picks.

mod common;

use host_sim::bench::default_choice::{
    baseline_choices, baseline_choices_on_rows, choose, choose_on_rows, Choice,
};
use host_sim::bench::stats::Row;
use host_sim::bench::sweep::{RunRow, Sweep, TrialResult, SWEEPS};
use host_sim::bench::FamilyResults;
use host_sim::sim::controllers::ControllerKind;
use serde_json::Value;
use softgrip::controller::ControllerConfig;
use std::path::Path;

fn json(rel: &str) -> Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(rel);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{rel}: {e}"));
    serde_json::from_str(&text).unwrap()
}

fn seeds(v: &Value) -> Vec<u64> {
    v["key"]["seeds"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_u64().unwrap())
        .collect()
}

#[test]
fn the_default_is_the_held_out_runs_choice() {
    let held = json("docs/bench/heldout/summary.json");
    let published = json("docs/bench/summary.json");
    let (h, p) = (seeds(&held), seeds(&published));
    assert!(
        h.iter().all(|s| !p.contains(s)),
        "the held-out seeds {h:?} must not be the published run's {p:?}"
    );
    assert_eq!(held["key"]["plant"], "brush");
    assert_eq!(held["key"]["hard"], false);
    let chosen = &held["default_choice"]["chosen"];
    let mode = ControllerKind::of_mode(ControllerConfig::DEFAULT.mode).name();
    assert_eq!(
        (
            chosen["controller"].as_str().unwrap(),
            chosen["knob_value"].as_f64().unwrap()
        ),
        (mode, ControllerConfig::DEFAULT.safety),
        "ControllerConfig::DEFAULT is not the held-out run's choice: {}",
        held["default_choice"]
    );
}

#[test]
fn every_baselines_default_is_the_held_out_runs_choice() {
    let held = json("docs/bench/heldout/summary.json");
    let choices = held["baseline_default_choices"].as_array().unwrap();
    let baselines: Vec<&Sweep> = SWEEPS
        .iter()
        .filter(|s| !s.controller.is_softgrip())
        .collect();
    assert_eq!(choices.len(), baselines.len(), "{choices:?}");
    for sw in baselines {
        let name = sw.controller.name();
        let c = choices
            .iter()
            .find(|c| c["chosen"]["controller"] == name)
            .unwrap_or_else(|| panic!("the held-out run chose no default for {name}"));
        assert_eq!(
            sw.default,
            c["chosen"]["knob_value"].as_f64().unwrap(),
            "{name}'s default is not the held-out run's choice: {c}"
        );
    }
}

const BLOCK: (&str, &str) = ("<!-- default-choice:begin", "<!-- default-choice:end -->");

/// docs/bench-results.md's block on the default, from the held-out run's `default_choice`.
fn render(held: &Value) -> String {
    let c = &held["default_choice"];
    let seeds: Vec<String> = seeds(held).iter().map(u64::to_string).collect();
    let cands = c["candidates"].as_array().unwrap();
    let find = |mode: &str, s: f64| {
        cands.iter().find(|x| {
            x["controller"] == mode && (x["knob_value"].as_f64().unwrap() - s).abs() < 1e-9
        })
    };
    let least_safe = |mode: &str| {
        cands
            .iter()
            .filter(|x| x["controller"] == mode && x["drops"] == c["safest_drops"])
            .map(|x| x["knob_value"].as_f64().unwrap())
            .fold(f64::INFINITY, f64::min)
    };
    let mut out = format!(
        "{} (generated from docs/bench/heldout/summary.json by \
         host-sim/tests/default_choice.rs; SOFTGRIP_WRITE_DOCS=1 rewrites it) -->\n",
        BLOCK.0
    );
    out += &format!(
        "Held-out run: seeds {}, {} trials a family and seed, {} holdable trials. The \
         fewest drops of them, {}, come from ellipse mode at {} and table mode at {}; \
         settings within {:.1} drops count as safe, and the cheapest of them is **{} at \
         {}**: {} drops, {:.3} × the oracle's force (geometric mean over the five \
         families).\n\n",
        seeds.join(", "),
        held["key"]["trials"],
        c["aim_trials"],
        c["safest_drops"],
        least_safe("softgrip-ellipse"),
        least_safe("softgrip-table"),
        c["safe_drops_max"].as_f64().unwrap(),
        c["chosen"]["controller"].as_str().unwrap(),
        c["chosen"]["knob_value"],
        c["chosen"]["drops"],
        c["chosen"]["force_over_oracle"].as_f64().unwrap(),
    );
    out += "| safety | ellipse: drops, force/oracle | table: drops, force/oracle |\n";
    out += "| ---: | ---: | ---: |\n";
    for k in 0..=15 {
        let s = 1.25 + 0.05 * f64::from(k);
        let cell = |mode: &str| {
            find(mode, s).map_or("–".to_string(), |x| {
                format!(
                    "{}, {:.3}",
                    x["drops"],
                    x["force_over_oracle"].as_f64().unwrap()
                )
            })
        };
        out += &format!(
            "| {:.2} | {} | {} |\n",
            s,
            cell("softgrip-ellipse"),
            cell("softgrip-table")
        );
    }
    out += &without_limit(held, c, &find);
    out += "\nEvery baseline enters on the same terms: the same rule, over its own knob \
            alone, chooses the default the bench marks for it (`*`).\n\n\
            | controller | default | its drops | the fewest (safe within) | \
            force/oracle |\n| --- | ---: | ---: | ---: | ---: |\n";
    for b in held["baseline_default_choices"].as_array().unwrap() {
        out += &format!(
            "| {} | {} | {} | {} ({:.1}) | {:.3} |\n",
            b["chosen"]["controller"].as_str().unwrap(),
            b["chosen"]["knob_value"],
            b["chosen"]["drops"],
            b["safest_drops"],
            b["safe_drops_max"].as_f64().unwrap(),
            b["chosen"]["force_over_oracle"].as_f64().unwrap(),
        );
    }
    out + BLOCK.1
}

/// The block's paragraph on the trials at the hand's limit: the rule without them, and
/// the chosen mode's drops family by family, with its force in `lift-hold` (the issue's
/// aim there is 1.25 × the oracle's), from 1.0 up.
fn without_limit<'a>(
    held: &Value,
    c: &Value,
    find: &impl Fn(&str, f64) -> Option<&'a Value>,
) -> String {
    let w = &c["without_limit"];
    let mode = c["chosen"]["controller"].as_str().unwrap();
    let mut out = format!(
        "\nOf the choice's {} drops, {} are trials at the hand's limit. Without the {} \
         trials at the hand's limit, the fewest drops are {}, settings within {:.1} count as \
         safe, and the rule chooses **{} at {}** ({:.3} ×). {mode}'s drops, family by \
         family (`mu-mismatch` counts the trials without a slip sensor too), and its force \
         in `lift-hold`:\n\n\
         | safety | `lift-hold` | `shake` | `twist` | `mu-mismatch` | `faults` | \
         of them at the hand's limit | `lift-hold` force/oracle |\n\
         | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
        c["chosen"]["drops"],
        c["chosen"]["drops_at_limit"],
        c["aim_trials"].as_u64().unwrap() - w["aim_trials"].as_u64().unwrap(),
        w["safest_drops"],
        w["safe_drops_max"].as_f64().unwrap(),
        w["chosen"]["controller"].as_str().unwrap(),
        w["chosen"]["knob_value"],
        w["chosen"]["force_over_oracle"].as_f64().unwrap(),
    );
    let lift_hold = |s: f64| {
        held["rows"].as_array().unwrap().iter().find(|r| {
            r["controller"] == mode
                && r["family"] == "lift-hold"
                && (r["knob_value"].as_f64().unwrap() - s).abs() < 1e-9
        })
    };
    for k in 0..=20 {
        let s = 1.0 + 0.05 * f64::from(k);
        if let (Some(x), Some(r)) = (find(mode, s), lift_hold(s)) {
            let f: Vec<String> = x["drops_per_family"]
                .as_array()
                .unwrap()
                .iter()
                .map(Value::to_string)
                .collect();
            out += &format!(
                "| {s:.2} | {} | {} | {:.3} |\n",
                f.join(" | "),
                x["drops_at_limit"],
                r["force_over_oracle"].as_f64().unwrap()
            );
        }
    }
    out
}

#[test]
fn the_bench_page_states_the_held_out_choice() {
    let held = json("docs/bench/heldout/summary.json");
    common::check_block(
        "docs/bench-results.md",
        BLOCK,
        &render(&held),
        "docs/bench/heldout/",
    )
    .unwrap();
}

const VALUES: [f64; 2] = [1.0, 1.5];

fn sweeps() -> Vec<Sweep> {
    safety_sweeps([
        ControllerKind::SoftgripEllipse,
        ControllerKind::SoftgripTable,
    ])
}

/// Two controllers swept over [`VALUES`], in this order.
fn safety_sweeps(kinds: [ControllerKind; 2]) -> Vec<Sweep> {
    kinds
        .into_iter()
        .map(|controller| Sweep {
            controller,
            knob: "safety",
            values: &VALUES,
            default: 1.0,
        })
        .collect()
}

/// Ten holdable trials per family (mu-mismatch's all with a sensor); `drops[j]` of the
/// first trials of `shake` dropped by setting `j` (ellipse 1.0, 1.5, table 1.0, 1.5), and
/// each setting's force over the oracle `force[j]` on every trial.
fn run(drops: [usize; 4], force: [f64; 4]) -> Option<Choice> {
    choose(&sweeps(), &groups(drops, force))
}

/// The trials of [`run`], for any four columns of settings.
fn groups(drops: [usize; 4], force: [f64; 4]) -> Vec<FamilyResults> {
    let families = ["lift-hold", "shake", "twist", "mu-mismatch", "faults"];
    let groups: Vec<FamilyResults> = families
        .into_iter()
        .map(|family| FamilyResults {
            family,
            seed: 1,
            results: (0..10)
                .map(|i| TrialResult {
                    true_mu: 1.0,
                    mu_ratio: 1.0,
                    sensor: true,
                    holdable: true,
                    oracle_mean_n: 2.0,
                    runs: (0..4)
                        .map(|j| RunRow {
                            dropped: family == "shake" && i < drops[j],
                            slip_events: 0,
                            slip_distance_m: 0.0,
                            mean_force_n: 2.0 * force[j],
                            peak_force_n: 2.0 * force[j],
                        })
                        .collect(),
                })
                .collect(),
        })
        .collect();
    groups
}

#[test]
fn the_rule_takes_the_cheapest_setting_as_safe_as_the_safest() {
    // 50 trials on the aims; the safest drops none, and the Wilson bound of 0 in 50
    // (7.1 %) lets 3 drops count as safe, not 4.
    let c = run([3, 0, 1, 0], [1.0, 1.5, 0.98, 1.45]).unwrap();
    assert_eq!(c.aim_trials, 50);
    assert_eq!(c.safest_drops, 0);
    assert!(
        (c.safe_drops_max - 3.56).abs() < 0.01,
        "{}",
        c.safe_drops_max
    );
    assert_eq!(
        (c.chosen.controller.as_str(), c.chosen.knob_value),
        ("softgrip-table", 1.0)
    );
    // Four drops are not as safe: the cheapest of the rest.
    let c = run([4, 0, 4, 0], [1.0, 1.5, 0.98, 1.45]).unwrap();
    assert_eq!(
        (c.chosen.controller.as_str(), c.chosen.knob_value),
        ("softgrip-table", 1.5)
    );
    let c = run([3, 0, 4, 0], [1.0, 1.5, 0.98, 1.45]).unwrap();
    assert_eq!(
        (c.chosen.controller.as_str(), c.chosen.knob_value),
        ("softgrip-ellipse", 1.0)
    );
}

#[test]
fn the_rule_needs_every_family() {
    let mut groups = Vec::new();
    for family in ["lift-hold", "shake", "twist", "faults"] {
        groups.push(FamilyResults {
            family,
            seed: 1,
            results: Vec::new(),
        });
    }
    assert!(choose(&sweeps(), &groups).is_none());
}

#[test]
fn a_baseline_is_judged_on_its_own_settings() {
    // Columns: softgrip-ellipse 1.0 and 1.5, then fixed-torsion 1.0 and 1.5.
    let sweeps = safety_sweeps([
        ControllerKind::SoftgripEllipse,
        ControllerKind::FixedTorsion,
    ]);
    // softgrip drops none; fixed-torsion's fewest is 6 (at 1.5), and 9 at 1.0 lies
    // within the Wilson bound of 6 in 50 (11.9 drops): its cheaper 1.0 is its default,
    // though softgrip's 0 would rule both out.
    let trials = groups([0, 0, 9, 6], [1.0, 1.5, 1.1, 1.6]);
    let c = baseline_choices(&sweeps, &trials);
    assert_eq!(c.len(), 1);
    assert_eq!(c[0].safest_drops, 6);
    assert!(
        (c[0].safe_drops_max - 11.9).abs() < 0.05,
        "{}",
        c[0].safe_drops_max
    );
    assert_eq!(c[0].candidates.len(), 2);
    assert_eq!(
        (c[0].chosen.controller.as_str(), c[0].chosen.knob_value),
        ("fixed-torsion", 1.0)
    );
    // Ten drops, beyond the bound of 1 in 50 (5.2): the safer setting.
    let c = baseline_choices(&sweeps, &groups([0, 0, 10, 1], [1.0, 1.5, 1.1, 1.6]));
    assert_eq!(
        (c[0].chosen.controller.as_str(), c[0].chosen.knob_value),
        ("fixed-torsion", 1.5)
    );
}

/// A trial of [`at_the_limit`]'s run: four columns of softgrip (ellipse 1.0, 1.5, table
/// 1.0, 1.5) that drop as `drop` says, then `constant` at 10 N and at 20 N, of which only
/// 20 N holds a trial `at_limit`.
fn limit_trial(at_limit: bool, drop: [bool; 4]) -> TrialResult {
    let row = |dropped| RunRow {
        dropped,
        slip_events: 0,
        slip_distance_m: 0.0,
        mean_force_n: 2.0,
        peak_force_n: 2.0,
    };
    let mut runs: Vec<RunRow> = drop.into_iter().map(row).collect();
    runs.extend([row(at_limit), row(false)]);
    TrialResult {
        true_mu: 1.0,
        mu_ratio: 1.0,
        sensor: true,
        holdable: true,
        oracle_mean_n: 2.0,
        runs,
    }
}

#[test]
fn the_rule_also_says_what_it_chooses_without_the_trials_at_the_hands_limit() {
    let mut sweeps = sweeps();
    sweeps.push(Sweep {
        controller: ControllerKind::Constant,
        knob: "force_n",
        values: &[10.0, 20.0],
        default: 20.0,
    });
    // Ten trials a family; four `twist` trials at the hand's limit, which the modes drop
    // at 1.0 and hold at 1.5.
    let groups: Vec<FamilyResults> = ["lift-hold", "shake", "twist", "mu-mismatch", "faults"]
        .into_iter()
        .map(|family| FamilyResults {
            family,
            seed: 1,
            results: (0..10)
                .map(|i| {
                    let limit = family == "twist" && i < 4;
                    limit_trial(limit, [limit, false, limit, false])
                })
                .collect(),
        })
        .collect();
    let c = choose(&sweeps, &groups).unwrap();
    // Counted, 4 drops are beyond the bound of 0 in 50 (3.56): the safer setting.
    assert_eq!((c.aim_trials, c.safest_drops), (50, 0));
    assert_eq!(c.chosen.knob_value, 1.5);
    let table_1 = &c.candidates[2];
    assert_eq!(table_1.drops_per_family, [0, 0, 4, 0, 0]);
    assert_eq!(table_1.drops_at_limit, Some(4));
    // Left out, nothing drops: the cheaper 1.0 (a tie on force goes to the lower factor).
    let w = c.without_limit.unwrap();
    assert_eq!((w.aim_trials, w.safest_drops), (46, 0));
    assert_eq!(w.chosen.knob_value, 1.0);
    // Without a `constant` sweep there are no trials at the limit to leave out.
    let c = choose(&sweeps[..2], &groups).unwrap();
    assert_eq!(c.candidates[2].drops_at_limit, None);
    assert!(c.without_limit.is_none());
}

#[test]
fn a_run_of_one_mode_gets_the_rule_over_that_mode() {
    // Columns: ellipse 1.0, 1.5, table 1.0, 1.5. Table mode alone: its 1.0 drops 5 of
    // the 50 aims, beyond the bound of 0 (3.56), so the rule takes its 1.5; ellipse's
    // columns, which would win both ways, are not in the run.
    let groups = groups([0, 0, 5, 0], [1.0, 1.1, 1.2, 1.3]);
    let both = choose(&sweeps(), &groups).unwrap();
    assert_eq!(both.chosen.controller, "softgrip-ellipse");
    let table = sweeps()[1..].to_vec();
    let alone = choose(&table, &groups_of(&groups, 2..4)).unwrap();
    assert_eq!(
        (alone.chosen.controller.as_str(), alone.chosen.knob_value),
        ("softgrip-table", 1.5)
    );
    assert_eq!(alone.candidates.len(), 2);
    // No softgrip mode in the run: no choice.
    let baselines = safety_sweeps([ControllerKind::FixedTorsion, ControllerKind::Box]);
    assert!(choose(&baselines, &groups).is_none());
}

/// `groups` with only the runs of columns `cols` (a run that swept fewer controllers).
fn groups_of(groups: &[FamilyResults], cols: std::ops::Range<usize>) -> Vec<FamilyResults> {
    groups
        .iter()
        .map(|g| FamilyResults {
            family: g.family,
            seed: g.seed,
            results: g
                .results
                .iter()
                .map(|r| TrialResult {
                    runs: r.runs[cols.clone()].to_vec(),
                    ..r.clone()
                })
                .collect(),
        })
        .collect()
}

#[test]
fn a_sensorless_mu_mismatch_drop_counts() {
    // Table 1.0 drops 4 `mu-mismatch` trials that have no slip sensor, and nothing else:
    // the aims leave them out, the rule does not, and 4 drops lie beyond the bound of 0
    // in 50 (3.56): the rule takes table 1.5.
    let mut groups = groups([0, 0, 0, 0], [1.2, 1.3, 1.0, 1.1]);
    let mu = groups
        .iter_mut()
        .find(|g| g.family == "mu-mismatch")
        .unwrap();
    for r in &mut mu.results[..4] {
        r.sensor = false;
        r.runs[2].dropped = true;
    }
    let c = choose(&sweeps(), &groups).unwrap();
    assert_eq!(c.aim_trials, 50);
    assert_eq!(c.candidates[2].drops_per_family, [0, 0, 0, 4, 0]);
    assert_eq!(
        (c.chosen.controller.as_str(), c.chosen.knob_value),
        ("softgrip-table", 1.5)
    );
}

#[test]
fn the_committed_runs_are_judged_by_this_rule() {
    // Each committed summary.json's choices are the ones this build's rule makes from its
    // pooled rows (`host-sim bench rejudge` rewrites them after a change of the rule).
    for rel in ["docs/bench/heldout/summary.json", "docs/bench/summary.json"] {
        let v = json(rel);
        let rows: Vec<Row> = serde_json::from_value(v["rows"].clone()).unwrap();
        let again = serde_json::to_value(choose_on_rows(&rows)).unwrap();
        assert_eq!(
            v["default_choice"], again,
            "{rel}: run `host-sim bench rejudge`"
        );
        let baselines = serde_json::to_value(baseline_choices_on_rows(&rows)).unwrap();
        assert_eq!(v["baseline_default_choices"], baselines, "{rel}");
    }
}
