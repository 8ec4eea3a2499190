//! The normal force over time, the load, and each run's slip intervals.

use super::*;

/// The time intervals during which a run slips: from the first slipping sample to the
/// sample after the last one of each episode. Intervals closer than `merge_gap` merge.
pub(super) fn slip_intervals(samples: &[Sample], merge_gap: f64) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut start: Option<f64> = None;
    let mut last_t = f64::NAN;
    for s in samples.iter().filter(|s| s.t_s.is_finite()) {
        match (s.slipping, start) {
            (true, None) => start = Some(s.t_s),
            (false, Some(t0)) => {
                out.push((t0, s.t_s));
                start = None;
            }
            _ => {}
        }
        last_t = s.t_s;
    }
    if let Some(t0) = start {
        out.push((t0, last_t));
    }
    merge_intervals(&out, merge_gap)
}

/// Merges time intervals (in time order) closer than `merge_gap`.
pub(super) fn merge_intervals(out: &[(f64, f64)], merge_gap: f64) -> Vec<(f64, f64)> {
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(out.len());
    for &(t0, t1) in out {
        match merged.last_mut() {
            Some(prev) if t0 - prev.1 <= merge_gap => prev.1 = prev.1.max(t1),
            _ => merged.push((t0, t1)),
        }
    }
    merged
}

pub(super) const SLIP_LANE_LABEL: &str = "slipping (bars below, in the run's colour)";
pub(super) const LOAD_LABEL: &str = "tangential load (per contact)";
pub(super) const CLIPPED_SUFFIX: &str = " (clipped: ▲ leaves the top)";

/// Height of one slip lane below the force axes [px].
pub(super) const LANE_PX: u32 = 18;

/// Plots the applied normal force `n_true_n` over time `t_s` for each run as an SVG at
/// `path` (one line per run, legend by run name). The first run's tangential load `ft_n`
/// is drawn on the same axes in grey, dashed ("tangential load (per contact)"). Non-finite
/// values are skipped (they break the line). The legend sits right of the plot.
///
/// Readable with many runs: the force axis is scaled to the runs that never slipped (and
/// the load), so a baseline that loses the object and swings to `N_max` does not flatten
/// the others; its line is cut where it leaves the top, marked there with a ▲, and its
/// legend entry says so (all runs set the scale when every run slipped). The intervals in
/// which a run slips are bars in that run's colour in a lane of its own below the force
/// axes, on the same time axis, so nothing is drawn over the lines.
pub fn plot_force(path: &Path, title: &str, runs: &[(&str, &[Sample])]) -> Result<(), ReportError> {
    let slips: Vec<Vec<(f64, f64)>> = runs.iter().map(|(_, s)| slip_intervals(s, 0.0)).collect();
    plot_force_with_slips(path, title, runs, &slips)
}

/// Points of a line in data coordinates.
pub(super) type Polyline = Vec<(f64, f64)>;

/// The parts of the polyline `points` at or below `y_max`, the crossings interpolated, and
/// the points where it leaves the top.
pub(super) fn clip_above(points: &[(f64, f64)], y_max: f64) -> (Vec<Polyline>, Polyline) {
    let mut parts = Vec::new();
    let mut exits = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    let cross = |a: (f64, f64), b: (f64, f64)| {
        let t = (y_max - a.1) / (b.1 - a.1);
        (a.0 + t * (b.0 - a.0), y_max)
    };
    for (i, &p) in points.iter().enumerate() {
        let prev = i.checked_sub(1).map(|j| points[j]);
        match (prev, p.1 <= y_max) {
            (Some(q), true) if q.1 > y_max => cur.extend([cross(q, p), p]),
            (_, true) => cur.push(p),
            (Some(q), false) if q.1 <= y_max => {
                let c = cross(q, p);
                cur.push(c);
                exits.push(c);
                parts.push(std::mem::take(&mut cur));
            }
            (None, false) => exits.push((p.0, y_max)),
            _ => {}
        }
    }
    if !cur.is_empty() {
        parts.push(cur);
    }
    (parts, exits)
}

/// [`plot_force`] with each run's slip intervals given (`slips[i]` for `runs[i]`, as
/// `(start, end)` times \[s\]) instead of found in its samples: for samples decimated for
/// plotting (`sim::trace`), whose intervals were taken from every tick.
pub fn plot_force_with_slips(
    path: &Path,
    title: &str,
    runs: &[(&str, &[Sample])],
    slips: &[Vec<(f64, f64)>],
) -> Result<(), ReportError> {
    let times = time_range(runs);
    let slipped: Vec<bool> = (0..runs.len())
        .map(|i| slips.get(i).is_some_and(|v| !v.is_empty()))
        .collect();
    let (y_min, y_max) = force_range(runs, &slipped);
    let lanes: Vec<usize> = (0..runs.len()).filter(|&i| slipped[i]).collect();
    let labels = run_labels(runs, y_max);
    let explained = bands::explained_run(runs).map(|i| (runs[i].0, bands::held(runs[i].1)));
    let band_labels = explained.as_ref().map_or_else(Vec::new, |(name, s)| {
        bands::band_labels(name, s, (y_min, y_max))
    });
    let legend_w = legend_width(
        [SLIP_LANE_LABEL, LOAD_LABEL]
            .into_iter()
            .chain(labels.iter().map(String::as_str))
            .chain(band_labels.iter().map(|(_, l)| l.as_str())),
    );
    let lanes_px = if lanes.is_empty() {
        0
    } else {
        LANE_PX * lanes.len() as u32 + 50
    };
    write_svg(
        path,
        (1000, 600 + lanes_px),
        legend_w,
        |root, legend_area| {
            let (top, bottom) = root.split_vertically(600);
            let mut chart = ChartBuilder::on(&top)
                .caption(title, ("sans-serif", 22))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(60)
                .build_cartesian_2d(times.0..times.1, y_min..y_max)?;
            chart
                .configure_mesh()
                .x_desc("time [s]")
                .y_desc("force [N]")
                .draw()?;
            let band_legend = match &explained {
                Some((_, s)) => bands::draw_bands(&mut chart, s, &band_labels, (y_min, y_max))?,
                None => Vec::new(),
            };
            let load_legend = match runs.first() {
                Some((_, samples)) => Some(draw_load(&mut chart, samples)?),
                None => None,
            };
            let mut legend = draw_runs(&mut chart, runs, &labels, y_max)?;
            legend.extend(load_legend);
            legend.extend(band_legend);
            if !lanes.is_empty() {
                draw_slip_lanes(&bottom, runs, slips, &lanes, times)?;
                let first = run_colour(lanes[0]).filled();
                legend.push((SLIP_LANE_LABEL.into(), Swatch::Shade(first)));
            }
            draw_legend(legend_area, &legend)
        },
    )
}

/// The time axis [s]: the runs' finite times, at least one second wide if they span none.
fn time_range(runs: &[(&str, &[Sample])]) -> (f64, f64) {
    let finite_t = || {
        runs.iter()
            .flat_map(|(_, s)| s.iter().map(|s| s.t_s))
            .filter(|t| t.is_finite())
    };
    let t_min = finite_t().fold(f64::INFINITY, f64::min);
    let t_max = finite_t().fold(f64::NEG_INFINITY, f64::max);
    if t_min.is_finite() && t_max > t_min {
        (t_min, t_max)
    } else if t_min.is_finite() {
        (t_min, t_min + 1.0)
    } else {
        (0.0, 1.0)
    }
}

/// The force axis [N]: a margin beyond the normal forces of the runs that never slipped (of
/// all runs when every run `slipped`) and the first run's load, and beyond zero.
fn force_range(runs: &[(&str, &[Sample])], slipped: &[bool]) -> (f64, f64) {
    let any_held = slipped.iter().any(|s| !s);
    let forces = runs
        .iter()
        .enumerate()
        .filter(|(i, _)| !any_held || !slipped[*i])
        .flat_map(|(_, (_, s))| s.iter().map(|s| s.n_true_n))
        .chain(
            runs.first()
                .into_iter()
                .flat_map(|(_, s)| s.iter().map(|s| s.ft_n)),
        )
        .filter(|f| f.is_finite());
    let (f_min, f_max) = forces.fold((0.0_f64, 0.0_f64), |(lo, hi), f| (lo.min(f), hi.max(f)));
    let y_max = if f_max > 0.0 { 1.1 * f_max } else { 1.0 };
    (1.1 * f_min, y_max)
}

/// Each run's legend label, which says so when its force leaves the top `y_max` [N].
fn run_labels(runs: &[(&str, &[Sample])], y_max: f64) -> Vec<String> {
    runs.iter()
        .map(|(name, s)| {
            let clipped = s
                .iter()
                .any(|s| s.n_true_n.is_finite() && s.n_true_n > y_max);
            format!("{name}{}", if clipped { CLIPPED_SUFFIX } else { "" })
        })
        .collect()
}

/// The tangential load of `samples`, grey and dashed; its legend entry.
fn draw_load(
    chart: &mut Chart<'_, '_>,
    samples: &[Sample],
) -> Result<(String, Swatch), ReportError> {
    let style = ShapeStyle::from(&LOAD_GREY).stroke_width(1);
    let segs = segments(
        samples
            .iter()
            .map(|s| (s.t_s.is_finite() && s.ft_n.is_finite()).then_some((s.t_s, s.ft_n))),
    );
    chart.draw_series(
        segs.into_iter().map(|seg| {
            DashedPathElement::new(decimate_min_max(&seg, MAX_LINE_POINTS), 6, 4, style)
        }),
    )?;
    Ok((LOAD_LABEL.into(), Swatch::Dashed(style)))
}

/// Each run's normal force in its colour, cut at `y_max` [N] with a ▲ where it leaves the
/// top; their legend entries (`labels`).
fn draw_runs(
    chart: &mut Chart<'_, '_>,
    runs: &[(&str, &[Sample])],
    labels: &[String],
    y_max: f64,
) -> Result<Vec<(String, Swatch)>, ReportError> {
    let mut legend = Vec::new();
    for (i, (_, samples)) in runs.iter().enumerate() {
        let colour = run_colour(i);
        let style = ShapeStyle::from(&colour).stroke_width(2);
        let segs =
            segments(samples.iter().map(|s| {
                (s.t_s.is_finite() && s.n_true_n.is_finite()).then_some((s.t_s, s.n_true_n))
            }));
        let mut exits = Vec::new();
        for seg in segs {
            let (parts, out) = clip_above(&decimate_min_max(&seg, MAX_LINE_POINTS), y_max);
            chart.draw_series(parts.into_iter().map(|p| PathElement::new(p, style)))?;
            exits.extend(out);
        }
        chart.draw_series(
            stride(&exits, MAX_SLIP_MARKERS)
                .into_iter()
                .map(|(t, y)| TriangleMarker::new((t, y), 6, colour.filled())),
        )?;
        legend.push((labels[i].clone(), Swatch::Line(style)));
    }
    Ok(legend)
}

/// The slip lanes in `area`: one row per run that slipped (`lanes`, indices into `runs`),
/// bars over its slip intervals (`slips`) on the time axis `(t_min, t_max)` [s].
fn draw_slip_lanes(
    area: &Area<'_>,
    runs: &[(&str, &[Sample])],
    slips: &[Vec<(f64, f64)>],
    lanes: &[usize],
    (t_min, t_max): (f64, f64),
) -> Result<(), ReportError> {
    let n = lanes.len();
    let mut lane_chart = ChartBuilder::on(area)
        .margin_left(15)
        .margin_right(15)
        .margin_bottom(10)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .build_cartesian_2d(t_min..t_max, 0.0..n as f64)?;
    lane_chart
        .configure_mesh()
        .disable_y_mesh()
        .y_labels(0)
        .x_desc("time [s]; bars: the intervals in which each run slips")
        .draw()?;
    let merge_gap = (t_max - t_min) / 1000.0;
    for (row, &i) in lanes.iter().enumerate() {
        let y = (n - row) as f64 - 0.5;
        let bar = run_colour(i).filled();
        let intervals = merge_intervals(&slips[i], merge_gap);
        lane_chart.draw_series(intervals.into_iter().map(|(t0, t1)| {
            Rectangle::new([(t0.max(t_min), y - 0.3), (t1.min(t_max), y + 0.3)], bar)
        }))?;
        let font = TextStyle::from(("sans-serif", 12).into_font())
            .pos(Pos::new(HPos::Right, VPos::Center));
        lane_chart.draw_series(std::iter::once(
            EmptyElement::at((t_min, y)) + Text::new(runs[i].0.to_string(), (-6, 0), font),
        ))?;
    }
    Ok(())
}
