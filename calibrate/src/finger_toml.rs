//! The finger TOML: the calibration as a scene's `[finger]` table (shape, k, mu, c, gamma,
//! half_length_m) and, when the skew is nonzero, the scene's skew as it spells it:
//! `effects = ["skewed_pressure"]` and `[effect.skewed_pressure]` (delta_over_a, alpha,
//! locus_over_a). A scene includes it by copying these lines; `host-sim tables --finger`
//! and `host-sim experiment --finger` read the file as it is. Each value's interval, or
//! why it was held, is a comment on its line.

use crate::calibration::Calibration;
use crate::estimate::{Estimate, Refit};
use crate::lack_of_fit::{LackOfFit, NoiseSource, MIN_NOISE_DF};
use std::fmt::Write;

/// A number as TOML writes it: shortest round-trip, `inf` for infinity.
pub(crate) fn num(v: f64) -> String {
    if v.is_infinite() {
        if v > 0.0 { "inf" } else { "-inf" }.to_string()
    } else if v == v.trunc() && v.abs() < 1e15 {
        format!("{v:.1}")
    } else {
        format!("{v}")
    }
}

/// `v` to 4 significant digits, for people (comments, the text report).
pub(crate) fn sig4(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return num(v);
    }
    let decimals = 3 - v.abs().log10().floor() as i32;
    if (0..=9).contains(&decimals) {
        format!("{v:.*}", decimals as usize)
    } else {
        format!("{v:.3e}")
    }
}

fn comment(e: &Estimate) -> String {
    let ci = e
        .ci95
        .map(|[lo, hi]| format!("95 %: [{}, {}]", sig4(lo), sig4(hi)));
    match (&e.reason, ci) {
        (Some(r), Some(ci)) => format!("  # not identified ({ci}): {r}"),
        (Some(r), None) => format!("  # not identified: {r}"),
        (None, Some(ci)) => format!("  # {ci}"),
        (None, None) => String::new(),
    }
}

/// A lab file's name for the finger TOML's heading: relative to the current directory
/// when it lies under it (so that the heading does not depend on where the lab sits on
/// the machine), else as given.
pub fn source_name(path: &std::path::Path) -> String {
    std::env::current_dir()
        .ok()
        .filter(|_| path.is_absolute())
        .and_then(|cwd| path.strip_prefix(cwd).ok().map(|p| p.display().to_string()))
        .unwrap_or_else(|| path.display().to_string())
}

/// The finger TOML of `cal`; `source` (the data's file names) goes into the heading
/// comment.
pub fn finger_toml(cal: &Calibration, source: &str) -> String {
    let mut s = String::new();
    let kind = if cal.conservative {
        "conservative values (each at the capacity-lowering end of its 95 % interval)"
    } else if cal.friction_contact.is_some() {
        "fitted values, with the contact friction sees"
    } else {
        "fitted values"
    };
    let _ = writeln!(s, "# softgrip finger calibrated from {source}: {kind}.");
    for w in &cal.warnings {
        let _ = writeln!(s, "# WARNING: {w}");
    }
    if let Some(fc) = &cal.friction_contact {
        let _ = writeln!(s, "# {}.", fc.describe(cal.half_length_m, sig4));
    }
    let _ = writeln!(s, "# {}.", safety_line(cal));
    let skew = cal.skew();
    if skew.is_some() {
        let _ = writeln!(s, "effects = [\"skewed_pressure\"]");
    }
    let _ = writeln!(s, "\n[finger]");
    let _ = writeln!(s, "shape = \"{}\"", cal.shape);
    for (name, e) in [
        ("k", &cal.k),
        ("mu", &cal.mu),
        ("c", &cal.c),
        ("gamma", &cal.gamma),
    ] {
        let _ = writeln!(s, "{name} = {}{}", num(e.value), comment(e));
    }
    let length_note = match &cal.friction_contact {
        Some(fc) if fc.refit == Refit::HalfLength => "friction's, refitted (see above)",
        _ => "given",
    };
    let _ = writeln!(
        s,
        "half_length_m = {}  # {length_note}",
        num(cal.half_length_m)
    );
    let sp = &cal.skewed_pressure;
    let rows = [
        ("delta_over_a", &sp.delta_over_a),
        ("alpha", &sp.alpha),
        ("locus_over_a", &sp.locus_over_a),
    ];
    if skew.is_some() {
        let _ = writeln!(s, "\n[effect.skewed_pressure]");
        for (name, e) in rows {
            let _ = writeln!(s, "{name} = {}{}", num(e.value), comment(e));
        }
    } else {
        let _ = writeln!(s, "\n# No skew (the symmetric profile):");
        for (name, e) in rows {
            let _ = writeln!(
                s,
                "# skewed_pressure.{name} = {}{}",
                num(e.value),
                comment(e)
            );
        }
    }
    s
}

/// The calibration for people: one line per parameter, value and interval to 4
/// significant digits, and for a held one "not identified: kept at X (conservative)" with
/// the reason; then the fit's residuals and its lack-of-fit test
/// ([`crate::lack_of_fit`]).
pub fn report_text(cal: &Calibration) -> String {
    let mut s = String::new();
    let sp = &cal.skewed_pressure;
    let rows = [
        ("mu", &cal.mu),
        ("k", &cal.k),
        ("c", &cal.c),
        ("gamma", &cal.gamma),
        ("skew delta_over_a", &sp.delta_over_a),
        ("skew alpha", &sp.alpha),
        ("skew locus_over_a", &sp.locus_over_a),
    ];
    for (name, e) in rows {
        let ci = e.ci95.map_or(String::new(), |[lo, hi]| {
            format!("  95 % [{}, {}]", sig4(lo), sig4(hi))
        });
        match &e.reason {
            None => {
                let _ = writeln!(s, "{name:<18} {}{ci}", sig4(e.value));
            }
            Some(r) => {
                let _ = writeln!(s, "{name:<18} not identified: {r}{ci}");
            }
        }
    }
    let _ = writeln!(s, "{}", safety_line(cal));
    let f = &cal.fit;
    let [fo, to, mi] = f.onsets_force_torsion_mixed;
    let _ = writeln!(
        s,
        "fit: {} indentations (sd of ln a {:.4}), onsets {fo} force + {to} torsion + {mi} \
         mixed (sd of ln u {:.4}), {} degrees of freedom{}",
        f.indentation_rows,
        f.sigma_ln_half_width,
        f.sigma_ln_utilisation,
        f.df,
        if cal.conservative {
            "; conservative values"
        } else {
            ""
        }
    );
    let _ = writeln!(s, "{}", lack_of_fit_line(&f.lack_of_fit));
    if let Some(fc) = &cal.friction_contact {
        let _ = writeln!(s, "{}", fc.describe(cal.half_length_m, sig4));
    }
    s
}

/// What safety factor `μ`'s interval needs ([`Calibration::safety_for_mu`]), for the
/// text report and the finger TOML's heading.
fn safety_line(cal: &Calibration) -> String {
    match cal.safety_for_mu() {
        Some(s) => format!(
            "safety >= {} covers mu's 95 % interval (mu/mu_lo); a drift of mu you expect \
             multiplies it",
            sig4(s)
        ),
        None => "safety for mu: no interval on mu to cover".to_string(),
    }
}

/// The lack-of-fit test's line of the text report.
fn lack_of_fit_line(l: &LackOfFit) -> String {
    let from = match l.noise_from {
        NoiseSource::Repeats => "their repeats",
        NoiseSource::PureForceOnsets => "the pure-force onsets' scatter",
        NoiseSource::None => {
            return format!(
                "lack of fit: not tested (RMS of ln u {}): neither repeated onsets nor \
                 pure-force onsets give the noise {MIN_NOISE_DF} degrees of freedom",
                sig4(l.rms_ln_utilisation)
            )
        }
    };
    let [d1, d2] = l.f_df;
    format!(
        "lack of fit: RMS of ln u {} against a noise of {} from {from} (F {} on {d1} and {d2} \
         degrees of freedom, p {}): {}",
        sig4(l.rms_ln_utilisation),
        sig4(l.noise_sd.unwrap_or(0.0)),
        l.f_ratio.map_or("inf".to_string(), sig4),
        l.p_value.map_or("-".to_string(), |p| format!("{p:.2e}")),
        if l.contradicted {
            "the rows contradict the fit (see the warning)"
        } else {
            "consistent with the rows"
        }
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers() {
        assert_eq!(sig4(0.0025165), "0.002517");
        assert_eq!(sig4(12.3456), "12.35");
        assert_eq!(sig4(f64::INFINITY), "inf");
        assert_eq!(num(2.0), "2.0");
        assert_eq!(num(0.1), "0.1");
        assert_eq!(num(f64::INFINITY), "inf");
    }
}
