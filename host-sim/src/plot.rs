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

/// One series of an x–y plot: markers (measurements) or a line (a model).
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// Points `(x, y)`.
    pub points: Vec<(f64, f64)>,
    /// Drawn as a line (else as circles).
    pub line: bool,
}

/// One panel of [`plot_panels`]: title, axis labels, series.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Caption.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// The series, each in its own colour.
    pub series: Vec<Series>,
}

fn bounds(series: &[Series]) -> ((f64, f64), (f64, f64)) {
    let pts = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 1e-12f64, 0.0f64, 1e-12f64);
    for p in pts {
        x0 = x0.min(p.0);
        x1 = x1.max(p.0);
        y0 = y0.min(p.1);
        y1 = y1.max(p.1);
    }
    let (dx, dy) = ((x1 - x0) * 0.05, (y1 - y0) * 0.08);
    (
        (x0 - if x0 < 0.0 { dx } else { 0.0 }, x1 + dx),
        (y0 - if y0 < 0.0 { dy } else { 0.0 }, y1 + dy),
    )
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let ((x0, x1), (y0, y1)) = bounds(&p.series);
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(p.x_label.as_str())
        .y_desc(p.y_label.as_str())
        .draw()
        .map_err(|e| e.to_string())?;
    for (i, s) in p.series.iter().enumerate() {
        let col = PALETTE[i % PALETTE.len()];
        let style = ShapeStyle::from(&col).stroke_width(2);
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|q| q.0.is_finite() && q.1.is_finite())
            .collect();
        let drawn = if s.line {
            chart.draw_series(std::iter::once(PathElement::new(pts, style)))
        } else {
            chart.draw_series(pts.into_iter().map(|q| Circle::new(q, 3, style)))
        }
        .map_err(|e| e.to_string())?;
        drawn
            .label(s.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 13))
        .draw()
        .map_err(|e| e.to_string())
}

/// Draws `panels` one above the other into an SVG at `path` (900 px wide, 560 px per
/// panel).
pub fn plot_panels(path: &Path, panels: &[Panel]) -> Result<(), String> {
    let mut svg = String::new();
    {
        let height = 560 * u32::try_from(panels.len().max(1)).unwrap_or(1);
        let root = SVGBackend::with_string(&mut svg, (900, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let areas = root.split_evenly((panels.len().max(1), 1));
        for (area, p) in areas.iter().zip(panels) {
            draw_panel(area, p)?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    std::fs::write(path, svg).map_err(|e| format!("{}: {e}", path.display()))
}
