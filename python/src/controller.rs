//! `Controller`: the per-tick controller, its status and reconfiguration.

use crate::*;

/// What one tick decided, besides the command (Rust's `TickOutput`).
#[pyclass(frozen, get_all, module = "softgrip")]
#[derive(Clone)]
pub(crate) struct TickStatus {
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
    /// The margin multiplying the safety factor [1]: `slip_margin · load_factor`.
    margin: f64,
    /// The slip response's part of the margin [1].
    slip_margin: f64,
    /// The load's part of the margin (cyclic or steady factor, else 1) [1].
    load_factor: f64,
    /// How far the target leads the requirement for the actuator's lag [N].
    lead_n: f64,
}

#[pymethods]
impl TickStatus {
    fn __repr__(&self) -> String {
        format!(
            "TickStatus(status={:?}, command_n={}, required_n={}, n_slip_n={}, \
             utilisation={}, fault_active={}, iterations={}, mu_estimate={}, margin={}, \
             slip_margin={}, load_factor={}, lead_n={})",
            self.status,
            self.command_n,
            self.required_n,
            self.n_slip_n,
            self.utilisation,
            if self.fault_active { "True" } else { "False" },
            self.iterations,
            self.mu_estimate,
            self.margin,
            self.slip_margin,
            self.load_factor,
            self.lead_n
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
            slip_margin: o.slip_margin,
            load_factor: o.load_factor,
            lead_n: o.lead_n,
        }
    }
}

/// The slip-prevention controller (f64 precompute and tick, libm).
///
/// Every keyword is a `ControllerConfig` field with its default (the same names, units
/// and defaults as `softgrip.default_config()`, the scene TOML's `[controller]` keys and
/// `host-sim`'s flags): forces in N, moments in N·m, lengths in m, times in s, rates in
/// N/s. `shape` is "rect" (a hemicylinder: the rectangular patch `[-l, l] × [-a, a]`) or
/// "disc" (a hemisphere). `initial_force_n` takes over a grip already applied (the first
/// command is within one tick's rate limit of it); by default the controller starts at
/// `n_min_n`. A bad value raises `ConfigError` (a `ValueError`) naming the keyword.
#[pyclass(module = "softgrip")]
pub(crate) struct Controller {
    inner: CoreController<f64, Libm>,
}

pub(crate) fn slip_of(py: Python<'_>, v: Option<&Bound<'_, PyAny>>) -> PyResult<SlipSignal> {
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
    #[pyo3(signature = (*, initial_force_n = None, **config))]
    // The fields come in `config` and go through `apply`, as `reconfigure`'s do; the text
    // signature is written out for `help()` (and is the only copy of the defaults outside
    // config.rs): tests/test_vocabulary.py checks it against `CONFIG_FIELDS` and
    // `default_config()`, so a field missing here fails there.
    #[pyo3(text_signature = "(*, mu=0.8, shape='rect', k=2.0, skew=None, \
        c_m_per_n_gamma=0.0025, gamma=0.5, half_length_m=0.01, safety=1.35, n_min_n=0.2, \
        n_max_n=20.0, rise_rate_n_per_s=400.0, fall_rate_n_per_s=20.0, tick_period_s=0.001, \
        stale_timeout_s=0.02, fault_force_n=10.0, force_range_n=100.0, \
        moment_range_nm=2.0, mode='ellipse', force_nodes=48, quadrature_order=28, \
        table_samples=48, aspect_count=8, actuator_lag_s=0.0, actuator_slew_n_per_s=1e999, \
        disc_torsion_factor=1.5, cyclic_factor=1.45, steady_factor=0.85, steady_ramp_s=0.5, \
        slip_step_incipient=0.05, slip_step_gross=0.3, slip_margin_max=3.0, \
        creep_margin_max=1.1, mu_floor_fraction=0.5, untold_lag_s=0.04, \
        initial_force_n=None)")]
    fn new(
        py: Python<'_>,
        initial_force_n: Option<f64>,
        config: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let cfg = apply(py, ControllerConfig::DEFAULT, config)?;
        let mut inner = build(py, cfg)?;
        if let Some(n) = initial_force_n {
            let n = finite(py, "initial_force_n", n)?;
            inner.start_at(n);
        }
        Ok(Self { inner })
    }

    /// One control tick. Returns `(command [N], TickStatus)`.
    ///
    /// - `ft`: the tangential force [N], `|f_t|` or its two components.
    /// - `mn`: the torsional moment [N·m].
    /// - `t`: the measurement's timestamp [s] on a monotonic clock (rounded to µs). Each
    ///   tick's must be 1 µs to 1 s (or four tick periods, if longer) after the last
    ///   accepted one. A repeated or earlier stamp (or a jump into the far future) is
    ///   refused: the tick returns status "stale_input", the command holds, the frame
    ///   is counted in `time_rejections`, and after `stale_timeout_s` of refusals the
    ///   command goes to the fault force. Three refused stamps in a row that follow each
    ///   other by plausible steps re-anchor the clock (a sensor restart).
    /// - `slip`: the tactile slip signal. None or "none": no slip seen (or no sensor).
    ///   "incipient": the patch's edge slides while its centre sticks; acted on once it
    ///   has lasted 2 ms: the margin rises by 0.05 (if it persists, μ̂ is lowered too).
    ///   "gross": the object slides or turns in the grasp; acted on at once: the margin
    ///   rises by 0.3 and μ̂ is lowered to what the load at slip implies. Either way the
    ///   command jumps to the new requirement; a report at a utilisation below 0.4
    ///   moves the margin only. Both relax back once the signal stops.
    ///   A soft contact creeps under any load (its bristles stretch without sliding),
    ///   so derive the signal from relative *sliding*, not from motion: report
    ///   "gross" when the object's displacement relative to the fingertip keeps growing
    ///   beyond the skin's elastic range (e.g. more than 0.5 mm over 20 ms), and
    ///   "incipient" when a sensor sees sliding at the patch's edge (vibration bursts,
    ///   shear-field edge slip) while the centre sticks; a plain velocity threshold
    ///   fires on creep (docs/sensor-inputs.md).
    /// - `normal_force`: the measured normal force [N] (default: the present command).
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

    /// `N_req` [N] of a load without touching the state: what the tick asks of a steady
    /// load at `safety` (the configured one by default); a round patch's moment carries
    /// the core's `DISC_TORSION_SAFETY_FACTOR` on top of it.
    #[pyo3(signature = (ft, mn, safety=None))]
    fn required_force(&self, ft: f64, mn: f64, safety: Option<f64>) -> Option<f64> {
        let s = safety.unwrap_or(self.inner.config().safety);
        self.inner.tick_required_force(ft, mn, s).map(|r| r.force_n)
    }

    /// `N_slip` [N] of a load without touching the state: the normal force at which the
    /// model's contact starts to slip (no safety factor).
    fn slip_force(&self, ft: f64, mn: f64) -> Option<f64> {
        self.inner.slip_force(ft, mn).map(|r| r.force_n)
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

    /// The actuator's lag the controller has identified [s] (0: an ideal actuator, or
    /// none seen yet); `config["actuator_lag_s"]` is the one it was told.
    #[getter]
    fn actuator_lag_estimate_s(&self) -> f64 {
        self.inner.actuator_lag_estimate_s()
    }

    /// The actuator's slew the controller has identified [N/s] (the configured one, inf
    /// when not given, until a slew-limited tick is seen).
    #[getter]
    fn actuator_slew_estimate_n_per_s(&self) -> f64 {
        self.inner.actuator_slew_estimate_n_per_s()
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
