//! `required_force`: the controller's rule over arrays of loads.

use crate::*;

/// The keyword of `required_force` a core parameter corresponds to: the configuration's
/// field ([`softgrip::error::field_of`]), or for a field the rule derives
/// ([`ControllerConfig::for_loads`]) the keyword it is derived from.
pub(crate) fn rf_name(param: &'static str) -> &'static str {
    ControllerConfig::rule_input(field_name(param))
}

/// A controller build's error under the keyword of its cause: a sensor-range overflow on
/// `safety` (safety/mu), `ft` (the loads) or `half_length_m` (the contact).
fn build_err(py: Python<'_>, e: BuildError) -> PyErr {
    let name = match e {
        BuildError::Config(e) => return core_err(py, e, rf_name),
        BuildError::RangeOverflow(RangeOverflow::SafetyOverMu) => "safety",
        BuildError::RangeOverflow(RangeOverflow::SensorRange) => "ft",
        BuildError::RangeOverflow(RangeOverflow::Contact) => "half_length_m",
    };
    bad(
        py,
        name,
        format!(
            "{name}: the worst load the sensor range admits, times safety/mu, overflows the \
             tick's precision"
        ),
    )
}

/// `N_req` for many loads with one controller (see `softgrip.required_force`): the same
/// configuration and computation as `host-sim required-force` (f64 precompute, f64 libm
/// tick, 64 force nodes). Returns a dict of lists plus `ellipse_axes`.
#[pyfunction]
#[pyo3(signature = (
    ft,
    mn,
    *,
    mu = 0.8,
    c_m_per_n_gamma = 2.5e-3,
    gamma = 0.5,
    shape = "rect",
    half_length_m = 0.01,
    k = 2.0,
    safety = 1.35,
    mode = "ellipse",
    skew = None,
    n_min_n = 0.2,
    n_max_n = 20.0,
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn required_force<'py>(
    py: Python<'py>,
    ft: Vec<f64>,
    mn: Vec<f64>,
    mu: f64,
    c_m_per_n_gamma: f64,
    gamma: f64,
    shape: &str,
    half_length_m: f64,
    k: f64,
    safety: f64,
    mode: &str,
    skew: Option<&Bound<'py, PyAny>>,
    n_min_n: f64,
    n_max_n: f64,
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
    let skew = match skew {
        Some(v) => skew_of(v)?,
        None => None,
    };
    // The configuration `host-sim required-force` builds (the core's rule configuration).
    let cfg = ControllerConfig {
        mu,
        shape: shape_of(py, shape)?,
        k,
        skew,
        c_m_per_n_gamma,
        gamma,
        half_length_m,
        safety,
        n_min_n,
        n_max_n,
        mode: mode_of(py, mode)?,
        ..ControllerConfig::rule_base()
    }
    .for_loads(ft_max, mn_max)
    .check()
    .map_err(|e| core_err(py, e, rf_name))?;
    let ctl =
        CoreController::<f64, Libm>::from_checked_in::<f64>(&cfg).map_err(|e| build_err(py, e))?;
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
            .tick_required_force(f, m, cfg.safety)
            .ok_or_else(none)?
            .force_n;
        let slip = ctl.slip_force(f, m).ok_or_else(none)?.force_n;
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
