//! `fls`: one friction limit surface, swept.

use crate::*;

/// Sweeps one friction limit surface (see `softgrip.fls`). Returns a dict shaped like
/// `host-sim fls --format json` (samples as the lists `d`, `f`, `m`).
#[pyfunction]
#[pyo3(signature = (shape, k, aspect, skew, alpha, locus, samples, order, at))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn fls<'py>(
    py: Python<'py>,
    shape: &str,
    k: f64,
    aspect: f64,
    skew: f64,
    alpha: f64,
    locus: Option<f64>,
    samples: i64,
    order: i64,
    at: Option<Vec<f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    // The same checks, in the same order, as `host-sim fls`.
    if aspect.is_finite() && !(1e-6..=1e6).contains(&aspect) {
        return Err(bad(
            py,
            "aspect",
            format!("aspect: {aspect} is out of range, expected 1e-6 <= aspect <= 1e6"),
        ));
    }
    let order_n = usize::try_from(order).map_err(|_| {
        bad(
            py,
            "order",
            format!("order: {order} is out of range, expected 4 ..= 128"),
        )
    })?;
    let order_q = QuadratureOrder::new(order_n).map_err(|e| core_err(py, e, same))?;
    let shape_v = match shape_of(py, shape)? {
        FingerShape::Rect => softgrip::Shape::Rect { aspect },
        FingerShape::Disc => softgrip::Shape::Disc,
    };
    for (name, v) in [("alpha", alpha), ("aspect", aspect)] {
        finite(py, name, v)?;
    }
    let skew_v = if skew.is_nan() || skew != 0.0 {
        Some((skew, alpha, locus.unwrap_or(skew / 2.0)))
    } else {
        if let Some(h) = locus {
            if !h.is_finite() || h < 0.0 {
                return Err(bad(
                    py,
                    "locus",
                    format!("locus: {h} is out of range, expected locus >= 0"),
                ));
            }
        }
        None
    };
    if !(2..=MAX_SAMPLES as i64).contains(&samples) {
        return Err(bad(
            py,
            "samples",
            format!("samples: {samples} is out of range, expected 2 ..= {MAX_SAMPLES}"),
        ));
    }
    let at = at.unwrap_or_default();
    for &d in &at {
        if !(d.is_finite() && d >= 0.0) {
            return Err(bad(
                py,
                "at",
                format!("at: {d} is out of range, expected finite d_c/a >= 0"),
            ));
        }
    }
    let cfg = FlsConfig {
        shape: shape_v,
        k,
        skew: skew_v,
        order: order_q,
    };
    let model = FlsModel::<f64>::new(cfg).map_err(|e| core_err(py, e, same))?;
    let table: Box<FlsTable<f64, { MAX_SAMPLES + 1 }>> =
        Box::new(FlsTable::sweep(&model, samples as usize).map_err(|e| core_err(py, e, same))?);
    let fit = EllipseFit::fit(table.points())
        .ok_or_else(|| PyValueError::new_err("the sweep does not determine an ellipse"))?;
    let gap = RadialGap::find(&model, &table);
    let inscribed = InscribedEllipse::fit_within(table.points(), &[table.points()])
        .ok_or_else(|| PyValueError::new_err("no ellipse fits inside the sweep"))?;
    let (over_max, over_mean) = inscribed.force_overhead(table.points(), 91);
    let pts: Vec<_> = if at.is_empty() {
        table
            .points()
            .iter()
            .filter(|p| p.d.is_finite())
            .copied()
            .collect()
    } else {
        at.iter().map(|&d| model.point(d)).collect()
    };
    let out = PyDict::new(py);
    out.set_item("shape", cfg.shape.name())?;
    out.set_item("k", k)?;
    out.set_item("aspect", (shape == "rect").then_some(aspect))?;
    out.set_item("skew", skew)?;
    out.set_item("alpha", alpha)?;
    out.set_item("locus", cfg.skew.map(|s| s.2))?;
    out.set_item("order", order)?;
    out.set_item("pitch", table.pitch())?;
    out.set_item("star_shaped", table.is_star_shaped())?;
    let e = PyDict::new(py);
    e.set_item("f_semi_axis", fit.f_semi_axis)?;
    e.set_item("m_semi_axis", fit.m_semi_axis)?;
    e.set_item("rms_residual", fit.rms_residual)?;
    e.set_item("max_radial_gap", gap.max_gap)?;
    e.set_item("max_relative_gap", gap.max_relative_gap)?;
    let at_gap = PyDict::new(py);
    at_gap.set_item("d", gap.at.d)?;
    at_gap.set_item("f", gap.at.f)?;
    at_gap.set_item("m", gap.at.m)?;
    e.set_item("max_gap_at", at_gap)?;
    e.set_item("max_outside", gap.max_outside)?;
    out.set_item("ellipse", e)?;
    let i = PyDict::new(py);
    i.set_item("f_semi_axis", inscribed.x_semi_axis)?;
    i.set_item("m_over_pitch_semi_axis", inscribed.y_semi_axis)?;
    i.set_item("force_over_exact_max_pct", 100.0 * over_max)?;
    i.set_item("force_over_exact_mean_pct", 100.0 * over_mean)?;
    out.set_item("inscribed", i)?;
    out.set_item("d", pts.iter().map(|p| p.d).collect::<Vec<_>>())?;
    out.set_item("f", pts.iter().map(|p| p.f).collect::<Vec<_>>())?;
    out.set_item("m", pts.iter().map(|p| p.m).collect::<Vec<_>>())?;
    Ok(out)
}
