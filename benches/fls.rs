//! Cost of the limit surface: a 128-sample sweep into an [`FlsTable`], one
//! [`FlsModel::point`], and one point of the independent brute-force 2-D integrator of
//! `softgrip-reference` (reference/), so that one run gives the speed-up of the fast path,
//! `brute_force_point × 128 / sweep_128`.
//!
//! Run with `cargo bench --bench fls` (about a minute on two cores).

mod common;

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};

/// The skew `(Δ/a, α, h/a)` of the paper: `Δ/a = 0.9`, `α = 1.1`, circular locus.
const PAPER_SKEW: (f64, f64, f64) = (0.9, 1.1, 0.45);

fn model(shape: Shape, skew: Option<(f64, f64, f64)>) -> FlsModel<f64> {
    FlsModel::new(FlsConfig {
        shape,
        k: 2.0,
        skew,
        order: QuadratureOrder::DEFAULT,
    })
    .expect("valid configuration")
}

fn cases() -> [(&'static str, FlsModel<f64>); 4] {
    let square = Shape::Rect { aspect: 1.0 };
    [
        ("rect_k2_symmetric", model(square, None)),
        ("rect_k2_skewed", model(square, Some(PAPER_SKEW))),
        ("disc_k2_symmetric", model(Shape::Disc, None)),
        ("disc_k2_skewed", model(Shape::Disc, Some(PAPER_SKEW))),
    ]
}

fn sweep_128(c: &mut Criterion) {
    let mut group = c.benchmark_group("sweep_128");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(3));
    // The skewed disc (a 2-D integral per point, ~0.5 ms) is left out: it is measured by
    // `point` below, and 128 of it would dominate the run.
    for (name, m) in cases().into_iter().take(3) {
        common::id(&format!("sweep_128/{name}"));
        group.bench_function(name, |b| {
            b.iter(|| FlsTable::<f64, 130>::sweep(black_box(&m), black_box(128)).expect("fits"))
        });
    }
    group.finish();
}

fn point(c: &mut Criterion) {
    let mut group = c.benchmark_group("point");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    for (name, m) in cases() {
        common::id(&format!("point/{name}"));
        group.bench_function(name, |b| b.iter(|| black_box(&m).point(black_box(0.7))));
    }
    group.finish();
}

fn brute_force_point(c: &mut Criterion) {
    use softgrip_reference::{Case, Patch};
    let mut group = c.benchmark_group("brute_force_point");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    let case = Case {
        patch: Patch::Rect { aspect: 1.0 },
        k: 2.0,
        skew: None,
    };
    // Rectangle l = a, k = 2, d = 0.7. Measured error of (f̃, m̃) against `cells = 256`:
    // cells = 6 (2 × 3 pieces × 6 cells × 4 × 4 points = 6 912 evaluations): 1.3e-6, the
    // "~1e-6" point for the speed ratio; cells = 32 (196 608 evaluations): 1e-10, the fast
    // path's own accuracy.
    for cells in [6, 32] {
        let name = format!("rect_k2_d0.7_cells{cells}");
        common::id(&format!("brute_force_point/{name}"));
        group.bench_function(name, |b| {
            b.iter(|| case.point(black_box(0.7), black_box(cells)))
        });
    }
    group.finish();
}

criterion_group!(benches, sweep_128, point, brute_force_point);
criterion_main!(benches);
