//! `ControllerConfig` from Python keywords and back, and building the controller.

use crate::*;

/// Every `ControllerConfig` field, in declaration order.
pub(crate) const FIELDS: [&str; 24] = [
    "mu",
    "shape",
    "k",
    "skew",
    "c_m_per_n_gamma",
    "gamma",
    "half_length_m",
    "safety",
    "n_min_n",
    "n_max_n",
    "rise_rate_n_per_s",
    "fall_rate_n_per_s",
    "tick_period_s",
    "stale_timeout_s",
    "fault_force_n",
    "force_range_n",
    "moment_range_nm",
    "mode",
    "force_nodes",
    "quadrature_order",
    "table_samples",
    "aspect_count",
    "actuator_lag_s",
    "actuator_slew_n_per_s",
];

pub(crate) fn count(py: Python<'_>, name: &str, v: &Bound<'_, PyAny>) -> PyResult<u16> {
    let n: i64 = v
        .extract()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected an integer")))?;
    count_of(py, name, n)
}

/// A table size `n` as the configuration's `u16`, or a `ConfigError` naming `name`.
pub(crate) fn count_of(py: Python<'_>, name: &str, n: i64) -> PyResult<u16> {
    u16::try_from(n).map_err(|_| {
        bad(
            py,
            name,
            format!("{name}: {n} is out of range, expected 0 ..= 65535"),
        )
    })
}

pub(crate) fn real(name: &str, v: &Bound<'_, PyAny>) -> PyResult<f64> {
    v.extract()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected a number")))
}

/// `skew` as Python gives it: `None` (or 0), `Δ/a` (then `α = 1.1`, locus `Δ/2`), a tuple
/// `(Δ/a, α, h/a)` or a dict with those field names.
pub(crate) fn skew_of(v: &Bound<'_, PyAny>) -> PyResult<Option<SkewParams>> {
    if v.is_none() {
        return Ok(None);
    }
    if let Ok(d) = v.extract::<f64>() {
        if d == 0.0 {
            // No skew, as `--skew 0` on the command line.
            return Ok(None);
        }
        return Ok(Some(SkewParams {
            delta_over_a: d,
            alpha: 1.1,
            locus_over_a: d / 2.0,
        }));
    }
    if let Ok((d, a, h)) = v.extract::<(f64, f64, f64)>() {
        return Ok(Some(SkewParams {
            delta_over_a: d,
            alpha: a,
            locus_over_a: h,
        }));
    }
    if let Ok(dict) = v.cast::<PyDict>() {
        let get = |k: &str, default: Option<f64>| -> PyResult<f64> {
            match dict.get_item(k)? {
                Some(x) => real(k, &x),
                None => default.ok_or_else(|| PyTypeError::new_err(format!("skew: needs {k}"))),
            }
        };
        let d = get("delta_over_a", None)?;
        return Ok(Some(SkewParams {
            delta_over_a: d,
            alpha: get("alpha", Some(1.1))?,
            locus_over_a: get("locus_over_a", Some(d / 2.0))?,
        }));
    }
    Err(PyTypeError::new_err(
        "skew: expected None, a number (delta_over_a), a tuple (delta_over_a, alpha, \
         locus_over_a) or a dict with those keys",
    ))
}

/// `base` with the keywords applied.
pub(crate) fn apply(
    py: Python<'_>,
    mut cfg: ControllerConfig,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<ControllerConfig> {
    let Some(kw) = kwargs else {
        return Ok(cfg);
    };
    for (key, v) in kw.iter() {
        let key: String = key.extract()?;
        match key.as_str() {
            "mu" => cfg.mu = real(&key, &v)?,
            "shape" => cfg.shape = shape_of(py, &v.extract::<String>()?)?,
            "k" => cfg.k = real(&key, &v)?,
            "skew" => cfg.skew = skew_of(&v)?,
            "c_m_per_n_gamma" => cfg.c_m_per_n_gamma = real(&key, &v)?,
            "gamma" => cfg.gamma = real(&key, &v)?,
            "half_length_m" => cfg.half_length_m = real(&key, &v)?,
            "safety" => cfg.safety = real(&key, &v)?,
            "n_min_n" => cfg.n_min_n = real(&key, &v)?,
            "n_max_n" => cfg.n_max_n = real(&key, &v)?,
            "rise_rate_n_per_s" => cfg.rise_rate_n_per_s = real(&key, &v)?,
            "fall_rate_n_per_s" => cfg.fall_rate_n_per_s = real(&key, &v)?,
            "tick_period_s" => cfg.tick_period_s = real(&key, &v)?,
            "stale_timeout_s" => cfg.stale_timeout_s = real(&key, &v)?,
            "fault_force_n" => cfg.fault_force_n = real(&key, &v)?,
            "force_range_n" => cfg.force_range_n = real(&key, &v)?,
            "moment_range_nm" => cfg.moment_range_nm = real(&key, &v)?,
            "mode" => cfg.mode = mode_of(py, &v.extract::<String>()?)?,
            "force_nodes" => cfg.force_nodes = count(py, &key, &v)?,
            "quadrature_order" => cfg.quadrature_order = count(py, &key, &v)?,
            "table_samples" => cfg.table_samples = count(py, &key, &v)?,
            "aspect_count" => cfg.aspect_count = count(py, &key, &v)?,
            "actuator_lag_s" => cfg.actuator_lag_s = real(&key, &v)?,
            "actuator_slew_n_per_s" => cfg.actuator_slew_n_per_s = real(&key, &v)?,
            other => {
                return Err(PyTypeError::new_err(format!(
                    "unexpected keyword argument {other:?} (ControllerConfig fields: {})",
                    FIELDS.join(", ")
                )))
            }
        }
    }
    Ok(cfg)
}

pub(crate) fn config_dict<'py>(
    py: Python<'py>,
    c: &ControllerConfig,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("mu", c.mu)?;
    d.set_item("shape", c.shape.name())?;
    d.set_item("k", c.k)?;
    d.set_item(
        "skew",
        c.skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
    )?;
    d.set_item("c_m_per_n_gamma", c.c_m_per_n_gamma)?;
    d.set_item("gamma", c.gamma)?;
    d.set_item("half_length_m", c.half_length_m)?;
    d.set_item("safety", c.safety)?;
    d.set_item("n_min_n", c.n_min_n)?;
    d.set_item("n_max_n", c.n_max_n)?;
    d.set_item("rise_rate_n_per_s", c.rise_rate_n_per_s)?;
    d.set_item("fall_rate_n_per_s", c.fall_rate_n_per_s)?;
    d.set_item("tick_period_s", c.tick_period_s)?;
    d.set_item("stale_timeout_s", c.stale_timeout_s)?;
    d.set_item("fault_force_n", c.fault_force_n)?;
    d.set_item("force_range_n", c.force_range_n)?;
    d.set_item("moment_range_nm", c.moment_range_nm)?;
    d.set_item("mode", c.mode.name())?;
    d.set_item("force_nodes", c.force_nodes)?;
    d.set_item("quadrature_order", c.quadrature_order)?;
    d.set_item("table_samples", c.table_samples)?;
    d.set_item("aspect_count", c.aspect_count)?;
    d.set_item("actuator_lag_s", c.actuator_lag_s)?;
    d.set_item("actuator_slew_n_per_s", c.actuator_slew_n_per_s)?;
    Ok(d)
}

pub(crate) fn build(py: Python<'_>, cfg: ControllerConfig) -> PyResult<CoreController<f64, Libm>> {
    CoreController::<f64, Libm>::new_precomputed_in::<f64>(cfg)
        .map_err(|e| core_err(py, e, field_name))
}
