//! The per-knob tables of `accuracy.md` and the notes under each.

use super::*;

pub(super) fn has_target(results: &Results) -> bool {
    results.target.as_ref().is_ok_and(|t| !t.costs.is_empty())
}

pub(super) fn knob_table(out: &mut String, results: &Results, rows: &[(String, Variant)]) {
    let target = has_target(results);
    out.push_str(
        "| setting | mode | pitch err | surface err rect | surface err disc | N err own rule \
         | N err rect | N err disc | under-ask | start-up [µs] | tick [ns] |",
    );
    if target {
        out.push_str(" M4F start-up [instr] | M4F tick median [instr] |");
    }
    out.push_str(" Pareto |\n");
    out.push_str("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    if target {
        out.push_str(" --- | --- |");
    }
    out.push_str(" --- |\n");
    for (label, v) in rows {
        let Some(m) = results.measured.get(v) else {
            continue;
        };
        let _ = write!(
            out,
            "| {label} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
            v.mode_name(),
            sci(m.pitch_err),
            sci(m.surface_err[0]),
            sci(m.surface_err[1]),
            sci(m.n_err_own),
            sci(m.n_err[0]),
            sci(m.n_err[1]),
            sci(m.under_ask),
            time(m.precompute_us),
            time(m.tick_ns),
        );
        if target {
            let c = results.target.as_ref().ok().and_then(|t| t.costs.get(v));
            match c {
                Some(c) => {
                    let _ = write!(out, " {:.0} | {:.0} |", c.startup, c.tick_median);
                }
                None => out.push_str(" n/a | n/a |"),
            }
        }
        let _ = writeln!(out, " {} |", front_of(results, v).mark());
    }
    out.push('\n');
}

pub(super) fn find(results: &Results, knob: Knob) -> &[(String, Variant)] {
    results
        .sections
        .iter()
        .find(|(k, _)| *k == knob)
        .map_or(&[], |(_, r)| r.as_slice())
}

pub(super) fn get(results: &Results, v: &Variant) -> Measured {
    results
        .measured
        .get(&v.normalised())
        .copied()
        .unwrap_or_default()
}

/// The rows of `knob` in one mode, with their measurements.
pub(super) fn mode_rows(results: &Results, knob: Knob, table: bool) -> Vec<(Variant, Measured)> {
    find(results, knob)
        .iter()
        .filter(|(_, v)| matches!(v.engine, Engine::Grid { table: t, .. } if t == table))
        .map(|(_, v)| (*v, get(results, v)))
        .collect()
}

/// The cheapest setting (by `key`) whose force error is close to the best setting's (the
/// tolerance is in the filter below).
pub(super) fn enough(
    rows: &[(Variant, Measured)],
    err: impl Fn(&Measured) -> f64,
    key: impl Fn(&Variant) -> u16,
) -> Option<&(Variant, Measured)> {
    let best = rows
        .iter()
        .map(|(_, m)| err(m))
        .fold(f64::INFINITY, f64::min);
    let mut ok: Vec<&(Variant, Measured)> = rows
        .iter()
        .filter(|(_, m)| err(m) <= (best * 1.1).max(best + 1e-7))
        .collect();
    ok.sort_by_key(|(v, _)| key(v));
    ok.first().copied()
}

/// The notes under `knob`'s table.
pub(super) fn section_notes(out: &mut String, results: &Results, knob: Knob) {
    match knob {
        Knob::Order => {
            out.push_str(
                "The quadrature order sets the pitch at every force node (both modes) and \
                 the sweeps of table mode. With an f32 start-up the pitch cannot get better \
                 than f32 rounding (about 6e-8 relative), whatever the order.\n\n",
            );
        }
        Knob::Samples => samples_note(out, results),
        Knob::Aspects => {
            aspects_note(out, results);
            aspect_grid_table(out, results);
        }
        Knob::Nodes => {
            out.push_str(
                "The tick interpolates the moment arm `R(N) = a(N)·pitch(l/a(N))` linearly \
                 between force nodes spaced in `ln N` (and table mode the aspect position); \
                 `R` is concave, so the interpolation understates it and overstates the \
                 force (conservative). The other interpolation schemes, the Eq. 10 ellipse \
                 and the chord polygon of a sweep, measured radially against the exact \
                 surface on their own (f64, order 28):\n\n",
            );
            representation_table(out, results);
        }
        Knob::Precision => {
            out.push_str(
                "On the Cortex-M4F (single-precision FPU) an f64 start-up is soft-float: see \
                 the target section. An f64 tick has no firmware; it is the host's.\n\n",
            );
        }
        Knob::Math => {
            out.push_str(
                "`micromath`'s square root is a bit trick with no refinement: it enters the \
                 demand through `|f_t| = sqrt(f_x² + f_y²)` and overestimates, so the force \
                 errs on the safe side. On the target `libm` here is the FPU's `VSQRT` \
                 (bit-identical).\n\n",
            );
        }
        Knob::Rule => {
            out.push_str(
                "\"Exact integration\" runs docs/model.md's rule with no grid: at every trial \
                 force it builds the model at `l/a(N)` and finds the exact surface's radius \
                 in the load's direction (bracketed Illinois searches over the sweep \
                 parameter and over `ln N`, tolerances 1e-9 and 1e-8, f64, order 28); one \
                 exact tick solves `N_slip`, then `N_req(s)` in `[N_slip, s·N_slip]`, then \
                 the utilisation, like the controller's tick. Its start-up is only building \
                 the model.\n\n",
            );
        }
    }
}

/// The note under the samples knob: the direction count, not the samples, is the floor.
fn samples_note(out: &mut String, results: &Results) {
    let floor = results
        .representation
        .iter()
        .find(|r| r.name.ends_with("directions of the exact surface"))
        .map_or(0.0, |r| r.errors.iter().copied().fold(0.0, f64::max));
    let _ = writeln!(
        out,
        "Table mode only. The controller stores each sweep as its inverse radius at \
         {} load directions, read off the sweep's chords; that polygon alone, taken \
         through the exact surface, is up to {} away from it radially (section 4's \
         representation table). Once the chords are finer than that, more samples \
         no longer lower the surface error: the floor is the direction count (a \
         constant of the core, `DIRECTIONS`), not the samples.\n",
        softgrip::controller::DIRECTIONS,
        sci(floor)
    );
}

/// The note under the aspects knob: the one error of table mode whose sign is not
/// guaranteed, and what the grid does not touch.
fn aspects_note(out: &mut String, results: &Results) {
    let rows = mode_rows(results, Knob::Aspects, true);
    let under: Vec<String> = rows
        .iter()
        .map(|(v, m)| format!("{} at {} aspects", sci(m.under_ask), v.aspects))
        .collect();
    let sign = if rows.iter().any(|(_, m)| m.under_ask > 0.0) {
        format!("as the under-ask column shows: {}", under.join(", "))
    } else {
        "though over this run's loads it never asked for less force than the exact \
         surface: the under-ask column is 0 at every grid size"
            .to_string()
    };
    let _ = writeln!(
        out,
        "Table mode on the rectangle (the disc has one shape). The controller \
         interpolates the stored surfaces linearly in `ln(l/a)` between the grid's \
         aspects. That interpolation is table mode's one error whose sign is not \
         guaranteed (the chords and the arm interpolation only overstate the \
         force), {sign}.\n"
    );
}

/// The core's own `AspectGrid` measured on its own, with its introduction.
fn aspect_grid_table(out: &mut String, results: &Results) {
    let d = Variant::default_mode(false);
    let _ = writeln!(
        out,
        "The controller's pitch is exact at every force node, so the aspect grid does \
         not touch it. The core's own `AspectGrid` instead interpolates the pitch \
         too, linearly in `ln(pitch)` against `ln(l/a)`; measured on its own (f64, \
         48 samples, order {}) over the rectangle's aspect range, at {} aspects \
         between its entries:\n",
        d.order,
        if results.budget.quick { 9 } else { 29 }
    );
    out.push_str(
        "| aspects | pitch err (log-log) | surface err | build [µs] |\n\
         | --- | --- | --- | --- |\n",
    );
    for r in &results.aspect_grid {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} |",
            r.count,
            sci(r.pitch_err),
            sci(r.surface_err),
            time(r.build_us)
        );
    }
    out.push('\n');
}

/// The surface representations' radial errors, one row each, a column per probe.
fn representation_table(out: &mut String, results: &Results) {
    let _ = write!(out, "| representation |");
    for p in &results.probes {
        let _ = write!(out, " {p} |");
    }
    out.push_str("\n| --- |");
    for _ in &results.probes {
        out.push_str(" --- |");
    }
    out.push('\n');
    for r in &results.representation {
        let _ = write!(out, "| {} |", r.name);
        for e in &r.errors {
            let _ = write!(out, " {} |", sci(*e));
        }
        out.push('\n');
    }
    out.push('\n');
}

pub(super) fn target_cost(results: &Results, v: &Variant) -> Option<super::target::TargetCost> {
    results
        .target
        .as_ref()
        .ok()
        .and_then(|t| t.costs.get(&v.normalised()).copied())
}

/// "the same", "N % faster", "N % slower": time `a` against time `b`, small differences
/// counting as the same.
pub(super) fn compare_times(a: f64, b: f64) -> String {
    let r = a / b.max(1e-12);
    if (r - 1.0).abs() < 0.05 {
        "the same within timing noise".into()
    } else if r < 1.0 {
        format!("{} faster in this run", pct(1.0 - r))
    } else {
        format!("{} slower in this run", pct(r - 1.0))
    }
}
