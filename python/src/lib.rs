//! `softgrip._softgrip`: the Python bindings of the softgrip core.
//!
//! Thin by design: every number comes from the Rust core (`softgrip`), computed the way
//! `host-sim fls` and `host-sim required-force` compute it, so the Python answers equal the
//! command line's JSON. The Python package (`softgrip/__init__.py`) only turns lists into
//! numpy arrays and broadcasts array arguments.

#![forbid(unsafe_code)]

use pyo3::create_exception;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use softgrip::contact::ContactSize;
use softgrip::controller::{
    Controller as CoreController, ControllerConfig, FingerShape, Libm, Measurement, Mode,
    SkewParams, SlipSignal, Status, TickOutput,
};
use softgrip::fls::{EllipseFit, InscribedEllipse, RadialGap};
use softgrip::{ConfigError as CoreConfigError, FlsConfig, FlsModel, FlsTable, QuadratureOrder};

create_exception!(
    softgrip,
    ConfigError,
    PyValueError,
    "A bad argument: a ValueError whose `param` attribute names the parameter."
);

/// Largest `samples` of `fls` (as `host-sim fls`).
const MAX_SAMPLES: usize = 4096;

/// A `ConfigError` (a `ValueError`) with `param` set and the given text.
fn bad(py: Python<'_>, param: &str, text: String) -> PyErr {
    let err = ConfigError::new_err(text);
    // Setting an attribute on a fresh exception instance cannot fail in practice; if it
    // did, the error would still carry the parameter's name in its text.
    let _ = err.value(py).setattr("param", param);
    err
}

/// The core's error, its parameter renamed to the Python keyword `rename` gives.
fn core_err(py: Python<'_>, e: CoreConfigError, rename: fn(&str) -> &str) -> PyErr {
    let text = e.to_string();
    let rest = text.split_once(": ").map_or(text.as_str(), |(_, r)| r);
    let name = rename(e.param());
    bad(py, name, format!("{name}: {rest}"))
}

fn same(p: &str) -> &str {
    p
}

/// The `Controller` keyword of a parameter the core names otherwise: `QuadratureOrder`
/// names itself `order`, the configuration field is `quadrature_order`.
fn field_name(p: &str) -> &str {
    match p {
        "order" => "quadrature_order",
        "delta_over_a" => "skew",
        other => other,
    }
}

fn finite(py: Python<'_>, name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(py, name, format!("{name}: must be a finite number")))
    }
}

fn shape_of(py: Python<'_>, s: &str) -> PyResult<FingerShape> {
    match s {
        "rect" => Ok(FingerShape::Rect),
        "disc" => Ok(FingerShape::Disc),
        other => Err(bad(
            py,
            "shape",
            format!("shape: {other:?} is not a shape, expected \"rect\" or \"disc\""),
        )),
    }
}

fn mode_of(py: Python<'_>, s: &str) -> PyResult<Mode> {
    match s {
        "ellipse" => Ok(Mode::Ellipse),
        "table" => Ok(Mode::Table),
        other => Err(bad(
            py,
            "mode",
            format!("mode: {other:?} is not a mode, expected \"ellipse\" or \"table\""),
        )),
    }
}

// ---------------------------------------------------------------------------------------
// fls

/// Sweeps one friction limit surface (see `softgrip.fls`). Returns a dict shaped like
/// `host-sim fls --format json` (samples as the lists `d`, `f`, `m`).
#[pyfunction]
#[pyo3(signature = (shape, k, aspect, skew, alpha, locus, samples, order, at))]
#[allow(clippy::too_many_arguments)]
fn fls<'py>(
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

// ---------------------------------------------------------------------------------------
// required_force

/// The keyword of `required_force` a configuration field corresponds to.
fn rf_name(param: &str) -> &str {
    match param {
        "c_m_per_n_gamma" => "c",
        "half_length_m" => "length",
        "n_min_n" | "fault_force_n" => "n_min",
        "n_max_n" => "n_max",
        "force_range_n" => "ft",
        "moment_range_nm" => "mn",
        "delta_over_a" => "skew",
        "order" => "quadrature_order",
        other => other,
    }
}

/// `N_req` for many loads with one controller (see `softgrip.required_force`): the same
/// configuration and computation as `host-sim required-force` (f64 precompute, f64 libm
/// tick, 64 force nodes). Returns a dict of lists plus `ellipse_axes`.
#[pyfunction]
#[pyo3(signature = (ft, mn, mu, c, gamma, shape, length, k, safety, mode, skew, alpha, locus, n_min, n_max))]
#[allow(clippy::too_many_arguments)]
fn required_force<'py>(
    py: Python<'py>,
    ft: Vec<f64>,
    mn: Vec<f64>,
    mu: f64,
    c: f64,
    gamma: f64,
    shape: &str,
    length: f64,
    k: f64,
    safety: f64,
    mode: &str,
    skew: f64,
    alpha: f64,
    locus: Option<f64>,
    n_min: f64,
    n_max: f64,
) -> PyResult<Bound<'py, PyDict>> {
    if ft.len() != mn.len() {
        return Err(PyValueError::new_err("ft and mn must have the same length"));
    }
    let (mut ft_max, mut mn_max) = (0.0f64, 0.0f64);
    for (name, v) in [("ft", &ft), ("mn", &mn)] {
        for (i, &x) in v.iter().enumerate() {
            if !x.is_finite() {
                return Err(bad(
                    py,
                    name,
                    format!("{name}: must be a finite number (element {i}: {x})"),
                ));
            }
        }
    }
    for (&f, &m) in ft.iter().zip(&mn) {
        ft_max = ft_max.max(f.abs());
        mn_max = mn_max.max(m.abs());
    }
    let skew_v = if skew == 0.0 {
        None
    } else {
        Some(SkewParams {
            delta_over_a: skew,
            alpha,
            locus_over_a: locus.unwrap_or(skew / 2.0),
        })
    };
    let cfg = ControllerConfig {
        mu,
        shape: shape_of(py, shape)?,
        k,
        skew: skew_v,
        c_m_per_n_gamma: c,
        gamma,
        half_length_m: length,
        safety,
        n_min_n: n_min,
        n_max_n: n_max,
        fault_force_n: n_min,
        // The sensor must be able to read every load (as `host-sim required-force`; the
        // rule itself does not depend on it).
        force_range_n: (2.0 * ft_max).max(100.0),
        moment_range_nm: (2.0 * mn_max).max(2.0),
        mode: mode_of(py, mode)?,
        force_nodes: 64,
        ..ControllerConfig::default()
    };
    let ctl = CoreController::<f64, Libm>::new_precomputed_in::<f64>(cfg)
        .map_err(|e| core_err(py, e, rf_name))?;
    let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma)
        .map_err(|e| core_err(py, e, rf_name))?;
    let n = ft.len();
    let (mut req_v, mut slip_v, mut a_v, mut u_v, mut cmd_v, mut st_v) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n),
    );
    let none = || PyValueError::new_err("the solver returned no answer");
    for (&f0, &m0) in ft.iter().zip(&mn) {
        let (f, m) = (f0.abs(), m0.abs());
        let req = ctl
            .required_force(f, m, cfg.safety)
            .ok_or_else(none)?
            .force_n;
        let slip = ctl.required_force(f, m, 1.0).ok_or_else(none)?.force_n;
        let command = req.max(cfg.n_min_n).min(cfg.n_max_n);
        let u = ctl.utilisation(f, m, command).ok_or_else(none)?;
        let status = if req > cfg.n_max_n {
            Status::Saturated
        } else {
            Status::Ok
        };
        req_v.push(req);
        slip_v.push(slip);
        a_v.push(contact.half_width_m(req));
        u_v.push(u);
        cmd_v.push(command);
        st_v.push(status.name());
    }
    let out = PyDict::new(py);
    out.set_item("normal_force", req_v)?;
    out.set_item("n_slip", slip_v)?;
    out.set_item("a", a_v)?;
    out.set_item("utilisation", u_v)?;
    out.set_item("status", st_v)?;
    out.set_item("command", cmd_v)?;
    out.set_item("mode", cfg.mode.name())?;
    let [sf, sm] = ctl.capacity().demand_scale();
    out.set_item("ellipse_axes", (1.0 / sf, 1.0 / sm))?;
    Ok(out)
}

// ---------------------------------------------------------------------------------------
// Controller

/// Every `ControllerConfig` field, in declaration order.
const FIELDS: [&str; 24] = [
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

fn count(py: Python<'_>, name: &str, v: &Bound<'_, PyAny>) -> PyResult<u16> {
    let n: i64 = v
        .extract()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected an integer")))?;
    u16::try_from(n).map_err(|_| {
        bad(
            py,
            name,
            format!("{name}: {n} is out of range, expected 0 ..= 65535"),
        )
    })
}

fn real(name: &str, v: &Bound<'_, PyAny>) -> PyResult<f64> {
    v.extract()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected a number")))
}

/// `skew` as Python gives it: `None`, `Δ/a` (then `α = 1.1`, locus `Δ/2`), a tuple
/// `(Δ/a, α, h/a)` or a dict with those field names.
fn skew_of(v: &Bound<'_, PyAny>) -> PyResult<Option<SkewParams>> {
    if v.is_none() {
        return Ok(None);
    }
    if let Ok(d) = v.extract::<f64>() {
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
fn apply(
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

fn config_dict<'py>(py: Python<'py>, c: &ControllerConfig) -> PyResult<Bound<'py, PyDict>> {
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

fn build(py: Python<'_>, cfg: ControllerConfig) -> PyResult<CoreController<f64, Libm>> {
    CoreController::<f64, Libm>::new_precomputed_in::<f64>(cfg)
        .map_err(|e| core_err(py, e, field_name))
}

/// What one tick decided, besides the command (Rust's `TickOutput`).
#[pyclass(frozen, get_all, module = "softgrip")]
#[derive(Clone)]
struct TickStatus {
    /// "ok", "saturated", "sensor_fault" or "stale_input".
    status: &'static str,
    /// The commanded normal force [N].
    command_n: f64,
    /// `N_req(s)` with the present margin [N].
    required_n: f64,
    /// `N_slip = N_req(1)` [N].
    n_slip_n: f64,
    /// The load's utilisation of the limit surface at the measured normal force [1].
    utilisation: f64,
    /// Whether the input has been bad or stale for longer than the stale timeout.
    fault_active: bool,
    /// Illinois iterations spent in this tick.
    iterations: u8,
    /// The friction coefficient the controller believes now [1].
    mu_estimate: f64,
    /// The margin multiplying the safety factor [1].
    margin: f64,
}

#[pymethods]
impl TickStatus {
    fn __repr__(&self) -> String {
        format!(
            "TickStatus(status={:?}, command_n={}, required_n={}, n_slip_n={}, \
             utilisation={}, fault_active={}, iterations={}, mu_estimate={}, margin={})",
            self.status,
            self.command_n,
            self.required_n,
            self.n_slip_n,
            self.utilisation,
            if self.fault_active { "True" } else { "False" },
            self.iterations,
            self.mu_estimate,
            self.margin
        )
    }
}

impl From<TickOutput<f64>> for TickStatus {
    fn from(o: TickOutput<f64>) -> Self {
        Self {
            status: o.status.name(),
            command_n: o.command_n,
            required_n: o.required_n,
            n_slip_n: o.n_slip_n,
            utilisation: o.utilisation,
            fault_active: o.fault_active,
            iterations: o.iterations,
            mu_estimate: o.mu_estimate,
            margin: o.margin,
        }
    }
}

/// The slip-prevention controller (f64 precompute and tick, libm).
///
/// `Controller(**config)`: keywords are `ControllerConfig`'s fields (see
/// `softgrip.default_config()`): forces in N, moments in N·m, lengths in m, times in s,
/// rates in N/s. A bad value raises `ConfigError` (a `ValueError`) naming the field.
#[pyclass(module = "softgrip")]
struct Controller {
    inner: CoreController<f64, Libm>,
}

fn slip_of(py: Python<'_>, v: Option<&Bound<'_, PyAny>>) -> PyResult<SlipSignal> {
    let Some(v) = v else {
        return Ok(SlipSignal::None);
    };
    if v.is_none() {
        return Ok(SlipSignal::None);
    }
    let s: String = v
        .extract()
        .map_err(|_| PyTypeError::new_err("slip: expected None or a string"))?;
    match s.as_str() {
        "none" => Ok(SlipSignal::None),
        "incipient" => Ok(SlipSignal::Incipient),
        "gross" => Ok(SlipSignal::Gross),
        other => Err(bad(
            py,
            "slip",
            format!("slip: {other:?} is not a slip signal, expected None, \"none\", \"incipient\" or \"gross\""),
        )),
    }
}

#[pymethods]
impl Controller {
    #[new]
    #[pyo3(signature = (**config))]
    fn new(py: Python<'_>, config: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let cfg = apply(py, ControllerConfig::default(), config)?;
        Ok(Self {
            inner: build(py, cfg)?,
        })
    }

    /// One control tick. `ft`: the tangential force [N], `|f_t|` or its two components;
    /// `mn`: the torsional moment [N·m]; `t`: the sensor's timestamp [s] (it must
    /// increase; rounded to µs); `slip`: None, "none", "incipient" or "gross";
    /// `normal_force`: the measured normal force [N] (default: the present command).
    /// Returns `(command [N], TickStatus)`.
    #[pyo3(signature = (ft, mn, t, slip=None, normal_force=None))]
    fn tick(
        &mut self,
        py: Python<'_>,
        ft: &Bound<'_, PyAny>,
        mn: f64,
        t: f64,
        slip: Option<&Bound<'_, PyAny>>,
        normal_force: Option<f64>,
    ) -> PyResult<(f64, TickStatus)> {
        let tangential = if let Ok(x) = ft.extract::<f64>() {
            [x, 0.0]
        } else if let Ok((x, y)) = ft.extract::<(f64, f64)>() {
            [x, y]
        } else if let Ok(v) = ft.extract::<Vec<f64>>() {
            match v.as_slice() {
                [x, y] => [*x, *y],
                _ => {
                    return Err(bad(
                        py,
                        "ft",
                        format!("ft: expected a number or 2 components, got {}", v.len()),
                    ))
                }
            }
        } else {
            return Err(PyTypeError::new_err(
                "ft: expected a number or a pair of numbers [N]",
            ));
        };
        if !((0.0..1.8e13).contains(&t)) {
            return Err(bad(
                py,
                "t",
                format!("t: {t} is out of range, expected 0 <= t [s] < 1.8e13"),
            ));
        }
        let m = Measurement {
            tangential_force_n: tangential,
            torsional_moment_nm: mn,
            normal_force_n: normal_force.unwrap_or(self.inner.command_n()),
            timestamp_us: (t * 1e6).round() as u64,
            slip: slip_of(py, slip)?,
        };
        let out = self.inner.tick(&m);
        Ok((out.command_n, out.into()))
    }

    /// A tick with no measurement. Returns `(command_n, TickStatus)`.
    fn idle(&mut self) -> (f64, TickStatus) {
        let out = self.inner.idle();
        (out.command_n, out.into())
    }

    /// A new configuration (the present one with these fields changed) that takes over
    /// from the present controller: the command carries over.
    #[pyo3(signature = (**config))]
    fn reconfigure(&mut self, py: Python<'_>, config: Option<&Bound<'_, PyDict>>) -> PyResult<()> {
        let cfg = apply(py, *self.inner.config(), config)?;
        let mut next = build(py, cfg)?;
        next.take_over_from(&self.inner);
        self.inner = next;
        Ok(())
    }

    /// Back to the start-up state (command `n_min_n`), keeping the grid.
    fn reset(&mut self) {
        self.inner.reset();
    }

    /// `N_req` [N] of a load without touching the state (`safety=1` gives `N_slip`).
    #[pyo3(signature = (ft, mn, safety=None))]
    fn required_force(&self, ft: f64, mn: f64, safety: Option<f64>) -> Option<f64> {
        let s = safety.unwrap_or(self.inner.config().safety);
        self.inner.required_force(ft, mn, s).map(|r| r.force_n)
    }

    /// Utilisation of a load at a normal force, without touching the state.
    fn utilisation(&self, ft: f64, mn: f64, normal_force: f64) -> Option<f64> {
        self.inner.utilisation(ft, mn, normal_force)
    }

    #[getter]
    fn command_n(&self) -> f64 {
        self.inner.command_n()
    }

    #[getter]
    fn mu_estimate(&self) -> f64 {
        self.inner.mu_estimate()
    }

    #[getter]
    fn margin(&self) -> f64 {
        self.inner.margin()
    }

    #[getter]
    fn time_rejections(&self) -> u32 {
        self.inner.time_rejections()
    }

    /// The configuration as a dict of `ControllerConfig` fields.
    #[getter]
    fn config<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        config_dict(py, self.inner.config())
    }

    /// `(A, B)`: the semi-axes of the inscribed ellipse ellipse mode tests against.
    #[getter]
    fn ellipse_axes(&self) -> (f64, f64) {
        let [sf, sm] = self.inner.capacity().demand_scale();
        (1.0 / sf, 1.0 / sm)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let d = config_dict(py, self.inner.config())?;
        let items: Vec<String> = d
            .iter()
            .map(|(k, v)| Ok(format!("{}={}", k, v.repr()?)))
            .collect::<PyResult<_>>()?;
        Ok(format!("Controller({})", items.join(", ")))
    }
}

/// The defaults of `ControllerConfig`, as a dict.
#[pyfunction]
fn default_config(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    config_dict(py, &ControllerConfig::default())
}

/// Contact half-width `a = c·N^γ` [m] at normal force `n` [N].
#[pyfunction]
fn half_width(py: Python<'_>, c: f64, gamma: f64, n: f64) -> PyResult<f64> {
    let contact = ContactSize::<f64>::new(c, gamma).map_err(|e| core_err(py, e, rf_name))?;
    Ok(contact.half_width_m(n))
}

#[pymodule]
fn _softgrip(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fls, m)?)?;
    m.add_function(wrap_pyfunction!(required_force, m)?)?;
    m.add_function(wrap_pyfunction!(default_config, m)?)?;
    m.add_function(wrap_pyfunction!(half_width, m)?)?;
    m.add_class::<Controller>()?;
    m.add_class::<TickStatus>()?;
    m.add("ConfigError", m.py().get_type::<ConfigError>())?;
    m.add("CONFIG_FIELDS", PyTuple::new(m.py(), FIELDS)?)?;
    Ok(())
}
