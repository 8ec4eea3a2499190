//! Limit-surface plots in the manner of the paper's Figures 9–12: the surface `(f̃, m̃)`
//! of several configurations, with the Eq. 10 ellipse for comparison (SVG, plotters'
//! SVG backend, text as `<text>` elements).

use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::path::Path;

/// One curve: label, points, dashed or not.
#[derive(Debug, Clone)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
    /// Drawn dashed (the ellipse approximations).
    pub dashed: bool,
}

/// The simulator's run colours, so that every plot of the project looks alike.
const PALETTE: [RGBColor; 8] = crate::sim::report::RUN_COLOURS;

/// Draws `curves` into an SVG at `path`. Dashed curves take the colour of the solid curve
/// before them (a surface and its ellipse share a colour).
pub fn plot_curves(
    path: &Path,
    title: &str,
    x_label: &str,
    y_label: &str,
    curves: &[Curve],
) -> Result<(), String> {
    let finite = curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut xmax, mut ymax) = (1.0f64, 0.1f64);
    for p in finite {
        xmax = xmax.max(p.0);
        ymax = ymax.max(p.1);
    }
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..xmax * 1.05, 0.0..ymax * 1.15)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .draw()
            .map_err(|e| e.to_string())?;
        let mut colour = 0usize;
        for (i, c) in curves.iter().enumerate() {
            if !c.dashed && i > 0 {
                colour += 1;
            }
            let col = PALETTE[colour % PALETTE.len()];
            let style = ShapeStyle::from(&col).stroke_width(2);
            let pts: Vec<(f64, f64)> = c
                .points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            let series = if c.dashed {
                chart.draw_series(std::iter::once(DashedPathElement::new(pts, 6, 5, style)))
            } else {
                chart.draw_series(std::iter::once(PathElement::new(pts, style)))
            }
            .map_err(|e| e.to_string())?;
            series
                .label(c.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    std::fs::write(path, svg).map_err(|e| format!("{}: {e}", path.display()))
}

/// The Eq. 10 ellipse `f̃² + (m̃/pitch)² = 1` as a curve.
pub fn ellipse(pitch: f64, label: &str) -> Curve {
    Curve {
        label: label.to_string(),
        points: (0..=90)
            .map(|i| {
                let th = std::f64::consts::FRAC_PI_2 * f64::from(i) / 90.0;
                (th.sin(), pitch * th.cos())
            })
            .collect(),
        dashed: true,
    }
}
