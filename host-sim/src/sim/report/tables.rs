//! The fixed-width tables for the terminal and the verdict on a run.

use super::*;

/// The verdict on one run: for a scene that should hold (`expected_slip == false`),
/// `held` if it had no slip event and was not dropped, else `SLIPPED`; for an overload
/// scene, `overload (slipped as expected)` if it slipped or was dropped, else `held
/// (unexpected)`. (On the limit surface a drop always follows a slip event; the brush
/// finger can also lose the object by creep, its centre still stuck.)
pub fn verdict(run: &RunSummary) -> &'static str {
    match (run.expected_slip, run.slip_events > 0 || run.dropped) {
        (false, false) => "held",
        (false, true) => "SLIPPED",
        (true, true) => "overload (slipped as expected)",
        (true, false) => "held (unexpected)",
    }
}

#[derive(Clone, Copy, PartialEq)]
pub(super) enum Align {
    Left,
    Right,
}

/// Lays out a fixed-width table: a header, a rule, the rows; columns two spaces apart.
pub(super) fn render_table(headers: &[&str], align: &[Align], rows: &[Vec<String>]) -> String {
    let widths: Vec<usize> = headers
        .iter()
        .enumerate()
        .map(|(c, h)| {
            rows.iter()
                .map(|r| r[c].chars().count())
                .chain(std::iter::once(h.chars().count()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[&str]| -> String {
        let mut s = String::new();
        for (c, cell) in cells.iter().enumerate() {
            if c > 0 {
                s.push_str("  ");
            }
            let w = widths[c];
            match align[c] {
                Align::Left => s.push_str(&format!("{cell:<w$}")),
                Align::Right => s.push_str(&format!("{cell:>w$}")),
            }
        }
        s.truncate(s.trim_end().len());
        s.push('\n');
        s
    };
    let mut out = line(headers);
    let total: usize = widths.iter().sum::<usize>() + 2 * widths.len().saturating_sub(1);
    out.push_str(&"-".repeat(total));
    out.push('\n');
    for r in rows {
        let cells: Vec<&str> = r.iter().map(String::as_str).collect();
        out.push_str(&line(&cells));
    }
    out
}

/// A fixed-width text table of the runs, one row each, in input order: scene, controller,
/// dropped (yes/no), slip events, slip distance \[mm\], slip rotation \[mrad\], mean N \[N\],
/// peak N \[N\], max utilisation, expected slip (yes/no) and the [`verdict`].
pub fn summary_table(runs: &[RunSummary]) -> String {
    use Align::{Left as L, Right as R};
    let headers = [
        "scene",
        "controller",
        "dropped",
        "slip events",
        "slip distance [mm]",
        "slip rotation [mrad]",
        "mean N [N]",
        "peak N [N]",
        "max utilisation",
        "expected slip",
        "verdict",
    ];
    let align = [L, L, L, R, R, R, R, R, R, L, L];
    let rows: Vec<Vec<String>> = runs
        .iter()
        .map(|r| {
            vec![
                r.scene.clone(),
                r.controller.clone(),
                if r.dropped { "yes" } else { "no" }.to_string(),
                r.slip_events.to_string(),
                format!("{:.3}", r.slip_distance_m * 1e3),
                format!("{:.3}", r.slip_rotation_rad * 1e3),
                format!("{:.3}", r.mean_normal_force_n),
                format!("{:.3}", r.peak_normal_force_n),
                format!("{:.3}", r.max_utilisation),
                if r.expected_slip { "yes" } else { "no" }.to_string(),
                verdict(r).to_string(),
            ]
        })
        .collect();
    render_table(&headers, &align, &rows)
}

/// The distinct names, in order of first appearance.
pub(super) fn first_appearance<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

/// Whether a controller counts as softgrip (in any mode) rather than a baseline.
pub(super) fn is_softgrip(controller: &str) -> bool {
    crate::sim::controllers::ControllerKind::name_is_softgrip(controller)
}

/// Whether a run held its object: no slip event and not dropped (the verdict's rule,
/// [`verdict`]).
pub(super) fn held(r: &RunSummary) -> bool {
    r.slip_events == 0 && !r.dropped
}

/// A comparison of the controllers over all scenes (for `simulate --controller all`).
///
/// First a table with one row per controller (in order of first appearance): scenes held
/// of those not expected to slip (e.g. `5/6`), total slip events, total slip distance
/// \[mm\] (both totals over every scene, overloads included), mean of the runs' mean normal
/// force \[N\] and the largest peak force \[N\]. Then one line per scene (in order of first
/// appearance) naming the controllers that held it and the one(s) with the least mean
/// force. Wherever a baseline (a controller whose name does not start with `softgrip`)
/// holds a scene with a mean force no larger than a softgrip controller's, or holds a
/// scene a softgrip controller slipped in, a line says so explicitly.
pub fn comparison_table(runs: &[RunSummary]) -> String {
    use Align::{Left as L, Right as R};
    let controllers = first_appearance(runs.iter().map(|r| r.controller.as_str()));
    let scenes = first_appearance(runs.iter().map(|r| r.scene.as_str()));

    let headers = [
        "controller",
        "scenes held",
        "slip events",
        "slip distance [mm]",
        "mean of mean N [N]",
        "max peak N [N]",
    ];
    let align = [L, R, R, R, R, R];
    let rows: Vec<Vec<String>> = controllers
        .iter()
        .map(|&c| controller_row(c, runs))
        .collect();
    let mut out = render_table(&headers, &align, &rows);

    out.push('\n');
    for &scene in &scenes {
        out.push_str(&scene_lines(scene, runs));
    }
    out
}

/// The comparison table's row of the controller `c`.
fn controller_row(c: &str, runs: &[RunSummary]) -> Vec<String> {
    let mine: Vec<&RunSummary> = runs.iter().filter(|r| r.controller == c).collect();
    let eligible = mine.iter().filter(|r| !r.expected_slip).count();
    let held_n = mine.iter().filter(|r| !r.expected_slip && held(r)).count();
    let events: u64 = mine.iter().map(|r| r.slip_events).sum();
    let dist: f64 = mine.iter().map(|r| r.slip_distance_m).sum();
    let means: Vec<f64> = mine
        .iter()
        .map(|r| r.mean_normal_force_n)
        .filter(|v| v.is_finite())
        .collect();
    let mean_of_mean = if means.is_empty() {
        f64::NAN
    } else {
        means.iter().sum::<f64>() / means.len() as f64
    };
    let peak = mine
        .iter()
        .map(|r| r.peak_normal_force_n)
        .filter(|v| v.is_finite())
        .fold(f64::NAN, f64::max);
    vec![
        c.to_string(),
        format!("{held_n}/{eligible}"),
        events.to_string(),
        format!("{:.3}", dist * 1e3),
        format!("{mean_of_mean:.3}"),
        format!("{peak:.3}"),
    ]
}

/// The comparison's lines on `scene`: who held it, with the least mean force, and where
/// a baseline does as well as softgrip or better.
fn scene_lines(scene: &str, runs: &[RunSummary]) -> String {
    let here: Vec<&RunSummary> = runs.iter().filter(|r| r.scene == scene).collect();
    let holders: Vec<&RunSummary> = here.iter().copied().filter(|r| held(r)).collect();
    if here.iter().any(|r| r.expected_slip) {
        return overload_line(scene, &holders);
    }
    if holders.is_empty() {
        return format!("scene {scene}: no controller held it\n");
    }
    let least = holders
        .iter()
        .map(|r| r.mean_normal_force_n)
        .filter(|v| v.is_finite())
        .fold(f64::INFINITY, f64::min);
    let names: Vec<&str> = holders.iter().map(|r| r.controller.as_str()).collect();
    let best: Vec<&str> = holders
        .iter()
        .filter(|r| r.mean_normal_force_n == least)
        .map(|r| r.controller.as_str())
        .collect();
    let mut out = if best.is_empty() {
        format!(
            "scene {scene}: held by {}; no finite mean force\n",
            names.join(", ")
        )
    } else {
        format!(
            "scene {scene}: held by {}; least mean force: {} ({least:.3} N)\n",
            names.join(", "),
            best.join(", ")
        )
    };
    out.push_str(&baseline_lines(scene, &here, &holders));
    out
}

/// The comparison's line on the overload `scene`, held by `holders`.
fn overload_line(scene: &str, holders: &[&RunSummary]) -> String {
    if holders.is_empty() {
        return format!("scene {scene} (overload): every controller slipped, as expected\n");
    }
    let names: Vec<String> = holders
        .iter()
        .map(|r| format!("{} ({:.3} N mean)", r.controller, r.mean_normal_force_n))
        .collect();
    format!(
        "scene {scene} (overload): held by {} — unexpected for an overload\n",
        names.join(", ")
    )
}

/// A line for each baseline among `holders` that held `scene` where a softgrip run of
/// `here` slipped, or held it with no more mean force.
fn baseline_lines(scene: &str, here: &[&RunSummary], holders: &[&RunSummary]) -> String {
    let mut out = String::new();
    for s in here.iter().filter(|r| is_softgrip(&r.controller)) {
        for b in holders.iter().filter(|r| !is_softgrip(&r.controller)) {
            if !held(s) {
                out.push_str(&format!(
                    "scene {scene}: baseline \"{}\" held with {:.3} N mean, {} slipped \
                     ({} events) — the baseline does better here\n",
                    b.controller, b.mean_normal_force_n, s.controller, s.slip_events
                ));
            } else if b.mean_normal_force_n <= s.mean_normal_force_n {
                out.push_str(&format!(
                    "scene {scene}: baseline \"{}\" held with {:.3} N mean, {} {:.3} N \
                     — the baseline does as well here\n",
                    b.controller, b.mean_normal_force_n, s.controller, s.mean_normal_force_n
                ));
            }
        }
    }
    out
}
