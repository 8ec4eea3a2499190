//! The sweep table and the aspect grid: lookups against exact evaluations.

use softgrip::fls::{AspectGrid, SweepMap};
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};

fn model(shape: Shape, skew: Option<(f64, f64, f64)>) -> FlsModel<f64> {
    FlsModel::new(FlsConfig {
        shape,
        k: 2.0,
        skew,
        order: QuadratureOrder::DEFAULT,
    })
    .unwrap()
}

#[test]
fn sweep_map_round_trips_and_covers_zero_to_infinity() {
    let map = SweepMap::<f64>::for_shape(Shape::Rect { aspect: 1.0 });
    assert_eq!(map.d_of(0.0), 0.0);
    assert_eq!(map.d_of(1.0), f64::INFINITY);
    for t in [0.0, 0.1, 0.5, 0.9, 0.999] {
        assert!((map.t_of(map.d_of(t)) - t).abs() < 1e-15);
    }
    assert_eq!(map.t_of(f64::INFINITY), 1.0);
}

#[test]
fn the_table_brackets_the_exact_surface_from_inside() {
    for (shape, skew) in [
        (Shape::Rect { aspect: 1.0 }, None),
        (Shape::Rect { aspect: 1.0 }, Some((0.9, 1.1, 0.45))),
        (Shape::Rect { aspect: 3.0 }, None),
        (Shape::Disc, None),
    ] {
        let m = model(shape, skew);
        let table = FlsTable::<f64, 65>::sweep(&m, 64).unwrap();
        let map = table.map();
        let mut worst: f64 = 0.0;
        // Points of the exact surface between the samples: the chords lie inside the convex
        // curve, so the utilisation of an exact boundary point is >= 1, and close to 1.
        for i in 0..640 {
            let t = (i as f64 + 0.37) / 640.0;
            let p = m.point(map.d_of(t));
            let u = table.utilisation(p.f, p.m);
            assert!(u >= 1.0 - 1e-12, "{shape:?} {skew:?} t={t}: u = {u}");
            worst = worst.max(u - 1.0);
            // Scaling the load scales the utilisation.
            let half = table.utilisation(0.5 * p.f, 0.5 * p.m);
            assert!((half - 0.5 * u).abs() < 1e-12);
        }
        assert!(worst < 1e-3, "{shape:?} {skew:?}: chord error {worst:e}");
        println!("{shape:?} {skew:?}: 64-sample chord error at most {worst:.2e}");
    }
}

#[test]
fn lookup_is_total() {
    let m = model(Shape::Rect { aspect: 1.0 }, None);
    let table = FlsTable::<f64, 33>::sweep(&m, 32).unwrap();
    assert_eq!(table.utilisation(0.0, 0.0), 0.0);
    assert!((table.utilisation(1.0, 0.0) - 1.0).abs() < 1e-15);
    assert!((table.utilisation(0.0, table.pitch()) - 1.0).abs() < 1e-15);
    assert!((table.utilisation(-1.0, 0.0) - 1.0).abs() < 1e-15);
    assert!(table.utilisation(f64::NAN, 0.1).is_nan());
    assert_eq!(table.utilisation(f64::INFINITY, 0.1), f64::INFINITY);
    assert!(table.utilisation(1e300, 1e300).is_finite());
    assert!(table.utilisation(1e-300, 0.0) > 0.0);
}

#[test]
fn table_capacity_is_checked() {
    let m = model(Shape::Disc, None);
    assert!(FlsTable::<f64, 16>::sweep(&m, 16).is_err());
    assert!(FlsTable::<f64, 16>::sweep(&m, 1).is_err());
    assert!(FlsTable::<f64, 16>::sweep(&m, 15).is_ok());
}

#[test]
fn aspect_grid_interpolates_pitch_and_surface() {
    let m = model(Shape::Rect { aspect: 1.0 }, None);
    let grid = AspectGrid::<f64, 12, 65>::build(&m, 0.5, 4.0, 12, 64).unwrap();
    assert_eq!(grid.entries().len(), 12);
    // At the nodes the grid reproduces the exact pitch.
    for e in grid.entries() {
        let exact = m.with_aspect(e.aspect).unwrap().pitch();
        assert!((grid.pitch(e.aspect) - exact).abs() < 1e-12);
    }
    // Between the nodes, the log-log interpolation of the pitch is within 2.5e-3 of it
    // (relative; measured here) and the surface lookup within 3e-3 in utilisation.
    let mut worst_pitch: f64 = 0.0;
    let mut worst_u: f64 = 0.0;
    for i in 0..50 {
        let aspect = 0.5 * (8f64).powf((i as f64 + 0.5) / 50.0);
        let exact = m.with_aspect(aspect).unwrap();
        worst_pitch = worst_pitch.max((grid.pitch(aspect) / exact.pitch() - 1.0).abs());
        let p = exact.point(0.8);
        worst_u = worst_u.max((grid.utilisation(aspect, p.f, p.m) - 1.0).abs());
    }
    assert!(worst_pitch < 2.5e-3, "{worst_pitch:e}");
    assert!(worst_u < 3e-3, "{worst_u:e}");
    println!("12-point aspect grid 0.5..4: pitch error {worst_pitch:.2e}, utilisation error {worst_u:.2e}");
    // Outside the range it clamps, and hostile aspects stay finite.
    assert_eq!(grid.pitch(100.0), grid.pitch(4.0));
    assert_eq!(grid.pitch(0.01), grid.pitch(0.5));
    assert!(grid.pitch(f64::NAN).is_finite());
    assert!(grid.utilisation(f64::NAN, 0.3, 0.3).is_finite());
}

#[test]
fn configuration_errors_name_the_parameter() {
    let bad = |cfg: FlsConfig| FlsModel::<f64>::new(cfg).unwrap_err().param();
    let base = FlsConfig::default();
    assert_eq!(bad(FlsConfig { k: 0.5, ..base }), "k");
    assert_eq!(
        bad(FlsConfig {
            k: f64::NAN,
            ..base
        }),
        "k"
    );
    assert_eq!(
        bad(FlsConfig {
            shape: Shape::Rect { aspect: 0.0 },
            ..base
        }),
        "aspect"
    );
    assert_eq!(
        bad(FlsConfig {
            skew: Some((1.0, 1.1, 0.5)),
            ..base
        }),
        "skew"
    );
    assert_eq!(
        bad(FlsConfig {
            skew: Some((0.5, -1.0, 0.25)),
            ..base
        }),
        "alpha"
    );
    assert_eq!(
        bad(FlsConfig {
            shape: Shape::Disc,
            skew: Some((0.9, 1.1, 0.9)),
            ..base
        }),
        "locus"
    );
    assert_eq!(QuadratureOrder::new(1000).unwrap_err().param(), "order");
    let m = model(Shape::Rect { aspect: 1.0 }, None);
    assert_eq!(
        AspectGrid::<f64, 4, 17>::build(&m, 1.0, 2.0, 5, 16)
            .unwrap_err()
            .param(),
        "aspect_count"
    );
}
