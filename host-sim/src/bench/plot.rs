//! The Pareto plot of one family: drop rate [%] against mean force over the oracle's
//! [-], one curve per controller through its knob values, its default ringed. Written as
//! SVG (plotters) and as PNG (that SVG rasterised by resvg with a system font).

use super::stats::Row;
use crate::sim::controllers::ControllerKind;
use crate::sim::report::RUN_COLOURS;
use plotters::prelude::*;
use std::path::Path;

/// Width and height of the plots [px].
const SIZE: (u32, u32) = (1500, 650);

/// Drop rates up to this [%] are the right panel's range: the region of the Pareto check
/// ([`super::report::DOMINANCE_MAX_DROP_RATE`]), with room for the markers.
pub const ZOOM_DROP_PCT: f64 = 12.0;

/// The SVG text of the Pareto plot of `family`'s rows: every setting on the left, the
/// settings that drop at most [`ZOOM_DROP_PCT`] % on the right, on linear axes.
pub fn pareto_svg(family: &str, rows: &[Row]) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let root = root
            .titled(
                &format!("{family}: drop rate against force (ringed: each controller's default)"),
                ("sans-serif", 24),
            )
            .map_err(|e| e.to_string())?;
        let (left, right) = root.split_horizontally(SIZE.0 * 11 / 20);
        draw_all(&left, rows).map_err(|e| e.to_string())?;
        draw_zoom(&right, rows).map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

/// One setting's point: force over oracle [-], drop rate [%], whether it is the default.
type Point = (f64, f64, bool);

/// One controller's points, sorted by force.
type Curve<'a> = (&'a str, Vec<Point>);

/// Every controller's curve, in the order of the rows.
fn curves(rows: &[Row]) -> Vec<Curve<'_>> {
    let mut out: Vec<Curve<'_>> = Vec::new();
    for r in rows.iter().filter(|r| r.force_over_oracle.is_finite()) {
        let p = (r.force_over_oracle, 100.0 * r.drop_rate, r.default);
        match out.iter_mut().find(|(c, _)| *c == r.controller) {
            Some((_, pts)) => pts.push(p),
            None => out.push((&r.controller, vec![p])),
        }
    }
    for (_, pts) in &mut out {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    out
}

/// A log axis' tick label: two significant digits at most (plotters' own prints the
/// float's whole expansion, and its labels ran into each other).
fn tick_label(x: f64) -> String {
    let digits = if x >= 10.0 {
        0
    } else if x >= 1.0 {
        1
    } else {
        2
    };
    let s = format!("{x:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Every setting, force on a log axis.
fn draw_all<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[Row],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let xs = || {
        rows.iter()
            .map(|r| r.force_over_oracle)
            .filter(|x| x.is_finite() && *x > 0.0)
    };
    let x_max = xs().fold(1.0_f64, f64::max) * 1.1;
    let x_min = xs().fold(1.0_f64, f64::min) * 0.9;
    let y_max = rows
        .iter()
        .map(|r| 100.0 * r.drop_rate)
        .fold(5.0_f64, f64::max)
        * 1.08;
    let mut chart = ChartBuilder::on(area)
        .caption("every setting", ("sans-serif", 18))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(65)
        .build_cartesian_2d((x_min..x_max).log_scale(), 0.0..y_max)?;
    chart
        .configure_mesh()
        .x_labels(8)
        .x_label_formatter(&|x| tick_label(*x))
        .max_light_lines(3)
        .x_desc("mean normal force / oracle's mean force [-] (log scale)")
        .y_desc("trials dropped [%]")
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    for (i, (c, pts)) in curves(rows).into_iter().enumerate() {
        let colour = RUN_COLOURS[i % RUN_COLOURS.len()];
        let style = ShapeStyle::from(&colour).stroke_width(2);
        chart
            .draw_series(std::iter::once(PathElement::new(
                pts.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
                style,
            )))?
            .label(c)
            .legend(move |(x, y)| {
                EmptyElement::at((x, y))
                    + PathElement::new(vec![(0, 0), (20, 0)], style)
                    + Circle::new((10, 0), 4, colour.filled())
            });
        draw_markers(&mut chart, &pts, colour)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 16))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// The settings that drop at most [`ZOOM_DROP_PCT`] %, on linear axes; each curve is cut
/// where it leaves that range (its segments to the points beyond are drawn up to the
/// frame).
fn draw_zoom<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    rows: &[Row],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let all = curves(rows);
    let inside = |p: &Point| p.1 <= ZOOM_DROP_PCT;
    // From the least force that drops at most ZOOM_DROP_PCT to a margin beyond the least force
    // at which some baseline reaches its fewest drops (none, unless some trials cannot be held
    // at all), or softgrip's farthest default.
    let x_min = all
        .iter()
        .flat_map(|(_, pts)| pts.iter().filter(|p| inside(p)).map(|p| p.0))
        .fold(f64::INFINITY, f64::min);
    let least_zero = |c: &Curve<'_>| {
        let fewest = c.1.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        c.1.iter()
            .filter(|p| p.1 == fewest && inside(p))
            .map(|p| p.0)
            .fold(f64::INFINITY, f64::min)
    };
    let baseline_zero = all
        .iter()
        .filter(|c| !ControllerKind::name_is_softgrip(c.0))
        .map(least_zero)
        .fold(f64::INFINITY, f64::min);
    let softgrip_default = all
        .iter()
        .filter(|c| ControllerKind::name_is_softgrip(c.0))
        .flat_map(|c| c.1.iter().filter(|p| p.2).map(|p| p.0))
        .fold(0.0_f64, f64::max);
    let x_max = (baseline_zero * 1.3).max(softgrip_default * 1.15);
    if !(x_min.is_finite() && x_max.is_finite() && x_max > x_min) {
        return Ok(());
    }
    let (x_min, x_max) = (x_min * 0.97, x_max);
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("settings that drop at most {ZOOM_DROP_PCT:.0} %"),
            ("sans-serif", 18),
        )
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(55)
        .build_cartesian_2d(x_min..x_max, 0.0..ZOOM_DROP_PCT)?;
    chart
        .configure_mesh()
        .x_desc("mean normal force / oracle's mean force [-]")
        .y_desc("trials dropped [%]")
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    let in_box = |p: &Point| inside(p) && p.0 >= x_min && p.0 <= x_max;
    for (i, (_, pts)) in all.iter().enumerate() {
        let colour = RUN_COLOURS[i % RUN_COLOURS.len()];
        let style = ShapeStyle::from(&colour).stroke_width(2);
        for seg in pts.windows(2) {
            if let Some(line) = clip_segment(seg[0], seg[1], (x_min, x_max), ZOOM_DROP_PCT) {
                chart.draw_series(std::iter::once(PathElement::new(line.to_vec(), style)))?;
            }
        }
        let shown: Vec<Point> = pts.iter().copied().filter(in_box).collect();
        draw_markers(&mut chart, &shown, colour)?;
    }
    Ok(())
}

/// A point per setting, the default ringed.
fn draw_markers<DB: DrawingBackend, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    pts: &[Point],
    colour: RGBColor,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    chart.draw_series(
        pts.iter()
            .map(|p| Circle::new((p.0, p.1), 4, colour.filled())),
    )?;
    chart.draw_series(
        pts.iter()
            .filter(|p| p.2)
            .map(|p| Circle::new((p.0, p.1), 9, colour.stroke_width(2))),
    )?;
    Ok(())
}

/// The part of the segment `a`–`b` inside `x ∈ x_range`, `0 ≤ y ≤ y_max` (Liang–Barsky),
/// or `None` if none of it is.
fn clip_segment(
    a: Point,
    b: Point,
    (x_lo, x_hi): (f64, f64),
    y_max: f64,
) -> Option<[(f64, f64); 2]> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - x_lo),
        (dx, x_hi - a.0),
        (-dy, a.1),
        (dy, y_max - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    (t0 <= t1).then_some([
        (a.0 + t0 * dx, a.1 + t0 * dy),
        (a.0 + t1 * dx, a.1 + t1 * dy),
    ])
}

/// Rasterises SVG text to a PNG file, with the system's fonts (DejaVu Sans for
/// `sans-serif`: `bash scripts/fonts-setup.sh` installs it).
pub fn svg_to_png(svg: &str, path: &Path) -> Result<(), String> {
    let mut opt = resvg::usvg::Options::default();
    {
        let db = opt.fontdb_mut();
        db.load_system_fonts();
        db.set_sans_serif_family("DejaVu Sans");
    }
    if opt.fontdb.is_empty() {
        return Err("no system fonts: run scripts/fonts-setup.sh (fonts-dejavu-core)".into());
    }
    let tree = resvg::usvg::Tree::from_str(svg, &opt).map_err(|e| e.to_string())?;
    let size = tree.size().to_int_size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or("empty plot")?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    pixmap.save_png(path).map_err(|e| e.to_string())
}

/// Writes `pareto-FAMILY.svg` and `pareto-FAMILY.png` into `dir`.
pub fn write_pareto(dir: &Path, family: &str, rows: &[Row]) -> Result<(), String> {
    let svg = pareto_svg(family, rows)?;
    std::fs::write(dir.join(format!("pareto-{family}.svg")), &svg).map_err(|e| e.to_string())?;
    svg_to_png(&svg, &dir.join(format!("pareto-{family}.png")))
}
