//! What `host-sim simulate` writes: the per-tick time series as CSV, two SVG plots, a
//! JSON summary of the runs, and text tables for the terminal.
//!
//! - [`write_csv`]: one row per [`Sample`], header = the field names of [`Sample`].
//! - [`plot_surface`]: the load in normalised coordinates against the limit surface.
//! - [`plot_force`]: the applied normal force over time, slip intervals as bars below.
//! - [`write_summary_json`]: `{"runs": [...]}` of [`RunSummary`].
//! - [`summary_table`] and [`comparison_table`]: fixed-width tables for the terminal.
//!
//! The plots are drawn with `plotters`' SVG backend without any font feature: text (title,
//! axis labels, legend) is written as SVG `<text>` elements with a generic `font-family`
//! that the viewer renders; plotters only estimates text extents for the layout.

use super::record::{RunSummary, Sample};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::Serialize;
use std::fmt;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

/// The CSV header [`write_csv`] writes: the field names of [`Sample`], in declaration order.
pub const SAMPLE_CSV_FIELDS: [&str; 16] = [
    "t_s",
    "ft_n",
    "mn_nm",
    "ft_meas_n",
    "mn_meas_nm",
    "n_cmd_n",
    "n_true_n",
    "a_true_m",
    "f_norm",
    "m_norm",
    "pitch",
    "utilisation",
    "slipping",
    "slip_distance_m",
    "slip_rotation_rad",
    "status",
];

/// Most line vertices drawn per run and curve (longer series are decimated for the plot
/// only; the CSV keeps every sample).
const MAX_LINE_POINTS: usize = 4000;
/// Most slip markers drawn per run in the surface plot.
const MAX_SLIP_MARKERS: usize = 2000;
/// Upper bound of the surface plot's axes, whatever the data.
const MAX_SURFACE_AXIS: f64 = 1.0e6;

/// Run colours (the "tab10" palette without its red and grey, which mark slip and the
/// tangential load).
pub(crate) const RUN_COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
const SLIP_COLOUR: RGBColor = RGBColor(214, 39, 40);
const LOAD_GREY: RGBColor = RGBColor(127, 127, 127);

fn run_colour(i: usize) -> RGBColor {
    RUN_COLOURS[i % RUN_COLOURS.len()]
}

/// A failure to write a report file.
#[derive(Debug)]
pub enum ReportError {
    /// Creating or writing a file failed.
    Io(io::Error),
    /// `plotters` failed to draw (its `DrawingAreaErrorKind`, as text).
    Plot(String),
}

impl fmt::Display for ReportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ReportError::Io(e) => write!(f, "report I/O error: {e}"),
            ReportError::Plot(e) => write!(f, "plotting error: {e}"),
        }
    }
}

impl std::error::Error for ReportError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            ReportError::Io(e) => Some(e),
            ReportError::Plot(_) => None,
        }
    }
}

impl From<io::Error> for ReportError {
    fn from(e: io::Error) -> Self {
        ReportError::Io(e)
    }
}

impl<E: std::error::Error + Send + Sync> From<DrawingAreaErrorKind<E>> for ReportError {
    fn from(e: DrawingAreaErrorKind<E>) -> Self {
        ReportError::Plot(e.to_string())
    }
}

// ---------------------------------------------------------------------------------------
// CSV and JSON
// ---------------------------------------------------------------------------------------

/// Writes `samples` as a CSV time series to `path`: a header row with the field names of
/// [`Sample`] (the units are in the names, see [`SAMPLE_CSV_FIELDS`]), then one row per
/// sample. Floats are printed in their shortest round-trip form (`NaN`, `inf`, `-inf` for
/// the non-finite ones), `slipping` as `true`/`false`. An empty `samples` still gets the
/// header.
pub fn write_csv(path: &Path, samples: &[Sample]) -> io::Result<()> {
    let mut w = csv::Writer::from_writer(BufWriter::new(File::create(path)?));
    if samples.is_empty() {
        w.write_record(SAMPLE_CSV_FIELDS)?;
    }
    for s in samples {
        w.serialize(s)?;
    }
    w.flush()
}

#[derive(Serialize)]
struct SummaryFile<'a> {
    runs: &'a [RunSummary],
}

/// Writes `{"runs": [...]}` with every [`RunSummary`] as pretty-printed JSON to `path`.
/// Non-finite floats become `null` (JSON has no NaN).
pub fn write_summary_json(path: &Path, runs: &[RunSummary]) -> io::Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    serde_json::to_writer_pretty(&mut w, &SummaryFile { runs })?;
    w.write_all(b"\n")?;
    w.flush()
}

// ---------------------------------------------------------------------------------------
// Plots
// ---------------------------------------------------------------------------------------

/// The sample's load in the surface plot's coordinates: `(f̃, |m̃| / pitch)`, or `None`
/// if either is not finite.
fn surface_point(s: &Sample) -> Option<(f64, f64)> {
    let x = s.f_norm;
    let y = (s.m_norm / s.pitch).abs();
    (x.is_finite() && y.is_finite()).then_some((x, y))
}

/// The `q`-quantile (0..=1, nearest rank) of the finite values of `values`.
fn quantile(values: impl Iterator<Item = f64>, q: f64) -> Option<f64> {
    let mut v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let rank = (q * v.len() as f64).ceil() as usize;
    Some(v[rank.clamp(1, v.len()) - 1])
}

/// Every `k`-th element so that at most `max` remain (the last one always kept).
fn stride<T: Copy>(v: &[T], max: usize) -> Vec<T> {
    if v.len() <= max || max < 2 {
        return v.to_vec();
    }
    let k = v.len().div_ceil(max - 1);
    let mut out: Vec<T> = v.iter().step_by(k).copied().collect();
    if (v.len() - 1) % k != 0 {
        out.push(v[v.len() - 1]);
    }
    out
}

/// Decimates a time series for drawing: per bucket of `k` points, keeps the lowest and
/// the highest point (in time order), so peaks survive.
fn decimate_min_max(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
    if points.len() <= max || max < 4 {
        return points.to_vec();
    }
    let k = points.len().div_ceil(max / 2);
    let mut out = Vec::with_capacity(max + 2);
    for chunk in points.chunks(k) {
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[lo].1 {
                lo = i;
            }
            if p.1 > chunk[hi].1 {
                hi = i;
            }
        }
        out.push(chunk[lo.min(hi)]);
        if lo != hi {
            out.push(chunk[lo.max(hi)]);
        }
    }
    out
}

/// Splits a sequence of optional points into the runs of consecutive `Some`s.
fn segments(points: impl Iterator<Item = Option<(f64, f64)>>) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    let mut cur = Vec::new();
    for p in points {
        match p {
            Some(p) => cur.push(p),
            None if !cur.is_empty() => out.push(std::mem::take(&mut cur)),
            None => {}
        }
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

/// The area one plot is drawn on.
type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// Renders into an SVG string, then writes it to `path` (so that file errors come back as
/// [`ReportError::Io`] and drawing errors as [`ReportError::Plot`]). The canvas is
/// `plot_size` plus a legend panel of `legend_w` pixels on the right; `draw` gets the plot
/// area and the legend area.
fn write_svg(
    path: &Path,
    plot_size: (u32, u32),
    legend_w: u32,
    draw: impl FnOnce(&Area<'_>, &Area<'_>) -> Result<(), ReportError>,
) -> Result<(), ReportError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (plot_size.0 + legend_w, plot_size.1))
            .into_drawing_area();
        root.fill(&WHITE)?;
        let (plot, legend) = root.split_horizontally(plot_size.0);
        draw(&plot, &legend)?;
        root.present()?;
    }
    std::fs::write(path, svg)?;
    Ok(())
}

/// How a legend entry shows its series.
#[derive(Clone, Copy)]
enum Swatch {
    Line(ShapeStyle),
    Dashed(ShapeStyle),
    Cross(ShapeStyle),
    Shade(ShapeStyle),
}

/// Legend font size [px].
const LEGEND_FONT: u32 = 15;
/// Height of one legend row [px].
const LEGEND_ROW: i32 = 22;
/// Top of the legend (level with the top of the plotting area) [px].
const LEGEND_TOP: i32 = 45;

/// Width [px] of the legend panel for these labels (generous: the SVG viewer's font
/// decides the real width).
fn legend_width<'a>(labels: impl Iterator<Item = &'a str>) -> u32 {
    let chars = labels.map(|l| l.chars().count()).max().unwrap_or(0) as u32;
    (chars * 7 + 60).clamp(140, 480)
}

/// Draws the legend: one row per entry, a swatch and its label, in a framed box.
fn draw_legend(area: &Area<'_>, entries: &[(String, Swatch)]) -> Result<(), ReportError> {
    if entries.is_empty() {
        return Ok(());
    }
    let right = area.dim_in_pixel().0 as i32 - 10;
    let bottom = LEGEND_TOP + LEGEND_ROW * entries.len() as i32 + 6;
    area.draw(&Rectangle::new(
        [(0, LEGEND_TOP - 8), (right, bottom)],
        ShapeStyle::from(&BLACK).stroke_width(1),
    ))?;
    let font = TextStyle::from(("sans-serif", LEGEND_FONT).into_font())
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (i, (label, swatch)) in entries.iter().enumerate() {
        let y = LEGEND_TOP + LEGEND_ROW * i as i32 + LEGEND_ROW / 2 - 4;
        let (x0, x1) = (10, 34);
        match *swatch {
            Swatch::Line(style) => area.draw(&PathElement::new([(x0, y), (x1, y)], style))?,
            Swatch::Dashed(style) => {
                area.draw(&DashedPathElement::new([(x0, y), (x1, y)], 5, 3, style))?
            }
            Swatch::Cross(style) => area.draw(&Cross::new(((x0 + x1) / 2, y), 4, style))?,
            Swatch::Shade(style) => {
                area.draw(&Rectangle::new([(x0, y - 6), (x1, y + 6)], style))?
            }
        }
        area.draw(&Text::new(label.clone(), (x1 + 8, y), font.clone()))?;
    }
    Ok(())
}

const ELLIPSE_LABEL: &str = "Eq. 10 ellipse";
const SURFACE_LABEL: &str = "limit surface";
const SLIP_MARK_LABEL: &str = "slipping";

/// The upper end `L` of both axes of [`plot_surface`]: `max(1.2, 1.05 × the 99th
/// percentile of the runs' finite coordinates, 1.05 × the largest finite surface
/// coordinate)`, at most 10⁶ (always finite).
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
    let inside = |(x, y): (f64, f64)| (0.0..=lim).contains(&x) && (0.0..=lim).contains(&y);

    let legend_w = legend_width(
        [ELLIPSE_LABEL, SURFACE_LABEL, SLIP_MARK_LABEL]
            .into_iter()
            .chain(runs.iter().map(|(name, _)| *name)),
    );
    write_svg(path, (800, 800), legend_w, |root, legend_area| {
        let mut legend: Vec<(String, Swatch)> = Vec::new();
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
        legend.push((ELLIPSE_LABEL.into(), Swatch::Dashed(ellipse_style)));

        let surface_style = ShapeStyle::from(&BLACK).stroke_width(2);
        let surface_segments = segments(
            surface
                .iter()
                .map(|&p| (p.0.is_finite() && p.1.is_finite() && inside(p)).then_some(p)),
        );
        chart.draw_series(
            surface_segments
                .into_iter()
                .map(|seg| PathElement::new(seg, surface_style)),
        )?;
        legend.push((SURFACE_LABEL.into(), Swatch::Line(surface_style)));

        for (i, (name, samples)) in runs.iter().enumerate() {
            let style = ShapeStyle::from(&run_colour(i)).stroke_width(1);
            let shown = stride(samples, MAX_LINE_POINTS);
            let segs = segments(
                shown
                    .iter()
                    .map(|s| surface_point(s).filter(|&p| inside(p))),
            );
            chart.draw_series(segs.into_iter().map(|seg| PathElement::new(seg, style)))?;
            legend.push(((*name).into(), Swatch::Line(style.stroke_width(2))));
        }

        let slip_style = ShapeStyle::from(&SLIP_COLOUR).stroke_width(1);
        let mut any_slip = false;
        for (_, samples) in runs {
            let slipping: Vec<(f64, f64)> = samples
                .iter()
                .filter(|s| s.slipping)
                .filter_map(surface_point)
                .filter(|&p| inside(p))
                .collect();
            any_slip |= !slipping.is_empty();
            chart.draw_series(
                stride(&slipping, MAX_SLIP_MARKERS)
                    .into_iter()
                    .map(|p| Cross::new(p, 4, slip_style)),
            )?;
        }
        if any_slip {
            legend.push((SLIP_MARK_LABEL.into(), Swatch::Cross(slip_style)));
        }
        draw_legend(legend_area, &legend)
    })
}

/// The time intervals during which a run slips: from the first slipping sample to the
/// sample after the last one of each episode. Intervals closer than `merge_gap` merge.
fn slip_intervals(samples: &[Sample], merge_gap: f64) -> Vec<(f64, f64)> {
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
fn merge_intervals(out: &[(f64, f64)], merge_gap: f64) -> Vec<(f64, f64)> {
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(out.len());
    for &(t0, t1) in out {
        match merged.last_mut() {
            Some(prev) if t0 - prev.1 <= merge_gap => prev.1 = prev.1.max(t1),
            _ => merged.push((t0, t1)),
        }
    }
    merged
}

const SLIP_LANE_LABEL: &str = "slipping (bars below, in the run's colour)";
const LOAD_LABEL: &str = "tangential load (per contact)";
const CLIPPED_SUFFIX: &str = " (clipped: ▲ leaves the top)";

/// Height of one slip lane below the force axes [px].
const LANE_PX: u32 = 18;

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
type Polyline = Vec<(f64, f64)>;

/// The parts of the polyline `points` at or below `y_max`, the crossings interpolated, and
/// the points where it leaves the top.
fn clip_above(points: &[(f64, f64)], y_max: f64) -> (Vec<Polyline>, Polyline) {
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
/// `(start, end)` times [s]) instead of found in its samples: for samples decimated for
/// plotting (`sim::trace`), whose intervals were taken from every tick.
pub fn plot_force_with_slips(
    path: &Path,
    title: &str,
    runs: &[(&str, &[Sample])],
    slips: &[Vec<(f64, f64)>],
) -> Result<(), ReportError> {
    let finite_t = || {
        runs.iter()
            .flat_map(|(_, s)| s.iter().map(|s| s.t_s))
            .filter(|t| t.is_finite())
    };
    let t_min = finite_t().fold(f64::INFINITY, f64::min);
    let t_max = finite_t().fold(f64::NEG_INFINITY, f64::max);
    let (t_min, t_max) = if t_min.is_finite() && t_max > t_min {
        (t_min, t_max)
    } else if t_min.is_finite() {
        (t_min, t_min + 1.0)
    } else {
        (0.0, 1.0)
    };

    let slipped = |i: usize| slips.get(i).is_some_and(|v| !v.is_empty());
    let any_held = (0..runs.len()).any(|i| !slipped(i));
    let forces = runs
        .iter()
        .enumerate()
        .filter(|(i, _)| !any_held || !slipped(*i))
        .flat_map(|(_, (_, s))| s.iter().map(|s| s.n_true_n))
        .chain(
            runs.first()
                .into_iter()
                .flat_map(|(_, s)| s.iter().map(|s| s.ft_n)),
        )
        .filter(|f| f.is_finite());
    let (f_min, f_max) = forces.fold((0.0_f64, 0.0_f64), |(lo, hi), f| (lo.min(f), hi.max(f)));
    let y_max = if f_max > 0.0 { 1.1 * f_max } else { 1.0 };
    let y_min = 1.1 * f_min;

    let lanes: Vec<usize> = (0..runs.len()).filter(|&i| slipped(i)).collect();
    let clipped: Vec<bool> = runs
        .iter()
        .map(|(_, s)| {
            s.iter()
                .any(|s| s.n_true_n.is_finite() && s.n_true_n > y_max)
        })
        .collect();
    let labels: Vec<String> = runs
        .iter()
        .zip(&clipped)
        .map(|((name, _), &c)| format!("{name}{}", if c { CLIPPED_SUFFIX } else { "" }))
        .collect();
    let legend_w = legend_width(
        [SLIP_LANE_LABEL, LOAD_LABEL]
            .into_iter()
            .chain(labels.iter().map(String::as_str)),
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
            let mut legend: Vec<(String, Swatch)> = Vec::new();
            let (top, bottom) = root.split_vertically(600);
            let mut chart = ChartBuilder::on(&top)
                .caption(title, ("sans-serif", 22))
                .margin(15)
                .x_label_area_size(45)
                .y_label_area_size(60)
                .build_cartesian_2d(t_min..t_max, y_min..y_max)?;
            chart
                .configure_mesh()
                .x_desc("time [s]")
                .y_desc("force [N]")
                .draw()?;

            let mut load_legend = None;
            if let Some((_, samples)) = runs.first() {
                let style = ShapeStyle::from(&LOAD_GREY).stroke_width(1);
                let segs =
                    segments(samples.iter().map(|s| {
                        (s.t_s.is_finite() && s.ft_n.is_finite()).then_some((s.t_s, s.ft_n))
                    }));
                chart.draw_series(segs.into_iter().map(|seg| {
                    DashedPathElement::new(decimate_min_max(&seg, MAX_LINE_POINTS), 6, 4, style)
                }))?;
                load_legend = Some((LOAD_LABEL.into(), Swatch::Dashed(style)));
            }

            for (i, (_, samples)) in runs.iter().enumerate() {
                let colour = run_colour(i);
                let style = ShapeStyle::from(&colour).stroke_width(2);
                let segs = segments(samples.iter().map(|s| {
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
            legend.extend(load_legend);

            // The slip lanes: one row per run that slipped, bars over its slip intervals.
            if !lanes.is_empty() {
                let n = lanes.len();
                let names: Vec<String> = lanes.iter().map(|&i| runs[i].0.to_string()).collect();
                let mut lane_chart = ChartBuilder::on(&bottom)
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
                        EmptyElement::at((t_min, y)) + Text::new(names[row].clone(), (-6, 0), font),
                    ))?;
                }
                let first = run_colour(lanes[0]).filled();
                legend.push((SLIP_LANE_LABEL.into(), Swatch::Shade(first)));
            }
            draw_legend(legend_area, &legend)
        },
    )
}

// ---------------------------------------------------------------------------------------
// Tables
// ---------------------------------------------------------------------------------------

/// The verdict on one run: for a scene that should hold (`expected_slip == false`),
/// `held` if it had no slip event, else `SLIPPED`; for an overload scene, `overload
/// (slipped as expected)` if it slipped, else `held (unexpected)`.
pub fn verdict(run: &RunSummary) -> &'static str {
    match (run.expected_slip, run.slip_events > 0) {
        (false, false) => "held",
        (false, true) => "SLIPPED",
        (true, true) => "overload (slipped as expected)",
        (true, false) => "held (unexpected)",
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Align {
    Left,
    Right,
}

/// Lays out a fixed-width table: a header, a rule, the rows; columns two spaces apart.
fn render_table(headers: &[&str], align: &[Align], rows: &[Vec<String>]) -> String {
    let widths: Vec<usize> = headers
        .iter()
        .enumerate()
        .map(|(c, h)| {
            rows.iter()
                .map(|r| r[c].chars().count())
                .chain(std::iter::once(h.chars().count()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |cells: &[&str]| -> String {
        let mut s = String::new();
        for (c, cell) in cells.iter().enumerate() {
            if c > 0 {
                s.push_str("  ");
            }
            let w = widths[c];
            match align[c] {
                Align::Left => s.push_str(&format!("{cell:<w$}")),
                Align::Right => s.push_str(&format!("{cell:>w$}")),
            }
        }
        s.truncate(s.trim_end().len());
        s.push('\n');
        s
    };
    let mut out = line(headers);
    let total: usize = widths.iter().sum::<usize>() + 2 * widths.len().saturating_sub(1);
    out.push_str(&"-".repeat(total));
    out.push('\n');
    for r in rows {
        let cells: Vec<&str> = r.iter().map(String::as_str).collect();
        out.push_str(&line(&cells));
    }
    out
}

/// A fixed-width text table of the runs, one row each, in input order: scene, controller,
/// dropped (yes/no), slip events, slip distance [mm], slip rotation [mrad], mean N [N],
/// peak N [N], max utilisation, expected slip (yes/no) and the [`verdict`].
pub fn summary_table(runs: &[RunSummary]) -> String {
    use Align::{Left as L, Right as R};
    let headers = [
        "scene",
        "controller",
        "dropped",
        "slip events",
        "slip distance [mm]",
        "slip rotation [mrad]",
        "mean N [N]",
        "peak N [N]",
        "max utilisation",
        "expected slip",
        "verdict",
    ];
    let align = [L, L, L, R, R, R, R, R, R, L, L];
    let rows: Vec<Vec<String>> = runs
        .iter()
        .map(|r| {
            vec![
                r.scene.clone(),
                r.controller.clone(),
                if r.dropped { "yes" } else { "no" }.to_string(),
                r.slip_events.to_string(),
                format!("{:.3}", r.slip_distance_m * 1e3),
                format!("{:.3}", r.slip_rotation_rad * 1e3),
                format!("{:.3}", r.mean_normal_force_n),
                format!("{:.3}", r.peak_normal_force_n),
                format!("{:.3}", r.max_utilisation),
                if r.expected_slip { "yes" } else { "no" }.to_string(),
                verdict(r).to_string(),
            ]
        })
        .collect();
    render_table(&headers, &align, &rows)
}

/// The distinct names, in order of first appearance.
fn first_appearance<'a>(names: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let mut out: Vec<&str> = Vec::new();
    for n in names {
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

/// Whether a controller counts as softgrip (its name starts with `softgrip`) rather than a
/// baseline.
fn is_softgrip(controller: &str) -> bool {
    controller.starts_with("softgrip")
}

fn held(r: &RunSummary) -> bool {
    r.slip_events == 0
}

/// A comparison of the controllers over all scenes (for `simulate --controller all`).
///
/// First a table with one row per controller (in order of first appearance): scenes held
/// of those not expected to slip (e.g. `5/6`), total slip events, total slip distance
/// [mm] (both totals over every scene, overloads included), mean of the runs' mean normal
/// force [N] and the largest peak force [N]. Then one line per scene (in order of first
/// appearance) naming the controllers that held it and the one(s) with the least mean
/// force. Wherever a baseline (a controller whose name does not start with `softgrip`)
/// holds a scene with a mean force no larger than a softgrip controller's, or holds a
/// scene a softgrip controller slipped in, a line says so explicitly.
pub fn comparison_table(runs: &[RunSummary]) -> String {
    use Align::{Left as L, Right as R};
    let controllers = first_appearance(runs.iter().map(|r| r.controller.as_str()));
    let scenes = first_appearance(runs.iter().map(|r| r.scene.as_str()));

    let headers = [
        "controller",
        "scenes held",
        "slip events",
        "slip distance [mm]",
        "mean of mean N [N]",
        "max peak N [N]",
    ];
    let align = [L, R, R, R, R, R];
    let rows: Vec<Vec<String>> = controllers
        .iter()
        .map(|&c| {
            let mine: Vec<&RunSummary> = runs.iter().filter(|r| r.controller == c).collect();
            let eligible = mine.iter().filter(|r| !r.expected_slip).count();
            let held_n = mine.iter().filter(|r| !r.expected_slip && held(r)).count();
            let events: u64 = mine.iter().map(|r| r.slip_events).sum();
            let dist: f64 = mine.iter().map(|r| r.slip_distance_m).sum();
            let means: Vec<f64> = mine
                .iter()
                .map(|r| r.mean_normal_force_n)
                .filter(|v| v.is_finite())
                .collect();
            let mean_of_mean = if means.is_empty() {
                f64::NAN
            } else {
                means.iter().sum::<f64>() / means.len() as f64
            };
            let peak = mine
                .iter()
                .map(|r| r.peak_normal_force_n)
                .filter(|v| v.is_finite())
                .fold(f64::NAN, f64::max);
            vec![
                c.to_string(),
                format!("{held_n}/{eligible}"),
                events.to_string(),
                format!("{:.3}", dist * 1e3),
                format!("{mean_of_mean:.3}"),
                format!("{peak:.3}"),
            ]
        })
        .collect();
    let mut out = render_table(&headers, &align, &rows);

    out.push('\n');
    for &scene in &scenes {
        let here: Vec<&RunSummary> = runs.iter().filter(|r| r.scene == scene).collect();
        let holders: Vec<&RunSummary> = here.iter().copied().filter(|r| held(r)).collect();
        let expected_slip = here.iter().any(|r| r.expected_slip);
        if expected_slip {
            if holders.is_empty() {
                out.push_str(&format!(
                    "scene {scene} (overload): every controller slipped, as expected\n"
                ));
            } else {
                let names: Vec<String> = holders
                    .iter()
                    .map(|r| format!("{} ({:.3} N mean)", r.controller, r.mean_normal_force_n))
                    .collect();
                out.push_str(&format!(
                    "scene {scene} (overload): held by {} — unexpected for an overload\n",
                    names.join(", ")
                ));
            }
            continue;
        }
        if holders.is_empty() {
            out.push_str(&format!("scene {scene}: no controller held it\n"));
            continue;
        }
        let least = holders
            .iter()
            .map(|r| r.mean_normal_force_n)
            .filter(|v| v.is_finite())
            .fold(f64::INFINITY, f64::min);
        let names: Vec<&str> = holders.iter().map(|r| r.controller.as_str()).collect();
        let best: Vec<&str> = holders
            .iter()
            .filter(|r| r.mean_normal_force_n == least)
            .map(|r| r.controller.as_str())
            .collect();
        if best.is_empty() {
            out.push_str(&format!(
                "scene {scene}: held by {}; no finite mean force\n",
                names.join(", ")
            ));
        } else {
            out.push_str(&format!(
                "scene {scene}: held by {}; least mean force: {} ({least:.3} N)\n",
                names.join(", "),
                best.join(", ")
            ));
        }
        for s in here.iter().filter(|r| is_softgrip(&r.controller)) {
            for b in holders.iter().filter(|r| !is_softgrip(&r.controller)) {
                if !held(s) {
                    out.push_str(&format!(
                        "scene {scene}: baseline \"{}\" held with {:.3} N mean, {} slipped \
                         ({} events) — the baseline does better here\n",
                        b.controller, b.mean_normal_force_n, s.controller, s.slip_events
                    ));
                } else if b.mean_normal_force_n <= s.mean_normal_force_n {
                    out.push_str(&format!(
                        "scene {scene}: baseline \"{}\" held with {:.3} N mean, {} {:.3} N \
                         — the baseline does as well here\n",
                        b.controller, b.mean_normal_force_n, s.controller, s.mean_normal_force_n
                    ));
                }
            }
        }
    }
    out
}
