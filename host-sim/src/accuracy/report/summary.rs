//! What `accuracy` prints on stdout: the run's headline figures.

use super::*;

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
