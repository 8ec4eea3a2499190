//! Measuring a configuration: errors against the exact answers, and host times.

use super::*;

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

pub(super) fn rel(got: f64, want: f64) -> f64 {
    got / want - 1.0
}

/// Accumulates the force errors of one finger.
#[derive(Debug, Default)]
pub(super) struct ForceErrors {
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

pub(super) fn measure_grid<T: Real, M: TickMath<T>, P: Real>(
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

pub(super) fn timer_grid<T: Real, M: TickMath<T> + 'static, P: Real>(
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

pub(super) fn measure_exact(v: &Variant, fingers: &[FingerRef; 2]) -> Result<Measured, String> {
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
        // As the tick does, a round patch's moment carries its own factor.
        let beta = finger.cfg.torsion_factor();
        for load in &fr.loads {
            let o = exact_tick(&surface, load.fx, load.fy, beta * load.mn, load.n_meas);
            errs.add(o.required_n, load, false);
        }
        out.n_err_own = out.n_err_own.max(errs.own);
        out.n_err[k] = errs.exact;
        out.under_ask = out.under_ask.max(errs.under);
    }
    Ok(out)
}

pub(super) fn timer_exact(v: &Variant, finger: Finger, b: &Budget) -> Result<Timer, String> {
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
        use MathKind::{Libm, Micromath};
        let both = [false, true];
        let rows = match self {
            Knob::Order => setting_rows(&both, &b.orders, |o, v| {
                (format!("order {o}"), Variant { order: o, ..v })
            }),
            Knob::Samples => setting_rows(&[true], &b.samples, |s, v| {
                (format!("{s} samples"), Variant { samples: s, ..v })
            }),
            Knob::Aspects => setting_rows(&[true], &b.aspects, |a, v| {
                (format!("{a} aspects"), Variant { aspects: a, ..v })
            }),
            Knob::Nodes => setting_rows(&both, &b.nodes, |n, v| {
                (format!("{n} nodes"), Variant { nodes: n, ..v })
            }),
            Knob::Precision => engine_rows(
                [Precision::F32, Precision::F64Precompute, Precision::F64]
                    .map(|p| (p.label(), p, Libm)),
            ),
            Knob::Math => engine_rows([
                ("libm", Precision::F32, Libm),
                ("micromath", Precision::F32, Micromath),
            ]),
            Knob::Rule => vec![
                ("ellipse (Eq. 10)".into(), Variant::default_mode(false)),
                ("table (chords)".into(), Variant::default_mode(true)),
                (
                    "exact integration".into(),
                    Variant {
                        engine: Engine::Exact,
                        ..Variant::default_mode(false)
                    },
                ),
            ],
        };
        rows.into_iter().map(|(s, v)| (s, v.normalised())).collect()
    }
}

/// A row for each of `values` in each mode of `tables` (false: ellipse, true: table),
/// mode by mode: `row` labels the value and sets it in the mode's default configuration.
fn setting_rows(
    tables: &[bool],
    values: &[u16],
    row: impl Fn(u16, Variant) -> (String, Variant),
) -> Vec<(String, Variant)> {
    let mut rows = Vec::new();
    for &table in tables {
        for &x in values {
            rows.push(row(x, Variant::default_mode(table)));
        }
    }
    rows
}

/// A row for each labelled precision and square root of `engines`, in ellipse mode and
/// then in table mode, the rest of the configuration the mode's default.
fn engine_rows<const N: usize>(
    engines: [(&str, Precision, MathKind); N],
) -> Vec<(String, Variant)> {
    let mut rows = Vec::new();
    for table in [false, true] {
        for (name, precision, math) in engines {
            let v = Variant {
                engine: Engine::Grid {
                    table,
                    precision,
                    math,
                },
                ..Variant::default_mode(table)
            };
            rows.push((name.to_string(), v));
        }
    }
    rows
}
