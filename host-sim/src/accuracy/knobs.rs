//! The knobs, the configurations that vary them, and what each configuration leaves in
//! error and costs in time.
//!
//! Every configuration is measured the same way, on two fingers (the default
//! [`ControllerConfig`], a rectangle whose contact grows with the force, and a Hertzian
//! disc), against the exact f64 answers of [`super::exact`]:
//!
//! - **pitch error**: the moment arm `a·pitch` the configuration stores at its grid forces
//!   against `a·pitch` with the converged pitch, worst relative error over both fingers;
//! - **surface error**: the largest radial error of the surface the tick tests the load
//!   against (arm interpolation, Eq. 10 ellipse or stored table, aspect interpolation)
//!   against the exact surface, `|u_exact/u − 1|` over a grid of forces and directions;
//! - **force error**: `N_req(s)` from a real tick against the exact rule's answer, over a
//!   fixed set of loads spread over directions and magnitudes; against the exact surface
//!   (both fingers), against the configuration's own rule (the ellipse rule with the exact
//!   pitch for ellipse mode), and the largest under-ask (the unsafe side);
//! - **costs**: host time of the start-up precomputation and of one tick, medians of
//!   repeated runs on the rectangle.

use super::exact::{exact_tick, ExactSurface, Finger, Rule};
use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, Libm, Measurement, Micromath, Mode, TickMath,
};
use softgrip::Real;
use std::hint::black_box;
use std::time::Instant;

/// How much work a run does: the quick run and the full run differ only here.
#[derive(Debug, Clone)]
pub struct Budget {
    /// Whether this is `--quick`.
    pub quick: bool,
    /// Target forces `N*` of the load set (log-spaced in `[0.4, 15]` N).
    pub load_forces: usize,
    /// Directions of the load set, from pure force to pure torsion.
    pub load_directions: usize,
    /// Forces of the surface-error grid (log-spaced over the grid range).
    pub grid_forces: usize,
    /// Directions of the surface-error grid.
    pub grid_directions: usize,
    /// Timing rounds: each round times every configuration's start-up once and its tick
    /// once (round-robin, so that a burst of load on the shared machine spreads over all
    /// configurations instead of biasing one); the report gives the medians.
    pub rounds: usize,
    /// Passes over the 256 timing loads per tick repetition.
    pub tick_passes: usize,
    /// Loads per round of the exact-per-tick timing.
    pub exact_tick_loads: usize,
    /// Quadrature orders tried.
    pub orders: Vec<u16>,
    /// Centre-of-rotation samples tried.
    pub samples: Vec<u16>,
    /// Aspect grid sizes tried.
    pub aspects: Vec<u16>,
    /// Force-node counts tried.
    pub nodes: Vec<u16>,
}

impl Budget {
    /// The quick run (`--quick`): under a minute on two cores.
    pub fn quick() -> Self {
        Self {
            quick: true,
            load_forces: 4,
            load_directions: 5,
            grid_forces: 6,
            grid_directions: 12,
            rounds: 5,
            tick_passes: 4,
            exact_tick_loads: 8,
            orders: vec![8, 16, 28],
            samples: vec![8, 32, 48],
            aspects: vec![2, 8],
            nodes: vec![8, 48],
        }
    }

    /// The full run.
    pub fn full() -> Self {
        Self {
            quick: false,
            load_forces: 10,
            load_directions: 11,
            grid_forces: 24,
            grid_directions: 64,
            rounds: 21,
            tick_passes: 16,
            exact_tick_loads: 32,
            orders: vec![4, 6, 8, 12, 16, 20, 28, 40],
            samples: vec![8, 16, 24, 32, 48, 64, 96, 128],
            aspects: vec![2, 3, 4, 6, 8, 12],
            nodes: vec![4, 8, 16, 24, 32, 48, 64],
        }
    }
}

/// Median of `v` (0 for an empty set).
pub fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Evenly log-spaced values from `lo` to `hi` inclusive.
pub fn log_space(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![lo];
    }
    (0..n)
        .map(|i| (lo.ln() + (hi.ln() - lo.ln()) * i as f64 / (n - 1) as f64).exp())
        .collect()
}

/// One load of the error set, with its exact answers.
#[derive(Debug, Clone, Copy)]
pub struct Load {
    /// Tangential force components [N].
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
    /// Torsional moment [N·m].
    pub mn: f64,
    /// Measured normal force [N].
    pub n_meas: f64,
    /// `N_req(s)` of the ellipse rule with the exact pitch.
    pub n_ellipse: f64,
    /// `N_req(s)` of the exact surface.
    pub n_exact: f64,
}

/// One point of the surface-error grid: a normalised load at a normal force, with its
/// exact utilisation.
#[derive(Debug, Clone, Copy)]
pub struct GridPoint {
    /// Normal force [N].
    pub n: f64,
    /// Tangential force [N].
    pub ft: f64,
    /// Torsional moment [N·m].
    pub mn: f64,
    /// Its utilisation on the exact surface.
    pub u_exact: f64,
}

/// One finger with its references.
#[derive(Debug, Clone)]
pub struct FingerRef {
    /// "rectangle" or "disc".
    pub name: &'static str,
    /// The finger and its converged surface.
    pub reference: ExactSurface,
    /// The error loads.
    pub loads: Vec<Load>,
    /// The surface-error grid.
    pub grid: Vec<GridPoint>,
    /// Largest radial gap between the Eq. 10 ellipse and the exact surface over the grid.
    pub ellipse_gap: f64,
}

/// The default rectangle ([`ControllerConfig::default`]).
pub fn rect_config() -> ControllerConfig {
    ControllerConfig::default()
}

/// The disc: a hemispherical fingertip, `k = 2`, Hertzian growth `a = 2.5 mm·N^⅓`.
pub fn disc_config() -> ControllerConfig {
    ControllerConfig {
        shape: FingerShape::Disc,
        gamma: 1.0 / 3.0,
        ..ControllerConfig::default()
    }
}

impl FingerRef {
    /// Builds the loads, the grid and their exact answers for `cfg`.
    pub fn build(name: &'static str, cfg: ControllerConfig, b: &Budget) -> Result<Self, String> {
        let reference = ExactSurface::reference(Finger::new(cfg)?)?;
        let finger = reference.finger().clone();
        let s = cfg.safety;
        let mut loads = Vec::new();
        let mut i = 0usize;
        for &n_star in &log_space(0.4, 15.0, b.load_forces) {
            let arm = finger.a(n_star) * reference.pitch_at(n_star);
            for j in 0..b.load_directions {
                let psi =
                    std::f64::consts::FRAC_PI_2 * j as f64 / (b.load_directions.max(2) - 1) as f64;
                // On the Eq. 10 ellipse at N*: the ellipse rule's answer is N* itself.
                let ft = cfg.mu * n_star * psi.cos() / s;
                let mn = cfg.mu * n_star * arm * psi.sin() / s;
                let beta = 0.61 * i as f64;
                let (fx, fy) = (ft * beta.cos(), ft * beta.sin());
                let (big_f, big_m) = (s * ft / cfg.mu, s * mn / cfg.mu);
                loads.push(Load {
                    fx,
                    fy,
                    mn,
                    n_meas: n_star * (0.8 + 0.05 * (i % 9) as f64),
                    n_ellipse: reference.required(Rule::Ellipse, big_f, big_m),
                    n_exact: reference.required(Rule::Exact, big_f, big_m),
                });
                i += 1;
            }
        }
        let mut grid = Vec::new();
        let mut ellipse_gap = 0.0f64;
        let forces = log_space(cfg.n_min_n * 1.25, cfg.n_max_n * 0.975, b.grid_forces);
        for &n in &forces {
            let model = reference.model_at(n);
            let pitch = model.pitch();
            let a = finger.a(n);
            for j in 0..b.grid_directions {
                // Directions strictly between the axes, where the tables interpolate.
                let psi = std::f64::consts::FRAC_PI_2 * (j as f64 + 0.5) / b.grid_directions as f64;
                let (f, m) = (0.5 * psi.cos(), 0.5 * pitch * psi.sin());
                let u_exact = reference.utilisation_normalised(&model, f, m);
                // The Eq. 10 ellipse's utilisation is 0.5 here by construction.
                ellipse_gap = ellipse_gap.max((u_exact / 0.5 - 1.0).abs());
                grid.push(GridPoint {
                    n,
                    ft: cfg.mu * n * f,
                    mn: cfg.mu * n * a * m,
                    u_exact,
                });
            }
        }
        Ok(Self {
            name,
            reference,
            loads,
            grid,
            ellipse_gap,
        })
    }
}

/// The tick's precision and where the start-up precomputation runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Precision {
    /// f32 precomputation, f32 tick (the firmware's default).
    F32,
    /// f64 precomputation, f32 tick (`precompute-f64`).
    F64Precompute,
    /// f64 precomputation, f64 tick (the host).
    F64,
}

impl Precision {
    /// How the report names it.
    pub fn label(self) -> &'static str {
        match self {
            Precision::F32 => "f32 start-up, f32 tick",
            Precision::F64Precompute => "f64 start-up, f32 tick",
            Precision::F64 => "f64 start-up, f64 tick",
        }
    }
}

/// The tick's square root.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MathKind {
    /// `libm` (on the target the FPU's `VSQRT`, bit-identical).
    Libm,
    /// `micromath`'s approximation.
    Micromath,
}

/// How the tick decides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Engine {
    /// The controller's start-up grid.
    Grid {
        /// Ellipse or table.
        table: bool,
        /// Precision.
        precision: Precision,
        /// Square root.
        math: MathKind,
    },
    /// The exact surface integrated at every trial force (f64).
    Exact,
}

/// One configuration: an engine and the grid sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Variant {
    /// How the tick decides.
    pub engine: Engine,
    /// Quadrature order.
    pub order: u16,
    /// Table samples (table mode only).
    pub samples: u16,
    /// Aspect grid size (table mode only).
    pub aspects: u16,
    /// Force nodes (grid only).
    pub nodes: u16,
}

impl Variant {
    /// The project's defaults in ellipse or table mode.
    pub fn default_mode(table: bool) -> Self {
        let d = ControllerConfig::default();
        Self {
            engine: Engine::Grid {
                table,
                precision: Precision::F32,
                math: MathKind::Libm,
            },
            order: d.quadrature_order,
            samples: d.table_samples,
            aspects: d.aspect_count,
            nodes: d.force_nodes,
        }
    }

    /// The same configuration with the settings it does not use set to the defaults, so
    /// that equal configurations compare equal.
    pub fn normalised(mut self) -> Self {
        let d = ControllerConfig::default();
        match self.engine {
            Engine::Grid { table: false, .. } => {
                self.samples = d.table_samples;
                self.aspects = d.aspect_count;
            }
            Engine::Grid { table: true, .. } => {}
            Engine::Exact => {
                self.samples = d.table_samples;
                self.aspects = d.aspect_count;
                self.nodes = d.force_nodes;
            }
        }
        self
    }

    /// The mode column: "ellipse", "table" or "exact".
    pub fn mode_name(&self) -> &'static str {
        match self.engine {
            Engine::Grid { table: false, .. } => "ellipse",
            Engine::Grid { table: true, .. } => "table",
            Engine::Exact => "exact",
        }
    }

    /// A full description, for the Pareto table.
    pub fn describe(&self) -> String {
        match self.engine {
            Engine::Exact => format!("exact per tick (f64, order {})", self.order),
            Engine::Grid {
                table,
                precision,
                math,
            } => {
                let p = match precision {
                    Precision::F32 => "f32",
                    Precision::F64Precompute => "f64→f32",
                    Precision::F64 => "f64",
                };
                let m = match math {
                    MathKind::Libm => "",
                    MathKind::Micromath => ", micromath",
                };
                if table {
                    format!(
                        "table, order {}, {} samples, {} aspects, {} nodes, {p}{m}",
                        self.order, self.samples, self.aspects, self.nodes
                    )
                } else {
                    format!(
                        "ellipse, order {}, {} nodes, {p}{m}",
                        self.order, self.nodes
                    )
                }
            }
        }
    }

    /// The controller configuration for `base`.
    pub fn config(&self, base: &ControllerConfig) -> ControllerConfig {
        let table = matches!(self.engine, Engine::Grid { table: true, .. });
        ControllerConfig {
            mode: if table { Mode::Table } else { Mode::Ellipse },
            quadrature_order: self.order,
            table_samples: self.samples,
            aspect_count: self.aspects,
            force_nodes: self.nodes,
            ..*base
        }
    }
}

/// What one configuration leaves in error and costs.
#[derive(Debug, Clone, Copy, Default)]
pub struct Measured {
    /// Pitch error (relative, worst over both fingers).
    pub pitch_err: f64,
    /// Surface error (relative radial), rectangle and disc.
    pub surface_err: [f64; 2],
    /// Force error against the configuration's own rule (relative, worst of both).
    pub n_err_own: f64,
    /// Force error against the exact surface (relative), rectangle and disc.
    pub n_err: [f64; 2],
    /// The largest under-ask against the exact surface (relative, ≥ 0).
    pub under_ask: f64,
    /// Host start-up time [µs] (rectangle, median).
    pub precompute_us: f64,
    /// Host time per tick [ns] (rectangle, median).
    pub tick_ns: f64,
}

impl Measured {
    /// The force error the Pareto front ranks by: the worse finger against the exact
    /// surface.
    pub fn error(&self) -> f64 {
        self.n_err[0].max(self.n_err[1])
    }
}

/// The 256 unrelated timing loads of `benches/tick.rs`: pure translation to pure torsion,
/// answers over the grid and beyond.
pub fn timing_loads() -> Vec<(f64, f64, f64, f64)> {
    (0..256)
        .map(|i| {
            let phase = i as f64 * 0.173;
            let scale = 0.05 + 4.0 * ((i * 37 % 256) as f64 / 256.0);
            (
                scale * phase.cos(),
                0.3 * scale * phase.sin(),
                0.01 * scale * (1.0 + (1.7 * phase).sin()),
                2.0 + scale,
            )
        })
        .collect()
}

fn rel(got: f64, want: f64) -> f64 {
    got / want - 1.0
}

/// Accumulates the force errors of one finger.
#[derive(Debug, Default)]
struct ForceErrors {
    own: f64,
    exact: f64,
    under: f64,
}

impl ForceErrors {
    fn add(&mut self, got: f64, load: &Load, own_is_ellipse: bool) {
        let own_want = if own_is_ellipse {
            load.n_ellipse
        } else {
            load.n_exact
        };
        self.own = self.own.max(rel(got, own_want).abs());
        let e = rel(got, load.n_exact);
        self.exact = self.exact.max(e.abs());
        self.under = self.under.max(-e);
    }
}

fn measure_grid<T: Real, M: TickMath<T>, P: Real>(
    v: &Variant,
    fingers: &[FingerRef; 2],
) -> Result<Measured, String> {
    let table = matches!(v.engine, Engine::Grid { table: true, .. });
    let mut out = Measured::default();
    for (k, fr) in fingers.iter().enumerate() {
        let cfg = v.config(&fr.reference.finger().cfg);
        let mut ctl = Controller::<T, M>::new_precomputed_in::<P>(cfg)
            .map_err(|e| format!("{}: {}: {e}", fr.name, v.describe()))?;
        let finger = fr.reference.finger();
        let cap = ctl.capacity();
        for (&n, &arm) in cap.forces_n().iter().zip(cap.arms_m()) {
            let n = n.to_f64();
            let want = finger.a(n) * fr.reference.pitch_at(n);
            out.pitch_err = out.pitch_err.max(rel(arm.to_f64(), want).abs());
        }
        for g in &fr.grid {
            let u = ctl
                .utilisation(T::of(g.ft), T::of(g.mn), T::of(g.n))
                .map_or(f64::NAN, |u| u.to_f64());
            out.surface_err[k] = out.surface_err[k].max((g.u_exact / u - 1.0).abs());
        }
        let mut errs = ForceErrors::default();
        for (i, load) in fr.loads.iter().enumerate() {
            let o = ctl.tick(&Measurement {
                tangential_force_n: [T::of(load.fx), T::of(load.fy)],
                torsional_moment_nm: T::of(load.mn),
                normal_force_n: T::of(load.n_meas),
                timestamp_us: 1000 * (i as u64 + 1),
                slip: Default::default(),
            });
            errs.add(o.required_n.to_f64(), load, !table);
        }
        out.n_err_own = out.n_err_own.max(errs.own);
        out.n_err[k] = errs.exact;
        out.under_ask = out.under_ask.max(errs.under);
    }
    Ok(out)
}

/// Times one configuration once: `(start-up [µs], tick [ns])`.
pub type Timer = Box<dyn FnMut() -> (f64, f64)>;

fn timer_grid<T: Real, M: TickMath<T> + 'static, P: Real>(
    cfg: ControllerConfig,
    b: &Budget,
) -> Result<Timer, String> {
    let mut ctl = Controller::<T, M>::new_precomputed_in::<P>(cfg).map_err(|e| e.to_string())?;
    let loads: Vec<Measurement<T>> = timing_loads()
        .into_iter()
        .map(|(fx, fy, mn, n)| Measurement {
            tangential_force_n: [T::of(fx), T::of(fy)],
            torsional_moment_nm: T::of(mn),
            normal_force_n: T::of(n),
            timestamp_us: 0,
            slip: Default::default(),
        })
        .collect();
    let passes = b.tick_passes;
    let mut stamp = 0u64;
    Ok(Box::new(move || {
        let t0 = Instant::now();
        let c = Controller::<T, M>::new_precomputed_in::<P>(black_box(cfg));
        let startup = t0.elapsed();
        black_box(&c);
        let t0 = Instant::now();
        for _ in 0..passes {
            for m in &loads {
                stamp += 1000;
                let mut m = *m;
                m.timestamp_us = stamp;
                black_box(ctl.tick(black_box(&m)));
            }
        }
        let ticks = t0.elapsed();
        (
            startup.as_secs_f64() * 1e6,
            ticks.as_secs_f64() * 1e9 / (passes * loads.len()) as f64,
        )
    }))
}

/// The per-tick exact rule's surface: the default order, tolerances fit for a control
/// loop (radius to 1e-9 in the sweep parameter, forces to 1e-8 relative).
pub fn exact_engine(finger: Finger, order: u16) -> Result<ExactSurface, String> {
    ExactSurface::new(finger, usize::from(order), 1e-9, 1e-8)
}

fn measure_exact(v: &Variant, fingers: &[FingerRef; 2]) -> Result<Measured, String> {
    let mut out = Measured::default();
    for (k, fr) in fingers.iter().enumerate() {
        let finger = fr.reference.finger().clone();
        let surface = exact_engine(finger.clone(), v.order)?;
        for g in fr.grid.iter().step_by(3) {
            let want = finger.a(g.n) * fr.reference.pitch_at(g.n);
            let got = finger.a(g.n) * surface.pitch_at(g.n);
            out.pitch_err = out.pitch_err.max(rel(got, want).abs());
        }
        for g in &fr.grid {
            let cfg = &finger.cfg;
            let u = surface.utilisation(Rule::Exact, g.ft / cfg.mu, g.mn / cfg.mu, g.n);
            out.surface_err[k] = out.surface_err[k].max((g.u_exact / u - 1.0).abs());
        }
        let mut errs = ForceErrors::default();
        for load in &fr.loads {
            let o = exact_tick(&surface, load.fx, load.fy, load.mn, load.n_meas);
            errs.add(o.required_n, load, false);
        }
        out.n_err_own = out.n_err_own.max(errs.own);
        out.n_err[k] = errs.exact;
        out.under_ask = out.under_ask.max(errs.under);
    }
    Ok(out)
}

fn timer_exact(v: &Variant, finger: Finger, b: &Budget) -> Result<Timer, String> {
    let surface = exact_engine(finger.clone(), v.order)?;
    let order = v.order;
    let loads: Vec<_> = timing_loads()
        .into_iter()
        .step_by(256 / b.exact_tick_loads.clamp(1, 256))
        .collect();
    Ok(Box::new(move || {
        let t0 = Instant::now();
        let s = exact_engine(black_box(finger.clone()), order);
        let startup = t0.elapsed();
        black_box(&s);
        let t0 = Instant::now();
        for &(fx, fy, mn, n) in &loads {
            black_box(exact_tick(&surface, black_box(fx), fy, mn, n));
        }
        let ticks = t0.elapsed();
        (
            startup.as_secs_f64() * 1e6,
            ticks.as_secs_f64() * 1e9 / loads.len() as f64,
        )
    }))
}

/// A [`Timer`] for one configuration, on the rectangle (`fingers[0]`).
pub fn timer(v: &Variant, fingers: &[FingerRef; 2], b: &Budget) -> Result<Timer, String> {
    let finger = fingers[0].reference.finger().clone();
    let cfg = v.config(&finger.cfg);
    match v.engine {
        Engine::Exact => timer_exact(v, finger, b),
        Engine::Grid {
            precision, math, ..
        } => match (precision, math) {
            (Precision::F32, MathKind::Libm) => timer_grid::<f32, Libm, f32>(cfg, b),
            (Precision::F32, MathKind::Micromath) => timer_grid::<f32, Micromath, f32>(cfg, b),
            (Precision::F64Precompute, MathKind::Libm) => timer_grid::<f32, Libm, f64>(cfg, b),
            (Precision::F64Precompute, MathKind::Micromath) => {
                timer_grid::<f32, Micromath, f64>(cfg, b)
            }
            (Precision::F64, MathKind::Libm) => timer_grid::<f64, Libm, f64>(cfg, b),
            (Precision::F64, MathKind::Micromath) => Err("micromath has no f64 square root".into()),
        },
    }
}

/// Measures one configuration's errors (its costs stay 0: see [`timer`]).
pub fn measure(v: &Variant, fingers: &[FingerRef; 2]) -> Result<Measured, String> {
    match v.engine {
        Engine::Exact => measure_exact(v, fingers),
        Engine::Grid {
            precision, math, ..
        } => match (precision, math) {
            (Precision::F32, MathKind::Libm) => measure_grid::<f32, Libm, f32>(v, fingers),
            (Precision::F32, MathKind::Micromath) => {
                measure_grid::<f32, Micromath, f32>(v, fingers)
            }
            (Precision::F64Precompute, MathKind::Libm) => {
                measure_grid::<f32, Libm, f64>(v, fingers)
            }
            (Precision::F64Precompute, MathKind::Micromath) => {
                measure_grid::<f32, Micromath, f64>(v, fingers)
            }
            (Precision::F64, MathKind::Libm) => measure_grid::<f64, Libm, f64>(v, fingers),
            (Precision::F64, MathKind::Micromath) => Err("micromath has no f64 square root".into()),
        },
    }
}

/// Which table a row belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Knob {
    /// Quadrature order.
    Order,
    /// Centre-of-rotation samples per sweep.
    Samples,
    /// Size of the aspect grid.
    Aspects,
    /// Interpolation: force nodes of the moment arm.
    Nodes,
    /// f32 against f64 precomputation.
    Precision,
    /// `libm` against `micromath` in the tick.
    Math,
    /// Ellipse against table against exact integration per tick.
    Rule,
}

impl Knob {
    /// Every knob, in report order.
    pub const ALL: [Knob; 7] = [
        Knob::Order,
        Knob::Samples,
        Knob::Aspects,
        Knob::Nodes,
        Knob::Precision,
        Knob::Math,
        Knob::Rule,
    ];

    /// The section title.
    pub fn title(self) -> &'static str {
        match self {
            Knob::Order => "Quadrature order",
            Knob::Samples => "Centre-of-rotation samples per sweep",
            Knob::Aspects => "Size of the aspect grid",
            Knob::Nodes => "Interpolation: force nodes of the moment arm",
            Knob::Precision => "f32 against f64 precomputation",
            Knob::Math => "libm against micromath in the tick",
            Knob::Rule => "Ellipse against table against exact integration per tick",
        }
    }

    /// The rows of this knob's table: a setting's label and its configuration.
    pub fn rows(self, b: &Budget) -> Vec<(String, Variant)> {
        let both = [false, true];
        let mut rows = Vec::new();
        match self {
            Knob::Order => {
                for table in both {
                    for &o in &b.orders {
                        let v = Variant {
                            order: o,
                            ..Variant::default_mode(table)
                        };
                        rows.push((format!("order {o}"), v));
                    }
                }
            }
            Knob::Samples => {
                for &s in &b.samples {
                    let v = Variant {
                        samples: s,
                        ..Variant::default_mode(true)
                    };
                    rows.push((format!("{s} samples"), v));
                }
            }
            Knob::Aspects => {
                for &a in &b.aspects {
                    let v = Variant {
                        aspects: a,
                        ..Variant::default_mode(true)
                    };
                    rows.push((format!("{a} aspects"), v));
                }
            }
            Knob::Nodes => {
                for table in both {
                    for &n in &b.nodes {
                        let v = Variant {
                            nodes: n,
                            ..Variant::default_mode(table)
                        };
                        rows.push((format!("{n} nodes"), v));
                    }
                }
            }
            Knob::Precision => {
                for table in both {
                    for p in [Precision::F32, Precision::F64Precompute, Precision::F64] {
                        let v = Variant {
                            engine: Engine::Grid {
                                table,
                                precision: p,
                                math: MathKind::Libm,
                            },
                            ..Variant::default_mode(table)
                        };
                        rows.push((p.label().to_string(), v));
                    }
                }
            }
            Knob::Math => {
                for table in both {
                    for (name, m) in [("libm", MathKind::Libm), ("micromath", MathKind::Micromath)]
                    {
                        let v = Variant {
                            engine: Engine::Grid {
                                table,
                                precision: Precision::F32,
                                math: m,
                            },
                            ..Variant::default_mode(table)
                        };
                        rows.push((name.to_string(), v));
                    }
                }
            }
            Knob::Rule => {
                rows.push(("ellipse (Eq. 10)".into(), Variant::default_mode(false)));
                rows.push(("table (chords)".into(), Variant::default_mode(true)));
                rows.push((
                    "exact integration".into(),
                    Variant {
                        engine: Engine::Exact,
                        ..Variant::default_mode(false)
                    },
                ));
            }
        }
        rows.into_iter().map(|(s, v)| (s, v.normalised())).collect()
    }
}
