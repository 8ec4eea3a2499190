//! Accuracy of the fast path at the default order against the same integrals at the highest
//! order (which converge to 1e-15 in f64; see the convergence test), at the hard places:
//! the centre of rotation at 0, 1e-12, on the patch edge, just off it and far away.

use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};

fn model(shape: Shape, k: f64, skew: Option<(f64, f64, f64)>, n: usize) -> FlsModel<f64> {
    FlsModel::new(FlsConfig {
        shape,
        k,
        skew,
        order: QuadratureOrder::new(n).unwrap(),
    })
    .unwrap()
}

const SKEW: Option<(f64, f64, f64)> = Some((0.9, 1.1, 0.45));

/// Skew `(Δ/a, α, h/a)`, if any.
type Skew = Option<(f64, f64, f64)>;

fn cases() -> Vec<(Shape, f64, Skew)> {
    let mut v = Vec::new();
    for k in [1.0, 2.0, 4.0, 50.0, f64::INFINITY] {
        v.push((Shape::Rect { aspect: 1.0 }, k, None));
        v.push((Shape::Rect { aspect: 1.0 }, k, SKEW));
        v.push((Shape::Disc, k, None));
    }
    v.push((Shape::Rect { aspect: 0.05 }, 2.0, SKEW));
    v.push((Shape::Rect { aspect: 20.0 }, 2.0, SKEW));
    v.push((Shape::Rect { aspect: 1.0 }, 2.0, Some((0.999, 1.1, 0.0))));
    v.push((Shape::Disc, 2.0, SKEW));
    v.push((Shape::Disc, 4.0, Some((0.6, 3.0, 0.5))));
    v
}

fn edge(shape: Shape) -> f64 {
    match shape {
        Shape::Rect { aspect } => aspect,
        Shape::Disc => 1.0,
    }
}

#[test]
fn default_order_is_within_1e9_of_the_converged_integral() {
    let mut worst: f64 = 0.0;
    for (shape, k, skew) in cases() {
        let fast = model(shape, k, skew, QuadratureOrder::DEFAULT.nodes_per_side());
        let exact = model(shape, k, skew, 128);
        let e = edge(shape);
        for d in [
            0.0,
            1e-12,
            0.05,
            0.5 * e,
            e * (1.0 - 1e-9),
            e,
            e * (1.0 + 1e-9),
            1.5 * e,
            3.0,
            1e3,
            1e12,
        ] {
            let (a, b) = (fast.point(d), exact.point(d));
            let err = (a.f - b.f).abs().max((a.m - b.m).abs());
            assert!(a.f.is_finite() && a.m.is_finite());
            assert!(
                err < 1e-9,
                "{shape:?} k={k} skew={skew:?} d={d}: {a:?} vs {b:?} ({err:e})"
            );
            worst = worst.max(err);
        }
    }
    println!("largest deviation at the default order: {worst:e}");
}

#[test]
fn quadrature_converges_with_order() {
    // Rising order shrinks the error by orders of magnitude (double-exponential convergence):
    // a broken split or a lost singularity would stall it at a fixed level.
    for (shape, skew) in [
        (Shape::Rect { aspect: 1.0 }, None),
        (Shape::Rect { aspect: 1.0 }, SKEW),
        (Shape::Disc, None),
        (Shape::Disc, SKEW),
    ] {
        let exact = model(shape, 2.0, skew, 128);
        let err = |n: usize| {
            let m = model(shape, 2.0, skew, n);
            [0.3, 1.0, 1.7]
                .iter()
                .map(|&d| {
                    let (a, b) = (m.point(d), exact.point(d));
                    (a.f - b.f).abs().max((a.m - b.m).abs())
                })
                .fold(0.0, f64::max)
        };
        let (e8, e16, e40) = (err(8), err(16), err(40));
        assert!(e16 < e8 / 50.0, "{shape:?} {skew:?}: {e8:e} -> {e16:e}");
        assert!(e40 < 1e-11, "{shape:?} {skew:?}: {e40:e}");
    }
}

#[test]
fn f32_precomputation_is_within_its_documented_accuracy() {
    for (shape, k, skew) in cases() {
        let m64 = model(shape, k, skew, 28);
        let m32 = FlsModel::<f32>::new(*m64.config()).unwrap();
        for d in [0.0f32, 0.2, 0.9, 1.0, 2.5, 40.0] {
            let (a, b) = (m32.point(d), m64.point(d as f64));
            // Relative to the scale of the surface (m̃ grows like l/a on long patches).
            let scale = 1f64.max(b.m);
            let err = (a.f as f64 - b.f)
                .abs()
                .max((a.m as f64 - b.m).abs() / scale);
            assert!(err < 2e-6, "{shape:?} k={k} {skew:?} d={d}: {a:?} vs {b:?}");
        }
    }
}
