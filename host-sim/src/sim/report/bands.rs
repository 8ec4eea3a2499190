//! softgrip's command explained in the force plot: under its run's line, stacked bands
//! show the force each part of the rule asks, from the model's `N_slip` up to the target.
//!
//! | band | from | to |
//! | --- | --- | --- |
//! | `N_slip` at `μ` (the model) | 0 | `n_slip_mu_n` |
//! | × safety factor (and a disc's torsion factor β on the moment) | `n_slip_mu_n` | `n_safety_n` |
//! | × load factor (> 1: shaking) | `n_safety_n` | `n_load_n` |
//! | × load factor (< 1: a steady hold, given back) | `n_load_n` | `n_safety_n` |
//! | × slip margin (and `μ/μ̂`) | `n_load_n` | `required_n` |
//! | + lead | `required_n` | `required_n + lead_n` (not while `saturated`) |
//!
//! A tick without a reply holds the last reply's parts, as it holds its command. Bands
//! clip to the force axis; a band never taller than a millionth of the axis on it
//! is left out of the legend.

use super::*;

/// The bands' fills (the light shades of the runs' palette, the model's the palest, so the
/// runs' lines stay on top): the model, the safety factor, the load factor above 1, the
/// load factor below 1 (given back), the slip margin, the lead.
const BAND_COLOURS: [RGBColor; 6] = [
    RGBColor(198, 219, 239),
    RGBColor(152, 223, 138),
    RGBColor(255, 187, 120),
    RGBColor(212, 212, 212),
    RGBColor(255, 152, 150),
    RGBColor(197, 176, 213),
];

/// The run whose command the force plot explains: the first whose samples carry
/// softgrip's parts (a finite `required_n`; the baselines' are NaN).
pub(super) fn explained_run(runs: &[(&str, &[Sample])]) -> Option<usize> {
    runs.iter()
        .position(|(_, s)| s.iter().any(|s| s.parts.required_n.is_finite()))
}

/// `samples` with each tick that had no reply (its parts NaN) given the last reply's
/// parts: its command holds, and so does what the command is made of.
pub(super) fn held(samples: &[Sample]) -> Vec<Sample> {
    let mut last: Option<Sample> = None;
    let mut out = Vec::with_capacity(samples.len());
    for s in samples {
        match last {
            Some(l) if s.parts.mu_hat.is_nan() => out.push(Sample {
                parts: l.parts,
                ..*s
            }),
            _ => {
                if !s.parts.mu_hat.is_nan() {
                    last = Some(*s);
                }
                out.push(*s);
            }
        }
    }
    out
}

/// The sample's levels `[n_slip_mu_n, n_safety_n, n_load_n, required_n]` \[N\], if all are
/// finite.
fn levels(s: &Sample) -> Option<[f64; 4]> {
    let p = &s.parts;
    let l = [p.n_slip_mu_n, p.n_safety_n, p.n_load_n, p.required_n].map(f64::from);
    (s.t_s.is_finite() && l.iter().all(|x| x.is_finite())).then_some(l)
}

/// Band `k`'s lower and upper edge on sample `s` \[N\] (the table of the module docs).
fn band(k: usize, s: &Sample) -> Option<(f64, f64)> {
    let [slip, safety, load, required] = levels(s)?;
    match k {
        0 => Some((0.0, slip)),
        1 => Some((slip, safety)),
        2 => Some((safety, load.max(safety))),
        3 => Some((load.min(safety), safety)),
        4 => Some((load, required)),
        _ => {
            let lead = f64::from(s.parts.lead_n);
            (s.status != "saturated" && lead.is_finite()).then_some((required, required + lead))
        }
    }
}

/// Band `k`'s legend label for the run `name` with `samples`.
fn label(k: usize, name: &str, samples: &[Sample]) -> String {
    let finite = |f: fn(&Sample) -> f32| samples.iter().map(f).filter(|x| x.is_finite());
    let max = |f| finite(f).fold(f32::NEG_INFINITY, f32::max);
    let min = |f| finite(f).fold(f32::INFINITY, f32::min);
    let what = match k {
        0 => "N_slip at μ (the model)".to_string(),
        1 => "× safety factor (and the disc factor β on torsion)".to_string(),
        2 => format!("× load factor (up to {:.2})", max(|s| s.parts.load_factor)),
        3 => format!(
            "× load factor (down to {:.2}): given back",
            min(|s| s.parts.load_factor)
        ),
        4 => {
            let lowered = min(|s| s.parts.mu_hat) < max(|s| s.parts.mu_hat);
            format!(
                "× slip margin (up to {:.2}){}",
                max(|s| s.parts.slip_margin),
                if lowered { ", μ/μ̂" } else { "" }
            )
        }
        _ => "+ lead for the actuator".to_string(),
    };
    format!("{name}: {what}")
}

/// The legend labels of the bands `samples` shows (those taller than a millionth of the
/// axis `(y_min, y_max)` somewhere on it), by band index.
pub(super) fn band_labels(
    name: &str,
    samples: &[Sample],
    (y_min, y_max): (f64, f64),
) -> Vec<(usize, String)> {
    let least = 1e-6 * (y_max - y_min);
    let clip = |y: f64| y.clamp(y_min, y_max);
    (0..BAND_COLOURS.len())
        .filter(|&k| {
            samples
                .iter()
                .filter_map(|s| band(k, s))
                .any(|(lo, hi)| clip(hi) - clip(lo) > least)
        })
        .map(|k| (k, label(k, name, samples)))
        .collect()
}

/// Draws the bands of `samples` (at most [`MAX_LINE_POINTS`] / 2 samples, taken at a
/// stride) clipped to `(y_min, y_max)`, and returns the legend entries of `labels`.
pub(super) fn draw_bands(
    chart: &mut Chart<'_, '_>,
    samples: &[Sample],
    labels: &[(usize, String)],
    (y_min, y_max): (f64, f64),
) -> Result<Vec<(String, Swatch)>, ReportError> {
    let kept = stride(samples, MAX_LINE_POINTS / 2);
    let clip = |y: f64| y.clamp(y_min, y_max);
    let mut legend = Vec::new();
    for (k, text) in labels {
        let fill = BAND_COLOURS[*k].filled();
        let spans = segments(
            kept.iter()
                .map(|s| band(*k, s).map(|(lo, hi)| (s.t_s, clip(lo), clip(hi)))),
        );
        chart.draw_series(spans.into_iter().map(|span| {
            let upper = span.iter().map(|&(t, _, hi)| (t, hi));
            let lower = span.iter().rev().map(|&(t, lo, _)| (t, lo));
            Polygon::new(upper.chain(lower).collect::<Vec<_>>(), fill)
        }))?;
        legend.push((text.clone(), Swatch::Shade(fill)));
    }
    Ok(legend)
}
