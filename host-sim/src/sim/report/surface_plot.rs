//! The load against the limit surface, in normalised coordinates.

use super::*;

pub(super) const ELLIPSE_LABEL: &str = "Eq. 10 ellipse";
pub(super) const SURFACE_LABEL: &str = "limit surface";
pub(super) const SLIP_MARK_LABEL: &str = "slipping";

/// The upper end `L` of both axes of [`plot_surface`]: `max(1.2, 1.05 × the 99th
/// percentile of the runs' finite coordinates, 1.05 × the largest finite surface
/// coordinate)`, at most 10⁶ (always finite;
/// `host-sim/tests/report.rs::surface_axes_follow_the_99th_percentile_and_stay_finite`).
pub fn surface_axis_limit(runs: &[(&str, &[Sample])], surface: &[(f64, f64)]) -> f64 {
    let coords = runs
        .iter()
        .flat_map(|(_, s)| s.iter().filter_map(surface_point))
        .flat_map(|(x, y)| [x, y]);
    let p99 = quantile(coords, 0.99).unwrap_or(0.0);
    let surface_max = surface
        .iter()
        .flat_map(|&(x, y)| [x, y])
        .filter(|v| v.is_finite())
        .fold(0.0_f64, f64::max);
    1.2_f64
        .max(1.05 * p99)
        .max(1.05 * surface_max)
        .min(MAX_SURFACE_AXIS)
}

/// Plots the load of each run against the limit surface as an SVG at `path`.
///
/// Coordinates are normalised: x = `f_norm` (`f̃ = f_t/(μN)`), y = `|m_norm| / pitch`,
/// so the Eq. 10 ellipse is the unit quarter circle (drawn dashed). `surface` is the exact
/// limit surface as (x, y) points in the same coordinates (drawn solid). Each run's
/// trajectory is a thin line in its own colour (legend: the run's name); samples where
/// `slipping` is true are marked with red crosses. Samples with a non-finite coordinate
/// are skipped. Both axes span `[0, L]`, `L` from [`surface_axis_limit`]; whatever lies
/// outside is clipped. The legend sits right of the plot.
pub fn plot_surface(
    path: &Path,
    title: &str,
    runs: &[(&str, &[Sample])],
    surface: &[(f64, f64)],
) -> Result<(), ReportError> {
    let lim = surface_axis_limit(runs, surface);
    let legend_w = legend_width(
        [ELLIPSE_LABEL, SURFACE_LABEL, SLIP_MARK_LABEL]
            .into_iter()
            .chain(runs.iter().map(|(name, _)| *name)),
    );
    write_svg(path, (800, 800), legend_w, |root, legend_area| {
        let mut chart = ChartBuilder::on(root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..lim, 0.0..lim)?;
        chart
            .configure_mesh()
            .x_desc("f_norm = f_t / (μN)")
            .y_desc("|m_norm| / pitch,  m_norm = m_n / (μNa)")
            .draw()?;
        let mut legend = draw_surfaces(&mut chart, surface, lim)?;
        legend.extend(draw_trajectories(&mut chart, runs, lim)?);
        legend.extend(draw_slip_marks(&mut chart, runs, lim)?);
        draw_legend(legend_area, &legend)
    })
}

/// Whether `(x, y)` lies on the plot, both axes spanning `[0, lim]`.
fn inside(lim: f64, (x, y): (f64, f64)) -> bool {
    (0.0..=lim).contains(&x) && (0.0..=lim).contains(&y)
}

/// The Eq. 10 ellipse (the unit quarter circle, dashed) and the exact limit surface
/// `surface` (solid), cut to `[0, lim]`; their legend entries.
fn draw_surfaces(
    chart: &mut Chart<'_, '_>,
    surface: &[(f64, f64)],
    lim: f64,
) -> Result<Vec<(String, Swatch)>, ReportError> {
    let circle: Vec<(f64, f64)> = (0..=180)
        .map(|i| {
            let th = std::f64::consts::FRAC_PI_2 * f64::from(i) / 180.0;
            (th.cos(), th.sin())
        })
        .collect();
    let ellipse_style = ShapeStyle::from(&BLACK).stroke_width(2);
    chart.draw_series(std::iter::once(DashedPathElement::new(
        circle,
        8,
        6,
        ellipse_style,
    )))?;
    let surface_style = ShapeStyle::from(&BLACK).stroke_width(2);
    let surface_segments = segments(
        surface
            .iter()
            .map(|&p| (p.0.is_finite() && p.1.is_finite() && inside(lim, p)).then_some(p)),
    );
    chart.draw_series(
        surface_segments
            .into_iter()
            .map(|seg| PathElement::new(seg, surface_style)),
    )?;
    Ok(vec![
        (ELLIPSE_LABEL.into(), Swatch::Dashed(ellipse_style)),
        (SURFACE_LABEL.into(), Swatch::Line(surface_style)),
    ])
}

/// Each run's trajectory, a thin line in its colour, cut to `[0, lim]`; their legend
/// entries.
fn draw_trajectories(
    chart: &mut Chart<'_, '_>,
    runs: &[(&str, &[Sample])],
    lim: f64,
) -> Result<Vec<(String, Swatch)>, ReportError> {
    let mut legend = Vec::new();
    for (i, (name, samples)) in runs.iter().enumerate() {
        let style = ShapeStyle::from(&run_colour(i)).stroke_width(1);
        let shown = stride(samples, MAX_LINE_POINTS);
        let segs = segments(
            shown
                .iter()
                .map(|s| surface_point(s).filter(|&p| inside(lim, p))),
        );
        chart.draw_series(segs.into_iter().map(|seg| PathElement::new(seg, style)))?;
        legend.push(((*name).into(), Swatch::Line(style.stroke_width(2))));
    }
    Ok(legend)
}

/// Red crosses where the runs slip, within `[0, lim]`; their legend entry if any slips.
fn draw_slip_marks(
    chart: &mut Chart<'_, '_>,
    runs: &[(&str, &[Sample])],
    lim: f64,
) -> Result<Option<(String, Swatch)>, ReportError> {
    let slip_style = ShapeStyle::from(&SLIP_COLOUR).stroke_width(1);
    let mut any_slip = false;
    for (_, samples) in runs {
        let slipping: Vec<(f64, f64)> = samples
            .iter()
            .filter(|s| s.slipping)
            .filter_map(surface_point)
            .filter(|&p| inside(lim, p))
            .collect();
        any_slip |= !slipping.is_empty();
        chart.draw_series(
            stride(&slipping, MAX_SLIP_MARKERS)
                .into_iter()
                .map(|p| Cross::new(p, 4, slip_style)),
        )?;
    }
    Ok(any_slip.then(|| (SLIP_MARK_LABEL.into(), Swatch::Cross(slip_style))))
}
