//! The other sections of `accuracy.md`: the target's figures, the brute force, the Pareto
//! front, the summary; and the whole document in order.

use super::*;

pub(super) fn target_section(out: &mut String, results: &Results) {
    out.push_str("## On the emulated target\n\n");
    match &results.target {
        Ok(t) if !t.costs.is_empty() => {
            out.push_str(
                "Measured in this run (`--target`): each configuration sent to the firmware \
                 in QEMU (netduinoplus2, `-icount shift=0`), start-up from `GetStats`, ticks \
                 over the 256 timing loads (64 with `--quick`), on the rectangle. \
                 Instructions, not cycles: QEMU models no pipeline or wait states. The \
                 per-knob tables above carry the same figures.\n\n",
            );
            out.push_str(
                "| configuration | start-up [instr] | tick median [instr] | tick max [instr] |\n\
                 | --- | --- | --- | --- |\n",
            );
            for (v, c) in &t.costs {
                let _ = writeln!(
                    out,
                    "| {} | {:.0} | {:.0} | {:.0} |",
                    v.describe(),
                    c.startup,
                    c.tick_median,
                    c.tick_max
                );
            }
            out.push('\n');
            for f in &t.firmware {
                let _ = writeln!(out, "- firmware {f}");
            }
            for s in &t.skipped {
                let _ = writeln!(out, "- not measured: {s}");
            }
            out.push('\n');
        }
        other => {
            let why = match other {
                Ok(_) => "no configuration could be measured".to_string(),
                Err(e) => e.clone(),
            };
            let _ = writeln!(
                out,
                "Instruction counts were {why}. To measure them: `bash scripts/firmware-setup.sh`, \
                 `bash scripts/firmware-build.sh default precompute-f64 fast-math`, then \
                 `cargo run --release -p host-sim -- accuracy --target` (adds the target's \
                 start-up and tick instructions to every table). The default firmware's own \
                 costs, over the worst-case trace of `host-sim/tests/firmware_costs.rs`, are the \
                 generated cost table of docs/firmware-costs.md.\n"
            );
        }
    }
}

pub(super) fn brute_section(out: &mut String, results: &Results) {
    let b = &results.brute;
    out.push_str("## Brute force against the core at matched accuracy\n\n");
    let _ = writeln!(
        out,
        "One limit-surface point of the rectangle `l = a`, `k = 2`, at `d_c/a` ∈ {{{}}}: \
         the core's fast path (`FlsModel::point`, tanh-sinh quadrature of a 1-D integral) \
         against the independent brute-force 2-D Gauss–Legendre integration of \
         `reference/src/lib.rs` (composite cells cut at every singular line, \
         `cells` per piece and axis). Errors are the worst over those points in `f̃` or \
         `m̃` against the core at order 128; times are per point, medians of repeated \
         runs.\n",
        super::brute::DS
            .iter()
            .map(|d| format!("{d}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(out, "{}\n", brute_headline(b));
    out.push_str(
        "Each brute-force setting against the cheapest core order at least as accurate:\n\n\
         | brute cells | brute err | brute [µs] | core order | core err | core [µs] | speed ratio |\n\
         | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for m in &b.matched {
        match m.core {
            Some(cm) => {
                let _ = writeln!(
                    out,
                    "| {} | {} | {} | {} | {} | {} | {:.0} |",
                    m.brute.setting,
                    sci(m.brute.err),
                    time(m.brute.us),
                    cm.setting,
                    sci(cm.err),
                    time(cm.us),
                    m.brute.us / cm.us
                );
            }
            None => {
                let _ = writeln!(
                    out,
                    "| {} | {} | {} | none | n/a | n/a | n/a |",
                    m.brute.setting,
                    sci(m.brute.err),
                    time(m.brute.us),
                );
            }
        }
    }
    out.push_str(
        "\nThe core at each order tried:\n\n| order | err | µs per point |\n| --- | --- | --- |\n",
    );
    for m in &b.core {
        let _ = writeln!(out, "| {} | {} | {} |", m.setting, sci(m.err), time(m.us));
    }
    out.push('\n');
}

pub(super) fn front_list(
    all: &[(Variant, Measured, Fronts)],
    results: &Results,
    cost: Cost,
) -> String {
    let mut on: Vec<(f64, String)> = all
        .iter()
        .filter(|(_, _, f)| f.on(cost))
        .filter_map(|(v, m, _)| {
            let c = cost.of(results, v, m)?;
            let c_text = match cost {
                Cost::HostTick => format!("{} ns", time(c)),
                Cost::HostStartup => format!("{} µs", time(c)),
                Cost::TargetTick | Cost::TargetStartup => format!("{c:.0} instructions"),
            };
            Some((
                c,
                format!("{} ({} in {c_text})", v.describe(), sci(m.error())),
            ))
        })
        .collect();
    on.sort_by(|a, b| a.0.total_cmp(&b.0));
    on.into_iter()
        .map(|(_, t)| t)
        .collect::<Vec<_>>()
        .join("; ")
}

/// The Pareto section: the front's definition, every configuration by host tick time
/// with the fronts it is on, and each front cheapest first.
pub(super) fn pareto_section(out: &mut String, results: &Results) {
    let target = has_target(results);
    let mut all = fronts(results);
    all.sort_by(|a, b| a.1.tick_ns.total_cmp(&b.1.tick_ns));
    out.push_str("## Pareto front\n\n");
    let _ = writeln!(
        out,
        "Every configuration measured above, by host tick time. The error is the commanded \
         force's worst relative error against the exact surface over both fingers. \
         **tick**: no other configuration is at least as accurate and at least as fast per \
         tick on the host (host times within {:.0} % count as equal: timing noise); \
         **start-up**: the same with the host start-up time, among the grid configurations \
         (the exact rule has no grid){}. Numbers in the plot are the `#` column.\n",
        100.0 * (TIME_TOLERANCE - 1.0),
        if target {
            "; **M4F tick** and **M4F start-up**: the same with the instruction counts on \
             the emulated target, which have no noise"
        } else {
            ""
        }
    );
    let _ = writeln!(out, "![error against time](accuracy.svg)\n");
    pareto_table(out, results, &all);
    front_lists(out, results, &all);
}

/// The Pareto table: every configuration of `all` (in order), its error and costs, and
/// the fronts it is on.
fn pareto_table(out: &mut String, results: &Results, all: &[(Variant, Measured, Fronts)]) {
    let target = has_target(results);
    out.push_str("| # | configuration | N err | under-ask | tick [ns] | start-up [µs] |");
    if target {
        out.push_str(" M4F tick [instr] | M4F start-up [instr] |");
    }
    out.push_str(" front |\n| --- | --- | --- | --- | --- | --- |");
    if target {
        out.push_str(" --- | --- |");
    }
    out.push_str(" --- |\n");
    for (i, (v, m, f)) in all.iter().enumerate() {
        let name = if f.any() {
            format!("**{}**", v.describe())
        } else {
            v.describe()
        };
        let _ = write!(
            out,
            "| {} | {name} | {} | {} | {} | {} |",
            i + 1,
            sci(m.error()),
            sci(m.under_ask),
            time(m.tick_ns),
            time(m.precompute_us),
        );
        if target {
            match target_cost(results, v) {
                Some(c) => {
                    let _ = write!(out, " {:.0} | {:.0} |", c.tick_median, c.startup);
                }
                None => out.push_str(" n/a | n/a |"),
            }
        }
        let _ = writeln!(out, " {} |", f.mark());
    }
    out.push('\n');
}

/// The tick fronts of `all`, cheapest first (the M4F's when measured), and a note when a
/// micromath configuration is on one.
fn front_lists(out: &mut String, results: &Results, all: &[(Variant, Measured, Fronts)]) {
    let _ = writeln!(
        out,
        "The host tick front, cheapest first: {}.\n",
        front_list(all, results, Cost::HostTick)
    );
    if has_target(results) {
        let _ = writeln!(
            out,
            "The M4F tick front, cheapest first: {}.\n",
            front_list(all, results, Cost::TargetTick)
        );
    }
    let micro_on_front = all.iter().any(|(v, _, f)| {
        (f.on(Cost::HostTick) || f.on(Cost::TargetTick))
            && matches!(
                v.engine,
                Engine::Grid {
                    math: super::knobs::MathKind::Micromath,
                    ..
                }
            )
    });
    if micro_on_front {
        out.push_str(
            "A micromath configuration on a front is there by its cost, not its accuracy: \
             its square root overestimates, which raises the force (the safe side) and adds \
             to the error.\n\n",
        );
    }
}

/// The whole `accuracy.md`.
pub fn markdown(results: &Results) -> String {
    let mut out = String::new();
    out.push_str("# What accuracy costs in time\n\n");
    header_lines(&mut out, results);
    how_to_read(&mut out, results);
    summary_section(&mut out, results);
    for (i, (knob, rows)) in results.sections.iter().enumerate() {
        let _ = writeln!(out, "## {}. {}\n", i + 1, knob.title());
        knob_table(&mut out, results, rows);
        section_notes(&mut out, results, *knob);
    }
    pareto_section(&mut out, results);
    out.push_str("## The defaults, and why\n\n");
    defaults_text(&mut out, results);
    brute_section(&mut out, results);
    target_section(&mut out, results);
    out.push_str(
        "## Benchmarks\n\n\
         Criterion benchmarks of the same costs: `cargo bench --bench fls` (128-point sweeps, \
         one point per shape, the brute-force point at 6 and 32 cells) and `cargo bench \
         --bench tick` (ticks per mode, precision and backend; a smooth 1 kHz load; the \
         start-up precomputation). The tests assert no timings.\n",
    );
    out
}

/// Where, when and how the report was made: machine, date, commit, toolchain, command
/// and the run's size.
fn header_lines(out: &mut String, results: &Results) {
    let h = &results.header;
    let b = &results.budget;
    let _ = writeln!(
        out,
        "- Machine: {}\n- Date: {}\n- Commit: {}\n- Toolchain: {}\n- Command: `{}`\n- Run: {} \
         ({:.1} s of measurements{})\n",
        h.machine,
        h.date,
        h.commit.as_deref().unwrap_or("unknown (no git)"),
        h.rustc.as_deref().unwrap_or("unknown"),
        h.command,
        if b.quick { "quick (`--quick`)" } else { "full" },
        results.elapsed_s,
        if cfg!(debug_assertions) {
            "; a debug build: the times mean nothing"
        } else {
            ""
        }
    );
}

/// "How to read the tables": the two fingers and every column, with the run's sizes.
fn how_to_read(out: &mut String, results: &Results) {
    let b = &results.budget;
    let [rect, disc] = &results.fingers;
    let _ = writeln!(
        out,
        "## How to read the tables\n\n\
         Two fingers: the **rectangle** is `ControllerConfig::default()` (hemicylinder, \
         `k = 2`, `a = 2.5 mm·N^½`, `l = 10 mm`, so `l/a` runs from 8.9 down to 0.89 over \
         0.2–20 N; `μ = 0.8`, `s = {}`); the **disc** is the same with a hemispherical tip \
         and Hertzian growth `a = 2.5 mm·N^⅓` (the tick asks for its moment times \
         `DISC_TORSION_SAFETY_FACTOR`, and its errors are against the exact answer to \
         that). Every configuration differs from the \
         project's defaults (order 28, 48 samples, 8 aspects, 48 force nodes, f32 start-up, \
         f32 tick, `libm`) in the one setting its row names.\n\n\
         - **pitch err**: the moment arm `a·pitch` the start-up stores at each force node \
           against the converged one (quadrature order 128, f64), worst relative error over \
           the nodes of both fingers.\n\
         - **surface err**: the largest radial error of the surface the tick tests the load \
           against (the Eq. 10 ellipse or the stored table, with the arm and aspect \
           interpolation), relative to the exact surface's radius, over {} forces × {} \
           directions per finger (`Controller::utilisation` against the exact utilisation). \
           For ellipse mode this is mostly the ellipse's own gap ({} on the rectangle, {} \
           on the disc, relative to the exact radius; `host-sim fls` reports the same gap \
           relative to the ellipse's radius, a little smaller).\n\
         - **N err**: the commanded force `N_req(s)` of a real tick against the exact f64 \
           answer, worst relative error over {} loads per finger ({} magnitudes, answers \
           from 0.4 to about 17 N, × {} directions from pure force to pure torsion). \
           **own rule**: against the configuration's own rule evaluated exactly (ellipse \
           mode: the ellipse with the exact pitch at `l/a(N)`; table and exact: the exact \
           surface), worst of both fingers, which isolates the numerical error. **rect**, \
           **disc**: against the exact surface. **under-ask**: the largest amount by which \
           the force falls short of the exact surface's answer (the unsafe side).\n\
         - The exact answers: bisection-safe Illinois searches in f64 at quadrature order \
           128, on the surface's radius (over the sweep parameter) and on `ln N`, to within \
           f64 rounding.\n\
         - **start-up**: host time of `Controller::new_precomputed_in`; **tick**: host time \
           of one `Controller::tick` over the 256 unrelated loads of `benches/tick.rs` ({} \
           ticks a run); both on the rectangle, in this run, medians of {} runs taken \
           round-robin over all configurations (so that a burst of load on the shared \
           machine does not bias one configuration). Timings of identical code still differ \
           by a few per cent.\n\
         - **Pareto**: see the Pareto section.\n",
        softgrip::controller::ControllerConfig::DEFAULT.safety,
        b.grid_forces,
        b.grid_directions,
        pct(rect.ellipse_gap),
        pct(disc.ellipse_gap),
        rect.loads.len(),
        b.load_forces,
        b.load_directions,
        b.tick_passes * 256,
        b.rounds,
    );
}

pub(super) fn summary_section(out: &mut String, results: &Results) {
    let me = get(results, &Variant::default_mode(false));
    let mt = get(results, &Variant::default_mode(true));
    out.push_str("## Summary\n\n");
    let _ = writeln!(
        out,
        "| default | pitch err | surface err (worst) | N err own rule | N err vs exact surface | under-ask | start-up [µs] | tick [ns] |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- |\n\
         | ellipse | {} | {} | {} | {} | {} | {} | {} |\n\
         | table | {} | {} | {} | {} | {} | {} | {} |\n",
        sci(me.pitch_err),
        sci(me.surface_err[0].max(me.surface_err[1])),
        sci(me.n_err_own),
        sci(me.error()),
        sci(me.under_ask),
        time(me.precompute_us),
        time(me.tick_ns),
        sci(mt.pitch_err),
        sci(mt.surface_err[0].max(mt.surface_err[1])),
        sci(mt.n_err_own),
        sci(mt.error()),
        sci(mt.under_ask),
        time(mt.precompute_us),
        time(mt.tick_ns),
    );
    let _ = writeln!(out, "{}\n", brute_headline(&results.brute));
}
