//! The core's limit-surface point against the independent brute-force 2-D integration of
//! `softgrip-reference` (reference/), at matched accuracy: both are measured against the
//! converged core (order 128) over the same centres of rotation, and timed per point.

use super::knobs::{median, Budget};
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};
use softgrip_reference::{Case, Patch};
use std::hint::black_box;
use std::time::Instant;

/// The centres of rotation `d = d_c/a` measured: pure torsion, inside the patch, on its
/// edge, outside, far.
pub const DS: [f64; 6] = [0.0, 0.3, 0.7, 1.0, 1.7, 20.0];

/// One method at one setting: its worst error over [`DS`] and its time per point.
#[derive(Debug, Clone, Copy)]
pub struct Method {
    /// Quadrature order (core) or cells per piece (brute force).
    pub setting: usize,
    /// Worst error in `f̃` or `m̃` against the converged core.
    pub err: f64,
    /// Time per point \[µs\] (median).
    pub us: f64,
}

/// A matched pair: a brute-force setting and the cheapest core order at least as accurate.
#[derive(Debug, Clone, Copy)]
pub struct Matched {
    /// The brute force.
    pub brute: Method,
    /// The core (None if no order tried reaches it).
    pub core: Option<Method>,
}

/// The comparison.
#[derive(Debug, Clone)]
pub struct BruteReport {
    /// Every core order tried.
    pub core: Vec<Method>,
    /// Every brute-force cell count tried.
    pub brute: Vec<Method>,
    /// Each brute-force setting with the cheapest core order that matches it.
    pub matched: Vec<Matched>,
    /// The core at the default order.
    pub core_default: Method,
    /// The cheapest brute force that reaches the default order's error, or the most
    /// accurate one tried if none does (then `reached` is false).
    pub brute_at_default: Method,
    /// Whether the brute force reached the default order's error.
    pub reached: bool,
}

impl BruteReport {
    /// Brute-force time over core time at the default order (a lower bound when the
    /// brute force did not reach the default order's error).
    pub fn ratio(&self) -> f64 {
        self.brute_at_default.us / self.core_default.us
    }

    /// The most accurate brute-force setting that some core order matches, with that
    /// order and the speed ratio.
    pub fn best_matched(&self) -> Option<(Method, Method, f64)> {
        self.matched
            .iter()
            .filter_map(|m| m.core.map(|c| (m.brute, c, m.brute.us / c.us)))
            .min_by(|a, b| a.0.err.total_cmp(&b.0.err))
    }
}

fn core_model(order: usize) -> Result<FlsModel<f64>, String> {
    FlsModel::new(FlsConfig {
        shape: Shape::Rect { aspect: 1.0 },
        k: 2.0,
        skew: None,
        order: QuadratureOrder::new(order).map_err(|e| e.to_string())?,
    })
    .map_err(|e| e.to_string())
}

fn time_per_point(reps: usize, points: usize, mut f: impl FnMut()) -> f64 {
    let mut times = Vec::new();
    for _ in 0..reps {
        let t0 = Instant::now();
        f();
        times.push(t0.elapsed().as_secs_f64() * 1e6 / points as f64);
    }
    median(times)
}

/// Runs the comparison on the rectangle `l = a`, `k = 2` (symmetric).
pub fn compare(b: &Budget) -> Result<BruteReport, String> {
    let reference = core_model(128)?;
    let exact: Vec<(f64, f64)> = DS
        .iter()
        .map(|&d| {
            let p = reference.point(d);
            (p.f, p.m)
        })
        .collect();
    let core = core_methods(b, &exact)?;
    let brute = brute_methods(b, &exact);
    let matched = brute
        .iter()
        .map(|&bm| Matched {
            brute: bm,
            core: core.iter().copied().find(|cm| cm.err <= bm.err),
        })
        .collect();
    let default_order = QuadratureOrder::DEFAULT.nodes_per_side();
    let core_default = core
        .iter()
        .copied()
        .find(|m| m.setting == default_order)
        .ok_or("the default order was not measured")?;
    let (brute_at_default, reached) =
        match brute.iter().copied().find(|m| m.err <= core_default.err) {
            Some(m) => (m, true),
            None => (
                brute
                    .iter()
                    .copied()
                    .min_by(|x, y| x.err.total_cmp(&y.err))
                    .ok_or("no brute-force setting")?,
                false,
            ),
        };
    Ok(BruteReport {
        core,
        brute,
        matched,
        core_default,
        brute_at_default,
        reached,
    })
}

/// The worst error of the points `pts` (at [`DS`]) against `exact`, in `f̃` or `m̃`.
fn worst_err(pts: &[(f64, f64)], exact: &[(f64, f64)]) -> f64 {
    pts.iter()
        .zip(exact)
        .map(|(p, e)| (p.0 - e.0).abs().max((p.1 - e.1).abs()))
        .fold(0.0f64, f64::max)
}

/// The core at each quadrature order the budget tries, against `exact`.
fn core_methods(b: &Budget, exact: &[(f64, f64)]) -> Result<Vec<Method>, String> {
    let orders: Vec<usize> = if b.quick {
        vec![4, 6, 8, 12, 16, 20, 28]
    } else {
        vec![4, 5, 6, 7, 8, 10, 12, 14, 16, 20, 24, 28, 40]
    };
    let mut core = Vec::new();
    for &o in &orders {
        let model = core_model(o)?;
        let pts: Vec<(f64, f64)> = DS
            .iter()
            .map(|&d| {
                let p = model.point(d);
                (p.f, p.m)
            })
            .collect();
        let passes = if b.quick { 50 } else { 400 };
        let us = time_per_point(b.rounds, passes * DS.len(), || {
            for _ in 0..passes {
                for &d in &DS {
                    black_box(black_box(&model).point(black_box(d)));
                }
            }
        });
        core.push(Method {
            setting: o,
            err: worst_err(&pts, exact),
            us,
        });
    }
    Ok(core)
}

/// The brute force at each cell count the budget tries, against `exact`.
fn brute_methods(b: &Budget, exact: &[(f64, f64)]) -> Vec<Method> {
    let cells: Vec<usize> = if b.quick {
        vec![2, 4, 8, 16]
    } else {
        vec![2, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128]
    };
    let case = Case {
        patch: Patch::Rect { aspect: 1.0 },
        k: 2.0,
        skew: None,
    };
    let mut brute = Vec::new();
    for &c in &cells {
        let pts: Vec<(f64, f64)> = DS.iter().map(|&d| case.point(d, c)).collect();
        let reps = if c >= 32 { 3 } else { 5 };
        let us = time_per_point(reps, DS.len(), || {
            for &d in &DS {
                black_box(case.point(black_box(d), c));
            }
        });
        brute.push(Method {
            setting: c,
            err: worst_err(&pts, exact),
            us,
        });
    }
    brute
}
