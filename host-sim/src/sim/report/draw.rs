//! What both plots share: decimation, line segments, the SVG canvas and the legend.

use super::*;

/// The sample's load in the surface plot's coordinates: `(f̃, |m̃| / pitch)`, or `None`
/// if either is not finite.
pub(super) fn surface_point(s: &Sample) -> Option<(f64, f64)> {
    let x = s.f_norm;
    let y = (s.m_norm / s.pitch).abs();
    (x.is_finite() && y.is_finite()).then_some((x, y))
}

/// The `q`-quantile (0..=1, nearest rank) of the finite values of `values`.
pub(super) fn quantile(values: impl Iterator<Item = f64>, q: f64) -> Option<f64> {
    let mut v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let rank = (q * v.len() as f64).ceil() as usize;
    Some(v[rank.clamp(1, v.len()) - 1])
}

/// Every `k`-th element so that at most `max` remain (the last one always kept).
pub(super) fn stride<T: Copy>(v: &[T], max: usize) -> Vec<T> {
    if v.len() <= max || max < 2 {
        return v.to_vec();
    }
    let k = v.len().div_ceil(max - 1);
    let mut out: Vec<T> = v.iter().step_by(k).copied().collect();
    if !(v.len() - 1).is_multiple_of(k) {
        out.push(v[v.len() - 1]);
    }
    out
}

/// Decimates a time series for drawing: per bucket of `k` points, keeps the lowest and
/// the highest point (in time order), so peaks survive.
pub(super) fn decimate_min_max(points: &[(f64, f64)], max: usize) -> Vec<(f64, f64)> {
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
pub(super) fn segments<T>(points: impl Iterator<Item = Option<T>>) -> Vec<Vec<T>> {
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
pub(super) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A chart with two `f64` axes on the SVG backend.
pub(super) type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Renders into an SVG string, then writes it to `path` (so that file errors come back as
/// [`ReportError::Io`] and drawing errors as [`ReportError::Plot`]). The canvas is
/// `plot_size` plus a legend panel of `legend_w` pixels on the right; `draw` gets the plot
/// area and the legend area.
pub(super) fn write_svg(
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
pub(super) enum Swatch {
    Line(ShapeStyle),
    Dashed(ShapeStyle),
    Cross(ShapeStyle),
    Shade(ShapeStyle),
}

/// Legend font size [px].
pub(super) const LEGEND_FONT: u32 = 15;
/// Height of one legend row [px].
pub(super) const LEGEND_ROW: i32 = 22;
/// Top of the legend (level with the top of the plotting area) [px].
pub(super) const LEGEND_TOP: i32 = 45;

/// Width [px] of the legend panel for these labels (generous: the SVG viewer's font
/// decides the real width).
pub(super) fn legend_width<'a>(labels: impl Iterator<Item = &'a str>) -> u32 {
    let chars = labels.map(|l| l.chars().count()).max().unwrap_or(0) as u32;
    (chars * 7 + 60).clamp(140, 480)
}

/// Draws the legend: one row per entry, a swatch and its label, in a framed box.
pub(super) fn draw_legend(
    area: &Area<'_>,
    entries: &[(String, Swatch)],
) -> Result<(), ReportError> {
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
