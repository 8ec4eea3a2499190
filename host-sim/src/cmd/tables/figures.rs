//! `tables --plot`: the limit surfaces of the paper's Figures 9–12, with their Eq. 10
//! ellipses, as SVG.

use super::bar;
use crate::plot::{ellipse, plot_curves, Curve};
use crate::CliError;
use rayon::prelude::*;
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};
use std::path::Path;

fn surface(
    shape: Shape,
    k: f64,
    skew: Option<(f64, f64, f64)>,
    samples: usize,
) -> Result<(Vec<(f64, f64)>, f64), String> {
    let model = FlsModel::<f64>::new(FlsConfig {
        shape,
        k,
        skew,
        order: QuadratureOrder::DEFAULT,
    })
    .map_err(|e| e.to_string())?;
    let table = FlsTable::<f64, 257>::sweep(&model, samples).map_err(|e| e.to_string())?;
    Ok((
        table.points().iter().map(|p| (p.f, p.m)).collect(),
        model.pitch(),
    ))
}

/// A figure: title, file name, and its surfaces `(label, shape, k, skew)`.
type Figure = (
    &'static str,
    &'static str,
    Vec<(String, Shape, f64, Option<(f64, f64, f64)>)>,
);

fn figures() -> Vec<Figure> {
    let sq = Shape::Rect { aspect: 1.0 };
    let paper = Some((0.9, 1.1, 0.45));
    vec![
        (
            "Rectangle l = a: the limit surface for several k (cf. Fig. 9)",
            "fls_k.svg",
            [1.0, 2.0, 4.0, 50.0, f64::INFINITY]
                .iter()
                .map(|&k| (format!("k = {k}"), sq, k, None))
                .collect(),
        ),
        (
            "Rectangle l = a, k = 2: with and without skew (Δ/a = 0.9, α = 1.1) (cf. Fig. 10)",
            "fls_skew.svg",
            vec![
                ("symmetric".into(), sq, 2.0, None),
                ("skewed".into(), sq, 2.0, paper),
            ],
        ),
        (
            "Rectangle l = a, skewed: several k (cf. Fig. 11)",
            "fls_skew_k.svg",
            [2.0, 4.0, 50.0]
                .iter()
                .map(|&k| (format!("k = {k}, skewed"), sq, k, paper))
                .collect(),
        ),
        (
            "Disc, k = 2, skewed: variants of the P_max locus h/a (cf. Fig. 12)",
            "fls_locus.svg",
            [0.0, 0.225, 0.45, 0.675]
                .iter()
                .map(|&h| {
                    (
                        format!("locus h/a = {h}"),
                        Shape::Disc,
                        2.0,
                        Some((0.9, 1.1, h)),
                    )
                })
                .collect(),
        ),
    ]
}

/// A computed surface: (figure, curve), its points and its pitch.
type Swept = ((usize, usize), Vec<(f64, f64)>, f64);

pub(super) fn plot(out: &Path, quiet: bool) -> Result<(), CliError> {
    let figs = figures();
    let jobs: Vec<(usize, usize)> = figs
        .iter()
        .enumerate()
        .flat_map(|(f, fig)| (0..fig.2.len()).map(move |c| (f, c)))
        .collect();
    let b = bar(jobs.len() as u64, "surfaces", quiet);
    let results: Vec<Result<Swept, String>> = jobs
        .par_iter()
        .map(|&(f, c)| {
            let (_, shape, k, skew) = &figs[f].2[c];
            let r = surface(*shape, *k, *skew, 128).map(|(p, pitch)| ((f, c), p, pitch));
            b.inc(1);
            r
        })
        .collect();
    b.finish_and_clear();
    let mut done: Vec<Swept> = results
        .into_iter()
        .collect::<Result<_, _>>()
        .map_err(CliError::Failed)?;
    done.sort_by_key(|r| r.0);
    for (f, (title, file, specs)) in figs.iter().enumerate() {
        let mut curves = Vec::new();
        let mut pitches: Vec<f64> = Vec::new();
        for (c, (label, ..)) in specs.iter().enumerate() {
            if let Some((_, pts, pitch)) = done.iter().find(|r| r.0 == (f, c)) {
                curves.push(Curve {
                    label: label.clone(),
                    points: pts.clone(),
                    dashed: false,
                });
                // One ellipse per pitch: the skew does not change it.
                if !pitches.iter().any(|p| (p - pitch).abs() < 1e-12) {
                    pitches.push(*pitch);
                    curves.push(ellipse(*pitch, &format!("{label}: Eq. 10 ellipse")));
                }
            }
        }
        let path = out.join(file);
        plot_curves(&path, title, "f̃ = f_t / (μN)", "m̃ = m_n / (μNa)", &curves)
            .map_err(CliError::Failed)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
