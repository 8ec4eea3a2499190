//! `accuracy.md`'s section on the defaults: why each default knob value is what it is,
//! from the measured neighbours.
//!
//! The section is [`REASONS`], one entry per default (its bullet's title and the function
//! that argues it from the measurements), and [`defaults_text`], which writes them.

use super::*;

/// One default and why: the bullet `- **TITLE.** WHY`, left out when the run has nothing to
/// argue it with.
struct Reason {
    title: &'static str,
    why: fn(&Ctx) -> Option<String>,
}

/// The defaults, in the order the report gives them.
const REASONS: [Reason; 7] = [
    Reason {
        title: "Quadrature order 28",
        why: order,
    },
    Reason {
        title: "48 centre-of-rotation samples",
        why: samples,
    },
    Reason {
        title: "8 aspects",
        why: aspects,
    },
    Reason {
        title: "48 force nodes",
        why: nodes,
    },
    Reason {
        title: "f32 precomputation",
        why: precision,
    },
    Reason {
        title: "libm (FPU) square root",
        why: math,
    },
    Reason {
        title: "The default mode",
        why: mode,
    },
];

/// Writes the section's bullets and a blank line.
pub(super) fn defaults_text(out: &mut String, results: &Results) {
    let ctx = Ctx::new(results);
    for reason in &REASONS {
        if let Some(why) = (reason.why)(&ctx) {
            let _ = writeln!(out, "- **{}.** {why}", reason.title);
        }
    }
    out.push('\n');
}

/// What the reasons read: the results and the two default configurations (ellipse and
/// table mode) with what they measured.
struct Ctx<'a> {
    results: &'a Results,
    def_e: Variant,
    def_t: Variant,
    me: Measured,
    mt: Measured,
}

impl<'a> Ctx<'a> {
    fn new(results: &'a Results) -> Self {
        let def_e = Variant::default_mode(false).normalised();
        let def_t = Variant::default_mode(true).normalised();
        Ctx {
            results,
            def_e,
            def_t,
            me: get(results, &def_e),
            mt: get(results, &def_t),
        }
    }
}

fn order(c: &Ctx) -> Option<String> {
    let mt = c.mt;
    // Orders that keep the pitch at the f32 floor (the default's level, or 1e-6).
    let pitch_floor = mt.pitch_err.max(1e-6);
    let orders: Vec<(Variant, Measured)> = mode_rows(c.results, Knob::Order, true)
        .into_iter()
        .filter(|(_, m)| m.pitch_err <= pitch_floor)
        .collect();
    let (vo, mo) = enough(&orders, Measured::error, |v| v.order)?;
    let verdict = if vo.order < c.def_t.order {
        format!(
            "the numbers would allow order {} for the f32 firmware ({} less start-up in \
             table mode); 28 stays the default because the same core serves f64 on the \
             host, where order 28 is what keeps a point within 1e-9 of the converged \
             integral (tests/fls_accuracy.rs; docs/core.md), and because the start-up runs \
             once",
            vo.order,
            pct(1.0 - mo.precompute_us / mt.precompute_us.max(1e-9))
        )
    } else {
        "the default is the cheapest order at that level".to_string()
    };
    Some(format!(
        "Pitch error {} (f32 start-up), force error {} in table mode. Order {} is the \
         cheapest that keeps the pitch within {} (pitch error {}) and the commanded force \
         within 10 % of the best order tried ({} against {}), at {} µs of table start-up \
         against {} µs: {verdict}.",
        sci(mt.pitch_err),
        sci(mt.error()),
        vo.order,
        sci(pitch_floor),
        sci(mo.pitch_err),
        sci(mo.error()),
        sci(mt.error()),
        time(mo.precompute_us),
        time(mt.precompute_us),
    ))
}

fn samples(c: &Ctx) -> Option<String> {
    let mt = c.mt;
    let rows = mode_rows(c.results, Knob::Samples, true);
    let (vs, ms) = enough(&rows, Measured::error, |v| v.samples)?;
    let verdict = if vs.samples < c.def_t.samples {
        format!(
            "{} samples would do as well here; 48 keeps a margin for other fingers",
            vs.samples
        )
    } else if vs.samples > c.def_t.samples {
        format!(
            "more samples still help ({} reach {}), at {} µs of start-up: a candidate if \
             the start-up budget allows",
            vs.samples,
            sci(ms.error()),
            time(ms.precompute_us)
        )
    } else {
        "48 is the cheapest setting at the best level".to_string()
    };
    Some(format!(
        "Table force error {} ({} µs start-up); {verdict}. Past the chords' error the \
         controller's {}-direction storage is the floor (section 2): more directions, not \
         more samples, would lower it.",
        sci(mt.error()),
        time(mt.precompute_us),
        softgrip::controller::DIRECTIONS,
    ))
}

fn aspects(c: &Ctx) -> Option<String> {
    let rows = mode_rows(c.results, Knob::Aspects, true);
    let (va, ma) = enough(&rows, Measured::error, |v| v.aspects)?;
    let verdict = if va.aspects < c.def_t.aspects {
        format!(
            "{} aspects are as good on this finger ({}); 8 covers fingers whose aspect \
             range is wider",
            va.aspects,
            sci(ma.error())
        )
    } else if va.aspects > c.def_t.aspects {
        format!(
            "{} aspects would cut the error to {} for {} µs of start-up",
            va.aspects,
            sci(ma.error()),
            time(ma.precompute_us)
        )
    } else {
        "8 is the cheapest setting at the best level".to_string()
    };
    Some(format!(
        "Table force error {}; {verdict}.",
        sci(c.mt.error())
    ))
}

fn nodes(c: &Ctx) -> Option<String> {
    let (me, def_e) = (c.me, c.def_e);
    let rows = mode_rows(c.results, Knob::Nodes, false);
    let (vn, mn) = enough(&rows, |m| m.n_err_own, |v| v.nodes)?;
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
    let on_target: Vec<(Variant, Measured, f64)> = rows
        .iter()
        .filter_map(|(v, m)| Some((*v, *m, target_cost(c.results, v)?.tick_median)))
        .collect();
    let target_text = match (
        on_target.iter().find(|(v, _, _)| v.nodes == def_e.nodes),
        on_target.iter().min_by(|a, b| a.2.total_cmp(&b.2)),
    ) {
        (Some(d), Some(best)) if best.0.nodes != def_e.nodes => {
            let advice = if best.1.n_err_own <= 1e-3 {
                format!(
                    "**the numbers suggest {} nodes** where the ellipse tick budget is tight",
                    best.0.nodes
                )
            } else {
                "a cheaper tick bought with that much more (safe-side) force".to_string()
            };
            format!(
                " On the M4F the node count moves the tick: {:.0} instructions median at 48 \
                 nodes (ellipse budget 2 000), {:.0} at {} nodes, the cheapest, which leave \
                 {} against the own rule (conservative): {advice}.",
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
    Some(format!(
        "Ellipse-mode force error against its own rule {} (the arm interpolation is \
         conservative); {verdict}.{target_text}",
        sci(me.n_err_own),
    ))
}

fn precision(c: &Ctx) -> Option<String> {
    let (mt, def_t) = (c.mt, c.def_t);
    let f64pre_v = Variant {
        engine: Engine::Grid {
            table: true,
            precision: super::knobs::Precision::F64Precompute,
            math: super::knobs::MathKind::Libm,
        },
        ..def_t
    };
    let f64pre = get(c.results, &f64pre_v);
    let target_startup = match (
        target_cost(c.results, &def_t),
        target_cost(c.results, &f64pre_v),
    ) {
        (Some(a), Some(b)) => format!(
            "{:.1} M against {:.1} M instructions in this run ({:.0}×)",
            b.startup / 1e6,
            a.startup / 1e6,
            b.startup / a.startup.max(1.0)
        ),
        _ => "not measured in this run (`--target`)".to_string(),
    };
    Some(format!(
        "Table force error {} with an f32 start-up against {} with f64, and the pitch error \
         {} against {}: the grid's own errors dominate both. On the host the f64 start-up \
         takes {} µs against {} µs; on the M4F's single-precision FPU it is soft-float: \
         {target_startup}, for nothing visible in the commanded force.",
        sci(mt.error()),
        sci(f64pre.error()),
        sci(mt.pitch_err),
        sci(f64pre.pitch_err),
        time(f64pre.precompute_us),
        time(mt.precompute_us),
    ))
}

fn math(c: &Ctx) -> Option<String> {
    let (me, def_e) = (c.me, c.def_e);
    let micro_v = Variant {
        engine: Engine::Grid {
            table: false,
            precision: super::knobs::Precision::F32,
            math: super::knobs::MathKind::Micromath,
        },
        ..def_e
    };
    let micro = get(c.results, &micro_v);
    let host = compare_times(micro.tick_ns, me.tick_ns);
    let target_math = match (
        target_cost(c.results, &def_e),
        target_cost(c.results, &micro_v),
    ) {
        (Some(a), Some(b)) => format!(
            "on the M4F {:.0} against {:.0} instructions median in this run",
            b.tick_median, a.tick_median
        ),
        _ => "on the M4F not measured in this run (`--target`)".to_string(),
    };
    Some(format!(
        "micromath raises the ellipse-mode force by up to {} against its own rule (libm: \
         {}), for a tick of {} ns against {} ns on the host ({host}) and {target_math}: the \
         FPU's `VSQRT` is one instruction, so there is nothing to win.",
        sci(micro.n_err_own),
        sci(me.n_err_own),
        time(micro.tick_ns),
        time(me.tick_ns),
    ))
}

fn mode(c: &Ctx) -> Option<String> {
    let (me, mt) = (c.me, c.mt);
    let exact_text = c
        .results
        .measured
        .iter()
        .find(|(v, _)| matches!(v.engine, Engine::Exact))
        .map_or(String::new(), |(_, x)| {
            format!(
                " Exact integration per tick gets {} but costs {} µs a tick, {:.0}× a table \
                 tick: not an option at 1 kHz on a microcontroller.",
                sci(x.error()),
                time(x.tick_ns / 1000.0),
                x.tick_ns / mt.tick_ns.max(1e-9)
            )
        });
    let on_front = |v: &Variant| {
        if front_of(c.results, v).on(Cost::HostTick) {
            "on"
        } else {
            "not on"
        }
    };
    let target_ticks = match (
        target_cost(c.results, &c.def_e),
        target_cost(c.results, &c.def_t),
    ) {
        (Some(e), Some(t)) => format!(
            "measured in this run: {:.0} against {:.0} instructions median on the M4F",
            t.tick_median, e.tick_median
        ),
        _ => "M4F instructions not measured in this run (`--target`)".to_string(),
    };
    // The ellipse is inscribed in the exact surface, so its error is on the safe side;
    // a run that measured an under-ask says so instead.
    let ellipse_side = if me.under_ask > 0.0 {
        format!(
            "against the exact surface it asks for up to {} less force than needed (worst \
             under-ask over both fingers), which the safety factor must cover",
            share(me.under_ask)
        )
    } else {
        format!(
            "against the exact surface it never asks for less force than needed (no \
             under-ask on either finger: the ellipse lies inside the surface), and pays \
             for that with up to {} more force than the exact surface needs",
            share(me.error())
        )
    };
    let table_under = if mt.under_ask > 0.0 {
        format!("worst under-ask {}", share(mt.under_ask))
    } else {
        "no under-ask".to_string()
    };
    let default_text = default_mode_text();
    Some(format!(
        "Ellipse mode is the cheapest tick ({} ns; table {} ns, {:.1}×) but the least accurate rule: \
         {ellipse_side}; table mode is within {} ({table_under}). The default ellipse \
         configuration is {} the tick front and the default table configuration is {} it \
         (configurations running the same tick code tie within timing noise, so which of \
         them lands on the front is partly chance).{exact_text} **At one safety factor the \
         numbers favour table mode** wherever its tick fits the budget ({target_ticks}; \
         budgets 5 000 and 2 000): the same model for less force. {default_text}",
        time(me.tick_ns),
        time(mt.tick_ns),
        mt.tick_ns / me.tick_ns.max(1e-9),
        share(mt.error()),
        on_front(&c.def_e),
        on_front(&c.def_t),
    ))
}

/// Why the default mode is the default: the bench's choice, whichever mode it is.
fn default_mode_text() -> String {
    let default = softgrip::controller::ControllerConfig::DEFAULT;
    match default.mode {
        softgrip::controller::Mode::Ellipse => format!(
            "But the default is ellipse mode, at safety {}: the bench chooses the mode and \
             the factor together on held-out seeds, on a plant neither rule models exactly \
             (docs/bench.md, \"The default\"), and there ellipse mode at a lower factor \
             held as many trials as table mode at its own choice, for less force. Table \
             mode serves a finger that matches the model closely (a calibrated one, say) \
             on a part with room for its tick.",
            default.safety
        ),
        softgrip::controller::Mode::Table => format!(
            "Table mode is the default, at safety {}, as the bench chose it on held-out \
             seeds (docs/bench.md, \"The default\"); ellipse mode is the cheaper tick, \
             whose error is on the safe side, for a part whose budget has no room for \
             table mode's.",
            default.safety
        ),
    }
}
