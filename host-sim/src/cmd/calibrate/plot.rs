//! The calibration's plot: the onsets in the fitted surface's normalised coordinates
//! `(f̃, m̃/pitch)`, with the fitted surface at the least, middle and greatest force of the
//! data (on the rectangle the surface's shape changes with `l/a(N)`); below, the
//! residuals `ln u` (the utilisation of each onset on the fitted surface, 0 on it) against
//! the normal force. Cost: one 64-point sweep per onset and per curve.

use crate::plot::{plot_panels, Panel, Series};
use softgrip::controller::FingerShape;
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};
use softgrip_calibrate::lab_csv::{OnsetKind, SlipOnset};
use softgrip_calibrate::Calibration;
use std::path::Path;

type Table = FlsTable<f64, 65>;

/// The fitted surface at normal force `n`, and `a(n)`.
fn surface(cal: &Calibration, n: f64) -> Result<(Table, f64), String> {
    let a = cal.half_width_m(n);
    let model = FlsModel::<f64>::new(FlsConfig {
        shape: match cal.finger_shape() {
            FingerShape::Rect => Shape::Rect {
                aspect: cal.half_length_m / a,
            },
            FingerShape::Disc => Shape::Disc,
        },
        k: cal.k.value,
        skew: cal
            .skew()
            .map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
        order: QuadratureOrder::DEFAULT,
    })
    .map_err(|e| e.to_string())?;
    Ok((Table::sweep(&model, 64).map_err(|e| e.to_string())?, a))
}

const KINDS: [(OnsetKind, &str); 3] = [
    (OnsetKind::Force, "pure force"),
    (OnsetKind::Torsion, "pure torsion"),
    (OnsetKind::Mixed, "mixed"),
];

/// Writes the plot of `cal` (the fitted values) and the onsets `slip` to `path`.
pub fn fit(path: &Path, cal: &Calibration, slip: &[SlipOnset]) -> Result<(), String> {
    let mu = cal.mu.value;
    let mut forces: Vec<f64> = slip.iter().map(|o| o.normal_force_n).collect();
    forces.sort_by(f64::total_cmp);
    let picks = [
        forces[0],
        forces[forces.len() / 2],
        forces[forces.len() - 1],
    ];
    let mut top = Vec::new();
    for n in picks {
        let (t, _) = surface(cal, n)?;
        let p = t.pitch();
        top.push(Series {
            label: format!("fitted surface, N = {n:.3} N"),
            points: t.points().iter().map(|q| (q.m / p, q.f)).collect(),
            line: true,
        });
    }
    let mut onsets: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 3];
    let mut residuals: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 3];
    for o in slip {
        let n = o.normal_force_n;
        let (t, a) = surface(cal, n)?;
        let (f, m) = (
            o.tangential_force_n / (mu * n),
            o.torsional_moment_nm / (mu * n * a),
        );
        let i = KINDS.iter().position(|k| k.0 == o.kind()).unwrap_or(2);
        onsets[i].push((m / t.pitch(), f));
        residuals[i].push((n, t.utilisation(f, m).ln()));
    }
    let series = |pts: Vec<Vec<(f64, f64)>>| {
        pts.into_iter()
            .zip(KINDS)
            .filter(|(p, _)| !p.is_empty())
            .map(|(points, (_, label))| Series {
                label: label.into(),
                points,
                line: false,
            })
            .collect::<Vec<_>>()
    };
    top.extend(series(onsets));
    let panels = [
        Panel {
            title: format!(
                "Onsets against the fitted surface (mu {mu:.3}, k {:.2})",
                cal.k.value
            ),
            x_label: "m_n/(mu N a pitch)".into(),
            y_label: "f_t/(mu N)".into(),
            series: top,
        },
        Panel {
            title: "Residuals: ln u of each onset on the fitted surface".into(),
            x_label: "normal force N [N]".into(),
            y_label: "ln u".into(),
            series: series(residuals),
        },
    ];
    plot_panels(path, &panels)
}
