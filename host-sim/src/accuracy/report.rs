//! The report: `accuracy.md` (tables, the Pareto front, the defaults, the brute-force
//! ratio, the target's figures) and `accuracy.svg` (error against time, log-log, the
//! Pareto points highlighted). The plot uses `plotters`' SVG backend without any font
//! feature: text is written as SVG `<text>` elements.

use super::knobs::{Engine, Knob, Measured, Variant};
use super::Results;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// Tick or start-up times within this factor of each other count as equal when ranking
/// (timing noise on a shared machine is a few per cent).
pub const TIME_TOLERANCE: f64 = 1.03;

/// An error or a small number, as `2.8e-5`.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// A time with three significant digits.
pub fn time(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

/// A per-cent figure with two significant digits.
fn pct(x: f64) -> String {
    let p = 100.0 * x;
    if p >= 10.0 {
        format!("{p:.0} %")
    } else if p >= 1.0 {
        format!("{p:.1} %")
    } else {
        format!("{p:.2} %")
    }
}

/// A relative amount: per cent when at least 0.1 %, else scientific.
fn share(x: f64) -> String {
    if x >= 1e-3 {
        pct(x)
    } else {
        format!("{} (relative)", sci(x))
    }
}

/// A cost a configuration can be ranked by.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cost {
    /// Host time per tick.
    HostTick,
    /// Host time of the start-up (grid configurations only).
    HostStartup,
    /// Instructions per tick on the emulated M4F (median; `--target`).
    TargetTick,
    /// Instructions of the start-up on the emulated M4F (`--target`).
    TargetStartup,
}

impl Cost {
    /// Every cost, in the order of [`Fronts`].
    pub const ALL: [Cost; 4] = [
        Cost::HostTick,
        Cost::HostStartup,
        Cost::TargetTick,
        Cost::TargetStartup,
    ];

    /// The name of its front.
    pub fn name(self) -> &'static str {
        match self {
            Cost::HostTick => "tick",
            Cost::HostStartup => "start-up",
            Cost::TargetTick => "M4F tick",
            Cost::TargetStartup => "M4F start-up",
        }
    }

    /// The axis label of its plot.
    fn axis(self) -> &'static str {
        match self {
            Cost::HostTick => "host tick [ns]",
            Cost::HostStartup => "host start-up [µs]",
            Cost::TargetTick => "M4F tick, median [instructions]",
            Cost::TargetStartup => "M4F start-up [instructions]",
        }
    }

    /// The configuration's cost, if it has one.
    pub fn of(self, results: &Results, v: &Variant, m: &Measured) -> Option<f64> {
        let grid = !matches!(v.engine, Engine::Exact);
        match self {
            Cost::HostTick => Some(m.tick_ns),
            Cost::HostStartup => grid.then_some(m.precompute_us),
            Cost::TargetTick => target_cost(results, v).map(|c| c.tick_median),
            Cost::TargetStartup => target_cost(results, v).map(|c| c.startup),
        }
    }

    /// Costs within this factor count as equal: host times are noisy, instruction counts
    /// are not.
    fn tolerance(self) -> f64 {
        match self {
            Cost::HostTick | Cost::HostStartup => TIME_TOLERANCE,
            Cost::TargetTick | Cost::TargetStartup => 1.0,
        }
    }
}

/// Which fronts a configuration is on, in the order of [`Cost::ALL`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Fronts(pub [bool; 4]);

impl Fronts {
    /// Whether it is on the front of `cost`.
    pub fn on(self, cost: Cost) -> bool {
        Cost::ALL
            .iter()
            .position(|&c| c == cost)
            .is_some_and(|i| self.0[i])
    }

    fn any(self) -> bool {
        self.0.iter().any(|&b| b)
    }

    fn mark(self) -> String {
        let names: Vec<&str> = Cost::ALL
            .iter()
            .filter(|&&c| self.on(c))
            .map(|c| c.name())
            .collect();
        if names.is_empty() {
            "—".into()
        } else {
            names.join(" + ")
        }
    }
}

/// Whether `(e1, c1)` dominates `(e0, c0)`: no worse in both, better in one, costs within
/// `tol` of each other counting as equal.
fn dominates(e1: f64, c1: f64, e0: f64, c0: f64, tol: f64) -> bool {
    (e1 < e0 && c1 <= c0 * tol) || (e1 <= e0 && c1 * tol < c0)
}

/// The Pareto fronts over every measured configuration: for each [`Cost`], the
/// configurations that have it and that no other is at least as accurate and as cheap as.
pub fn fronts(results: &Results) -> Vec<(Variant, Measured, Fronts)> {
    let all: Vec<(Variant, Measured)> = results.measured.iter().map(|(v, m)| (*v, *m)).collect();
    all.iter()
        .map(|&(v, m)| {
            let mut f = Fronts::default();
            for (i, cost) in Cost::ALL.iter().enumerate() {
                let Some(c0) = cost.of(results, &v, &m) else {
                    continue;
                };
                f.0[i] = !all.iter().any(|(ov, o)| {
                    cost.of(results, ov, o)
                        .is_some_and(|c1| dominates(o.error(), c1, m.error(), c0, cost.tolerance()))
                });
            }
            (v, m, f)
        })
        .collect()
}

fn front_of(results: &Results, v: &Variant) -> Fronts {
    fronts(results)
        .into_iter()
        .find(|(w, _, _)| w == v)
        .map_or(Fronts::default(), |(_, _, f)| f)
}

fn has_target(results: &Results) -> bool {
    results.target.as_ref().is_ok_and(|t| !t.costs.is_empty())
}

fn knob_table(out: &mut String, results: &Results, rows: &[(String, Variant)]) {
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

fn find(results: &Results, knob: Knob) -> &[(String, Variant)] {
    results
        .sections
        .iter()
        .find(|(k, _)| *k == knob)
        .map_or(&[], |(_, r)| r.as_slice())
}

fn get(results: &Results, v: &Variant) -> Measured {
    results
        .measured
        .get(&v.normalised())
        .copied()
        .unwrap_or_default()
}

/// The rows of `knob` in one mode, with their measurements.
fn mode_rows(results: &Results, knob: Knob, table: bool) -> Vec<(Variant, Measured)> {
    find(results, knob)
        .iter()
        .filter(|(_, v)| matches!(v.engine, Engine::Grid { table: t, .. } if t == table))
        .map(|(_, v)| (*v, get(results, v)))
        .collect()
}

/// The cheapest setting (by `key`) whose force error is within 10 % (or 1e-7) of the
/// best setting's.
fn enough(
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

fn section_notes(out: &mut String, results: &Results, knob: Knob) {
    let d = Variant::default_mode(false);
    match knob {
        Knob::Order => {
            out.push_str(
                "The quadrature order sets the pitch at every force node (both modes) and \
                 the sweeps of table mode. With an f32 start-up the pitch cannot get better \
                 than f32 rounding (about 6e-8 relative), whatever the order.\n\n",
            );
        }
        Knob::Samples => {
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
        Knob::Aspects => {
            let under: Vec<String> = mode_rows(results, Knob::Aspects, true)
                .iter()
                .map(|(v, m)| format!("{} at {} aspects", sci(m.under_ask), v.aspects))
                .collect();
            let _ = writeln!(
                out,
                "Table mode on the rectangle (the disc has one shape). The controller \
                 interpolates the stored surfaces linearly in `ln(l/a)` between the grid's \
                 aspects. That interpolation is table mode's one unsafe error (the chords and \
                 the arm interpolation only overstate the force), as the under-ask column \
                 shows: {}.\n",
                under.join(", ")
            );
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
        Knob::Nodes => {
            out.push_str(
                "The tick interpolates the moment arm `R(N) = a(N)·pitch(l/a(N))` linearly \
                 between force nodes spaced in `ln N` (and table mode the aspect position); \
                 `R` is concave, so the interpolation understates it and overstates the \
                 force (conservative). The other interpolation schemes, the Eq. 10 ellipse \
                 and the chord polygon of a sweep, measured radially against the exact \
                 surface on their own (f64, order 28):\n\n",
            );
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

fn target_cost(results: &Results, v: &Variant) -> Option<super::target::TargetCost> {
    results
        .target
        .as_ref()
        .ok()
        .and_then(|t| t.costs.get(&v.normalised()).copied())
}

/// "the same", "12 % faster", "12 % slower": time `a` against time `b`, differences under
/// 5 % counting as the same.
fn compare_times(a: f64, b: f64) -> String {
    let r = a / b.max(1e-12);
    if (r - 1.0).abs() < 0.05 {
        "the same within timing noise".into()
    } else if r < 1.0 {
        format!("{} faster in this run", pct(1.0 - r))
    } else {
        format!("{} slower in this run", pct(r - 1.0))
    }
}

fn defaults_text(out: &mut String, results: &Results) {
    let def_e = Variant::default_mode(false).normalised();
    let def_t = Variant::default_mode(true).normalised();
    let me = get(results, &def_e);
    let mt = get(results, &def_t);
    let exact = results
        .measured
        .iter()
        .find(|(v, _)| matches!(v.engine, Engine::Exact))
        .map(|(_, m)| *m);

    // Order.
    // Orders that keep the pitch at the f32 floor (the default's level, or 1e-6).
    let pitch_floor = mt.pitch_err.max(1e-6);
    let orders: Vec<(Variant, Measured)> = mode_rows(results, Knob::Order, true)
        .into_iter()
        .filter(|(_, m)| m.pitch_err <= pitch_floor)
        .collect();
    if let Some((vo, mo)) = enough(&orders, Measured::error, |v| v.order) {
        let verdict = if vo.order < def_t.order {
            format!(
                "the numbers would allow order {} for the f32 firmware ({} less start-up in \
                 table mode); 28 stays the default because the same core serves f64 on the \
                 host, where order 28 is what keeps a point within 5e-11 of the converged \
                 integral (README), and because the start-up runs once",
                vo.order,
                pct(1.0 - mo.precompute_us / mt.precompute_us.max(1e-9))
            )
        } else {
            "the default is the cheapest order at that level".to_string()
        };
        let _ = writeln!(
            out,
            "- **Quadrature order 28.** Pitch error {} (f32 start-up), force error {} in \
             table mode. Order {} is the cheapest that keeps the pitch within {} (pitch \
             error {}) and the commanded force within 10 % of the best order tried ({} \
             against {}), at {} µs of table start-up against {} µs: {verdict}.",
            sci(mt.pitch_err),
            sci(mt.error()),
            vo.order,
            sci(pitch_floor),
            sci(mo.pitch_err),
            sci(mo.error()),
            sci(mt.error()),
            time(mo.precompute_us),
            time(mt.precompute_us),
        );
    }
    // Samples.
    let samples = mode_rows(results, Knob::Samples, true);
    if let Some((vs, ms)) = enough(&samples, Measured::error, |v| v.samples) {
        let verdict = if vs.samples < def_t.samples {
            format!(
                "{} samples would do as well here; 48 keeps a margin for other fingers",
                vs.samples
            )
        } else if vs.samples > def_t.samples {
            format!(
                "more samples still help ({} reach {}), at {} µs of start-up: a candidate \
                 if the start-up budget allows",
                vs.samples,
                sci(ms.error()),
                time(ms.precompute_us)
            )
        } else {
            "48 is the cheapest setting at the best level".to_string()
        };
        let _ = writeln!(
            out,
            "- **48 centre-of-rotation samples.** Table force error {} ({} µs start-up); \
             {verdict}. Past the chords' error the controller's {}-direction storage is the \
             floor (section 2): more directions, not more samples, would lower it.",
            sci(mt.error()),
            time(mt.precompute_us),
            softgrip::controller::DIRECTIONS,
        );
    }
    // Aspects.
    let aspects = mode_rows(results, Knob::Aspects, true);
    if let Some((va, ma)) = enough(&aspects, Measured::error, |v| v.aspects) {
        let verdict = if va.aspects < def_t.aspects {
            format!(
                "{} aspects are as good on this finger ({}); 8 covers fingers whose aspect \
                 range is wider",
                va.aspects,
                sci(ma.error())
            )
        } else if va.aspects > def_t.aspects {
            format!(
                "{} aspects would cut the error to {} for {} µs of start-up",
                va.aspects,
                sci(ma.error()),
                time(ma.precompute_us)
            )
        } else {
            "8 is the cheapest setting at the best level".to_string()
        };
        let _ = writeln!(
            out,
            "- **8 aspects.** Table force error {}; {verdict}.",
            sci(mt.error())
        );
    }
    // Nodes.
    let nodes = mode_rows(results, Knob::Nodes, false);
    if let Some((vn, mn)) = enough(&nodes, |m| m.n_err_own, |v| v.nodes) {
        let verdict = if vn.nodes < def_e.nodes {
            format!(
                "{} nodes reach the same level ({}), so 48 buys margin, not accuracy",
                vn.nodes,
                sci(mn.n_err_own)
            )
        } else if vn.nodes > def_e.nodes {
            format!(
                "{} nodes would still cut it to {} (the interpolation error falls like \
                 1/nodes²), for a tick of {} ns against {} ns ({}) and {} µs of start-up \
                 against {} µs; the gain is conservative slack, not safety",
                vn.nodes,
                sci(mn.n_err_own),
                time(mn.tick_ns),
                time(me.tick_ns),
                compare_times(mn.tick_ns, me.tick_ns),
                time(mn.precompute_us),
                time(me.precompute_us)
            )
        } else {
            "48 is the cheapest count at that level".to_string()
        };
        // On the target the node count moves the tick: the node search and the Illinois
        // iterations trade against each other.
        let on_target: Vec<(Variant, Measured, f64)> = nodes
            .iter()
            .filter_map(|(v, m)| Some((*v, *m, target_cost(results, v)?.tick_median)))
            .collect();
        let target_text = match (
            on_target.iter().find(|(v, _, _)| v.nodes == def_e.nodes),
            on_target.iter().min_by(|a, b| a.2.total_cmp(&b.2)),
        ) {
            (Some(d), Some(best)) if best.0.nodes != def_e.nodes => {
                let advice = if best.1.n_err_own <= 1e-3 {
                    format!(
                        "**the numbers suggest {} nodes** where the ellipse tick budget is \
                         tight",
                        best.0.nodes
                    )
                } else {
                    "a cheaper tick bought with that much more (safe-side) force".to_string()
                };
                format!(
                    " On the M4F the node count moves the tick: {:.0} instructions median at \
                     48 nodes (ellipse budget 2 000), {:.0} at {} nodes, the cheapest, which \
                     leave {} against the own rule (conservative): {advice}.",
                    d.2,
                    best.2,
                    best.0.nodes,
                    sci(best.1.n_err_own),
                )
            }
            (Some(d), Some(_)) => format!(
                " On the M4F 48 nodes give the cheapest ellipse tick ({:.0} instructions \
                 median).",
                d.2
            ),
            _ => String::new(),
        };
        let _ = writeln!(
            out,
            "- **48 force nodes.** Ellipse-mode force error against its own rule {} (the \
             arm interpolation is conservative); {verdict}.{target_text}",
            sci(me.n_err_own),
        );
    }
    // Precision.
    let f64pre_v = Variant {
        engine: Engine::Grid {
            table: true,
            precision: super::knobs::Precision::F64Precompute,
            math: super::knobs::MathKind::Libm,
        },
        ..def_t
    };
    let f64pre = get(results, &f64pre_v);
    let target_startup = match (
        target_cost(results, &def_t),
        target_cost(results, &f64pre_v),
    ) {
        (Some(a), Some(b)) => format!(
            "{:.1} M against {:.1} M instructions in this run ({:.0}×)",
            b.startup / 1e6,
            a.startup / 1e6,
            b.startup / a.startup.max(1.0)
        ),
        _ => "about 20× the instructions and twice the stack (README)".to_string(),
    };
    let _ = writeln!(
        out,
        "- **f32 precomputation.** Table force error {} with an f32 start-up against {} \
         with f64, and the pitch error {} against {}: the grid's own errors dominate both. \
         On the host the f64 start-up takes {} µs against {} µs; on the M4F's \
         single-precision FPU it is soft-float: {target_startup}, for nothing visible in \
         the commanded force.",
        sci(mt.error()),
        sci(f64pre.error()),
        sci(mt.pitch_err),
        sci(f64pre.pitch_err),
        time(f64pre.precompute_us),
        time(mt.precompute_us),
    );
    // Math.
    let micro_v = Variant {
        engine: Engine::Grid {
            table: false,
            precision: super::knobs::Precision::F32,
            math: super::knobs::MathKind::Micromath,
        },
        ..def_e
    };
    let micro = get(results, &micro_v);
    let host = compare_times(micro.tick_ns, me.tick_ns);
    let target_math = match (target_cost(results, &def_e), target_cost(results, &micro_v)) {
        (Some(a), Some(b)) => format!(
            "on the M4F {:.0} against {:.0} instructions median in this run",
            b.tick_median, a.tick_median
        ),
        _ => "on the M4F 2 016 against 1 966 instructions median (README)".to_string(),
    };
    let _ = writeln!(
        out,
        "- **libm (FPU) square root.** micromath raises the ellipse-mode force by up to {} \
         against its own rule (libm: {}), for a tick of {} ns against {} ns on the host \
         ({host}) and {target_math}: the FPU's `VSQRT` is one instruction, so there is \
         nothing to win.",
        sci(micro.n_err_own),
        sci(me.n_err_own),
        time(micro.tick_ns),
        time(me.tick_ns),
    );
    // Mode.
    let exact_text = exact.map_or(String::new(), |x| {
        format!(
            " Exact integration per tick gets {} but costs {} µs a tick, {:.0}× a table \
             tick: not an option at 1 kHz on a microcontroller.",
            sci(x.error()),
            time(x.tick_ns / 1000.0),
            x.tick_ns / mt.tick_ns.max(1e-9)
        )
    });
    let fe = front_of(results, &def_e);
    let ft = front_of(results, &def_t);
    let target_ticks = match (target_cost(results, &def_e), target_cost(results, &def_t)) {
        (Some(e), Some(t)) => format!(
            "measured in this run: {:.0} against {:.0} instructions median on the M4F",
            t.tick_median, e.tick_median
        ),
        _ => "README: 3 688 against 1 960 instructions median on the M4F".to_string(),
    };
    let _ = writeln!(
        out,
        "- **Ellipse mode by default.** It is the cheapest tick ({} ns; table {} ns, {:.1}×) \
         but the least accurate rule: against the exact surface it asks for up to {} less \
         force than needed (worst under-ask over both fingers), table mode for {}. The \
         safety factor 1.3 covers the ellipse's gap, but for a load near the diagonal the \
         effective margin is only about {:.2}. The default ellipse configuration is {} the \
         tick front and the default table configuration is {} it (configurations running \
         the same tick code tie within timing noise, so which of them lands on the front is \
         partly chance).{exact_text} **The numbers favour table mode** wherever its tick \
         fits the budget ({target_ticks}; budgets 5 000 and 2 000); ellipse mode stays the \
         default as the cheaper, simpler rule whose error is one known number that the \
         safety factor must cover.",
        time(me.tick_ns),
        time(mt.tick_ns),
        mt.tick_ns / me.tick_ns.max(1e-9),
        share(me.under_ask),
        share(mt.under_ask),
        1.3 * (1.0 - me.under_ask),
        if fe.on(Cost::HostTick) {
            "on"
        } else {
            "not on"
        },
        if ft.on(Cost::HostTick) {
            "on"
        } else {
            "not on"
        },
    );
    out.push('\n');
}

fn target_section(out: &mut String, results: &Results) {
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
                 start-up and tick instructions to every table). The figures below are **not \
                 from this run**: they are the README's firmware section (commit 4061240, \
                 `cargo test --release -p host-sim --test qemu_link -- --nocapture`, 300 \
                 ticks per mode, default configuration, and `bash scripts/target-costs.sh`, \
                 all seven scenes).\n"
            );
            out.push_str(
                "| variant | tick median/max, ellipse | tick median/max, table | table start-up |\n\
                 | --- | --- | --- | --- |\n\
                 | default (FPU sqrt, f32 precomputation), qemu_link | 1 960 / 2 341 | 3 688 / 5 319 | 8.40 M (ellipse 1.78 M) |\n\
                 | default, scenes | 1 966 / 2 382 | 3 621 / 4 716 | 2.23 M |\n\
                 | `soft-sqrt` (libm's software sqrt) | 2 075 / 2 491 | 3 679 / 4 774 | 2.23 M |\n\
                 | `fast-math` (micromath sqrt) | 2 016 / 2 397 | 3 626 / 4 922 | 2.23 M |\n\
                 | `precompute-f64` | 2 002 / 2 342 | 3 621 / 4 917 | 46.3 M |\n\n",
            );
        }
    }
}

fn brute_section(out: &mut String, results: &Results) {
    let b = &results.brute;
    out.push_str("## Brute force against the core at matched accuracy\n\n");
    let _ = writeln!(
        out,
        "One limit-surface point of the rectangle `l = a`, `k = 2`, at `d_c/a` ∈ {{{}}}: \
         the core's fast path (`FlsModel::point`, tanh-sinh quadrature of a 1-D integral) \
         against the independent brute-force 2-D Gauss–Legendre integration of \
         `tests/common/brute_force.rs` (composite cells cut at every singular line, \
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

fn front_list(all: &[(Variant, Measured, Fronts)], results: &Results, cost: Cost) -> String {
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

fn pareto_section(out: &mut String, results: &Results) {
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
    let _ = writeln!(
        out,
        "The host tick front, cheapest first: {}.\n",
        front_list(&all, results, Cost::HostTick)
    );
    if target {
        let _ = writeln!(
            out,
            "The M4F tick front, cheapest first: {}.\n",
            front_list(&all, results, Cost::TargetTick)
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
            "A micromath configuration makes a front only because its square root \
             overestimates: that raises the force and so happens to offset part of the \
             ellipse's under-ask. It is an error of the opposite sign, not accuracy.\n\n",
        );
    }
}

/// The whole `accuracy.md`.
pub fn markdown(results: &Results) -> String {
    let h = &results.header;
    let b = &results.budget;
    let mut out = String::new();
    out.push_str("# What accuracy costs in time\n\n");
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
    let [rect, disc] = &results.fingers;
    let _ = writeln!(
        out,
        "## How to read the tables\n\n\
         Two fingers: the **rectangle** is `ControllerConfig::default()` (hemicylinder, \
         `k = 2`, `a = 2.5 mm·N^½`, `l = 10 mm`, so `l/a` runs from 8.9 down to 0.89 over \
         0.2–20 N; `μ = 0.8`, `s = 1.3`); the **disc** is the same with a hemispherical tip \
         and Hertzian growth `a = 2.5 mm·N^⅓`. Every configuration differs from the \
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

fn summary_section(out: &mut String, results: &Results) {
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

/// One sentence on the core against the brute force.
pub fn brute_headline(b: &super::brute::BruteReport) -> String {
    let mut s = String::from("Core against brute force at matched accuracy: ");
    if let Some((bm, cm, r)) = b.best_matched() {
        let _ = write!(
            s,
            "**speed ratio {r:.0}×** per point at the brute force's best accuracy tried \
             ({} cells, {}: {} µs; the core needs order {} for {}: {} µs). ",
            bm.setting,
            sci(bm.err),
            time(bm.us),
            cm.setting,
            sci(cm.err),
            time(cm.us)
        );
    }
    if b.reached {
        let _ = write!(
            s,
            "At the default order ({}) the ratio is {:.0}× ({} cells).",
            sci(b.core_default.err),
            b.ratio(),
            b.brute_at_default.setting
        );
    } else {
        let _ = write!(
            s,
            "At the default order the core is within {}, which no brute-force setting tried \
             reaches: there the ratio is more than {:.0}×.",
            sci(b.core_default.err),
            b.ratio()
        );
    }
    s
}

/// The few lines `host-sim accuracy` prints.
pub fn summary(results: &Results) -> String {
    let me = get(results, &Variant::default_mode(false));
    let mt = get(results, &Variant::default_mode(true));
    let mut s = String::new();
    for (name, m) in [("ellipse", me), ("table", mt)] {
        let _ = writeln!(
            s,
            "default {name}: pitch err {}, N err {} own rule / {} vs exact surface \
             (under-ask {}), start-up {} µs, tick {} ns",
            sci(m.pitch_err),
            sci(m.n_err_own),
            sci(m.error()),
            sci(m.under_ask),
            time(m.precompute_us),
            time(m.tick_ns)
        );
    }
    let front: Vec<String> = fronts(results)
        .into_iter()
        .filter(|(_, _, f)| f.on(Cost::HostTick))
        .map(|(v, _, _)| v.describe())
        .collect();
    let _ = writeln!(s, "tick Pareto front: {}", front.join("; "));
    let _ = writeln!(s, "{}", brute_headline(&results.brute).replace("**", ""));
    s
}

fn plot_err(e: f64) -> f64 {
    e.max(1e-16)
}

/// Draws `accuracy.svg`: the force error against each [`Cost`] the run measured
/// (host tick and start-up; with `--target` also the M4F's), log-log, one panel each, the
/// Pareto points circled, joined and numbered as in the Pareto table.
pub fn plot(path: &Path, results: &Results) -> Result<(), String> {
    let mut all = fronts(results);
    all.sort_by(|a, b| a.1.tick_ns.total_cmp(&b.1.tick_ns));
    let costs: Vec<Cost> = if has_target(results) {
        Cost::ALL.to_vec()
    } else {
        vec![Cost::HostTick, Cost::HostStartup]
    };
    let rows = costs.len().div_ceil(2) as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1400, 620 * rows)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let areas = root.split_evenly((rows as usize, 2));
        for (area, cost) in areas.iter().zip(costs) {
            panel(area, results, &all, cost)?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    std::fs::write(path, svg).map_err(|e| format!("{}: {e}", path.display()))
}

/// The x range of a log-scale panel: the data with a margin, widened to whole decades
/// when it spans less than one (a log axis inside one decade gets no labels).
fn x_range(xmin: f64, xmax: f64) -> std::ops::Range<f64> {
    let (lo, hi) = (xmin / 1.6, xmax * 1.6);
    if hi / lo < 10.0 {
        10f64.powf(lo.log10().floor())..10f64.powf(hi.log10().ceil())
    } else {
        lo..hi
    }
}

fn panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    results: &Results,
    all: &[(Variant, Measured, Fronts)],
    cost: Cost,
) -> Result<(), String> {
    let pts: Vec<(usize, f64, f64, &Variant, bool)> = all
        .iter()
        .enumerate()
        .filter_map(|(i, (v, m, f))| {
            let x = cost.of(results, v, m)?;
            Some((i + 1, x.max(1e-3), plot_err(m.error()), v, f.on(cost)))
        })
        .collect();
    if pts.is_empty() {
        return Ok(());
    }
    let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
    let (ymin, ymax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.2), b.max(p.2))
    });
    let title = format!("force error against {}", cost.axis());
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(
            x_range(xmin, xmax).log_scale(),
            (ymin / 3.0..ymax * 3.0).log_scale(),
        )
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(cost.axis())
        .y_desc("worst relative error of N_req(s)")
        .x_label_formatter(&|x| {
            if *x >= 1e5 {
                format!("{x:.0e}")
            } else {
                format!("{x:.0}")
            }
        })
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()
        .map_err(|e| e.to_string())?;
    let red = RGBColor(214, 39, 40);
    let mut front: Vec<(f64, f64)> = pts.iter().filter(|p| p.4).map(|p| (p.1, p.2)).collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart
        .draw_series(std::iter::once(PathElement::new(
            front,
            ShapeStyle::from(&red).stroke_width(2),
        )))
        .map_err(|e| e.to_string())?
        .label("Pareto front")
        .legend(move |(x, y)| {
            PathElement::new(
                [(x, y), (x + 20, y)],
                ShapeStyle::from(&red).stroke_width(2),
            )
        });
    type Kind = (&'static str, RGBColor, fn(&Variant) -> bool);
    let kinds: [Kind; 3] = [
        ("ellipse", RGBColor(31, 119, 180), |v| {
            matches!(v.engine, Engine::Grid { table: false, .. })
        }),
        ("table", RGBColor(255, 127, 14), |v| {
            matches!(v.engine, Engine::Grid { table: true, .. })
        }),
        ("exact per tick", RGBColor(44, 160, 44), |v| {
            matches!(v.engine, Engine::Exact)
        }),
    ];
    for (name, colour, is) in kinds {
        if !pts.iter().any(|p| is(p.3)) {
            continue;
        }
        let style = ShapeStyle::from(&colour).filled();
        chart
            .draw_series(
                pts.iter()
                    .filter(|p| is(p.3))
                    .map(|p| Circle::new((p.1, p.2), 5, style)),
            )
            .map_err(|e| e.to_string())?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, style));
    }
    chart
        .draw_series(
            pts.iter()
                .filter(|p| p.4)
                .map(|p| Circle::new((p.1, p.2), 9, ShapeStyle::from(&red).stroke_width(2))),
        )
        .map_err(|e| e.to_string())?;
    chart
        .draw_series(pts.iter().filter(|p| p.4).map(|p| {
            Text::new(
                format!("{}", p.0),
                (p.1 * 1.08, p.2 * 1.35),
                ("sans-serif", 13).into_font(),
            )
        }))
        .map_err(|e| e.to_string())?;
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(())
}
