//! `accuracy.svg`: error against each measured cost, log-log, one panel each.

use super::*;

pub(super) fn plot_err(e: f64) -> f64 {
    e.max(1e-16)
}

/// Draws `accuracy.svg`: the force error against each [`Cost`] the run measured
/// (host tick and start-up; with `--target` also the M4F's), log-log, one panel each, the
/// Pareto points circled, joined and numbered as in the Pareto table.
pub fn plot(path: &Path, results: &Results) -> Result<(), String> {
    let mut all = fronts(results);
    all.sort_by(|a, b| a.1.tick_ns.total_cmp(&b.1.tick_ns));
    let costs: Vec<Cost> = if has_target(results) {
        Cost::ALL.to_vec()
    } else {
        vec![Cost::HostTick, Cost::HostStartup]
    };
    let rows = costs.len().div_ceil(2) as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1400, 620 * rows)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let areas = root.split_evenly((rows as usize, 2));
        for (area, cost) in areas.iter().zip(costs) {
            panel(area, results, &all, cost)?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    std::fs::write(path, svg).map_err(|e| format!("{}: {e}", path.display()))
}

/// The x range of a log-scale panel: the data with a margin, widened to whole decades
/// when it spans less than one (a log axis inside one decade gets no labels).
pub(super) fn x_range(xmin: f64, xmax: f64) -> std::ops::Range<f64> {
    let (lo, hi) = (xmin / 1.6, xmax * 1.6);
    if hi / lo < 10.0 {
        10f64.powf(lo.log10().floor())..10f64.powf(hi.log10().ceil())
    } else {
        lo..hi
    }
}

/// One configuration in a panel: its number in the Pareto table, its cost (the x), its
/// force error (the y), and whether it is on this cost's front.
struct Point<'a> {
    number: usize,
    x: f64,
    err: f64,
    variant: &'a Variant,
    on_front: bool,
}

/// A log-log chart of the SVG backend.
type LogChart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;

/// One panel of [`plot`]: the force error of the configurations `all` against `cost`.
pub(super) fn panel(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    results: &Results,
    all: &[(Variant, Measured, Fronts)],
    cost: Cost,
) -> Result<(), String> {
    let pts: Vec<Point<'_>> = all
        .iter()
        .enumerate()
        .filter_map(|(i, (v, m, f))| {
            let x = cost.of(results, v, m)?;
            Some(Point {
                number: i + 1,
                x: x.max(1e-3),
                err: plot_err(m.error()),
                variant: v,
                on_front: f.on(cost),
            })
        })
        .collect();
    if pts.is_empty() {
        return Ok(());
    }
    let mut chart = log_chart(area, cost, &pts)?;
    draw_front(&mut chart, &pts)?;
    draw_modes(&mut chart, &pts)?;
    mark_front(&mut chart, &pts)?;
    chart
        .configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE.mix(0.9))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(())
}

/// The panel's axes: `cost` against the error, log-log, around the points `pts`.
fn log_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    cost: Cost,
    pts: &[Point<'_>],
) -> Result<LogChart<'a, 'b>, String> {
    let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.x), b.max(p.x))
    });
    let (ymin, ymax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
        (a.min(p.err), b.max(p.err))
    });
    let title = format!("force error against {}", cost.axis());
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(
            x_range(xmin, xmax).log_scale(),
            (ymin / 3.0..ymax * 3.0).log_scale(),
        )
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(cost.axis())
        .y_desc("worst relative error of N_req(s)")
        .x_label_formatter(&|x| {
            if *x >= 1e5 {
                format!("{x:.0e}")
            } else {
                format!("{x:.0}")
            }
        })
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(chart)
}

/// The colour of the Pareto front.
const FRONT_RED: RGBColor = RGBColor(214, 39, 40);

/// The Pareto front as a red line, with its legend entry.
fn draw_front(chart: &mut LogChart<'_, '_>, pts: &[Point<'_>]) -> Result<(), String> {
    let mut front: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| p.on_front)
        .map(|p| (p.x, p.err))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart
        .draw_series(std::iter::once(PathElement::new(
            front,
            ShapeStyle::from(&FRONT_RED).stroke_width(2),
        )))
        .map_err(|e| e.to_string())?
        .label("Pareto front")
        .legend(move |(x, y)| {
            PathElement::new(
                [(x, y), (x + 20, y)],
                ShapeStyle::from(&FRONT_RED).stroke_width(2),
            )
        });
    Ok(())
}

/// The points as dots in their mode's colour (ellipse, table, exact per tick), a legend
/// entry for each mode present.
fn draw_modes(chart: &mut LogChart<'_, '_>, pts: &[Point<'_>]) -> Result<(), String> {
    type Kind = (&'static str, RGBColor, fn(&Variant) -> bool);
    let kinds: [Kind; 3] = [
        ("ellipse", RGBColor(31, 119, 180), |v| {
            matches!(v.engine, Engine::Grid { table: false, .. })
        }),
        ("table", RGBColor(255, 127, 14), |v| {
            matches!(v.engine, Engine::Grid { table: true, .. })
        }),
        ("exact per tick", RGBColor(44, 160, 44), |v| {
            matches!(v.engine, Engine::Exact)
        }),
    ];
    for (name, colour, is) in kinds {
        if !pts.iter().any(|p| is(p.variant)) {
            continue;
        }
        let style = ShapeStyle::from(&colour).filled();
        chart
            .draw_series(
                pts.iter()
                    .filter(|p| is(p.variant))
                    .map(|p| Circle::new((p.x, p.err), 5, style)),
            )
            .map_err(|e| e.to_string())?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, style));
    }
    Ok(())
}

/// The Pareto points circled in red and numbered as in the Pareto table.
fn mark_front(chart: &mut LogChart<'_, '_>, pts: &[Point<'_>]) -> Result<(), String> {
    let ring = ShapeStyle::from(&FRONT_RED).stroke_width(2);
    chart
        .draw_series(
            pts.iter()
                .filter(|p| p.on_front)
                .map(|p| Circle::new((p.x, p.err), 9, ring)),
        )
        .map_err(|e| e.to_string())?;
    chart
        .draw_series(pts.iter().filter(|p| p.on_front).map(|p| {
            Text::new(
                format!("{}", p.number),
                (p.x * 1.08, p.err * 1.35),
                ("sans-serif", 13).into_font(),
            )
        }))
        .map_err(|e| e.to_string())?;
    Ok(())
}
