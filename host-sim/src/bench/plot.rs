//! The Pareto plot of one family: drop rate [%] against mean force over the oracle's
//! [-], one curve per controller through its knob values, its default ringed. Written as
//! SVG (plotters) and as PNG (that SVG rasterised by resvg with a system font).

use super::sweep::Row;
use crate::sim::report::RUN_COLOURS;
use plotters::prelude::*;
use std::path::Path;

/// Width and height of the plots [px].
const SIZE: (u32, u32) = (1000, 650);

/// The SVG text of the Pareto plot of `family`'s rows.
pub fn pareto_svg(family: &str, rows: &[Row]) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        draw(&root, family, rows).map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    family: &str,
    rows: &[Row],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let x_max = rows
        .iter()
        .map(|r| r.force_over_oracle)
        .filter(|x| x.is_finite())
        .fold(1.0_f64, f64::max)
        * 1.1;
    let x_min = rows
        .iter()
        .map(|r| r.force_over_oracle)
        .filter(|x| x.is_finite() && *x > 0.0)
        .fold(1.0_f64, f64::min)
        * 0.9;
    let y_max = rows
        .iter()
        .map(|r| 100.0 * r.drop_rate)
        .fold(5.0_f64, f64::max)
        * 1.08;
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("{family}: drop rate against force (ringed: each controller's default)"),
            ("sans-serif", 24),
        )
        .margin(20)
        .x_label_area_size(50)
        .y_label_area_size(65)
        .build_cartesian_2d((x_min..x_max).log_scale(), 0.0..y_max)?;
    chart
        .configure_mesh()
        .x_desc("mean normal force / oracle's mean force [-] (log scale)")
        .y_desc("trials dropped [%]")
        .label_style(("sans-serif", 16))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    let mut controllers: Vec<&str> = Vec::new();
    for r in rows {
        if !controllers.contains(&r.controller.as_str()) {
            controllers.push(&r.controller);
        }
    }
    for (i, c) in controllers.iter().enumerate() {
        let colour = RUN_COLOURS[i % RUN_COLOURS.len()];
        let mut pts: Vec<(f64, f64, bool)> = rows
            .iter()
            .filter(|r| r.controller == *c && r.force_over_oracle.is_finite())
            .map(|r| (r.force_over_oracle, 100.0 * r.drop_rate, r.default))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let style = ShapeStyle::from(&colour).stroke_width(2);
        chart
            .draw_series(std::iter::once(PathElement::new(
                pts.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>(),
                style,
            )))?
            .label(*c)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        chart.draw_series(
            pts.iter()
                .map(|p| Circle::new((p.0, p.1), 4, colour.filled())),
        )?;
        chart.draw_series(
            pts.iter()
                .filter(|p| p.2)
                .map(|p| Circle::new((p.0, p.1), 9, colour.stroke_width(2))),
        )?;
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
