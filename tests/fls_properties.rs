//! Properties of the limit surface along the sweep: `f̃` rises and `m̃` falls, the curve is
//! convex, it lies inside the Eq. 10 ellipse, the skew leaves the pitch alone and its sign
//! does not matter, and the surface responds to `k` and the aspect the way the physics says.

use proptest::prelude::*;
use softgrip::fls::ellipse_radius;
use softgrip::fls::{EllipseFit, RadialGap};
use softgrip::{FlsConfig, FlsModel, FlsPoint, FlsTable, QuadratureOrder, Shape};

fn model(shape: Shape, k: f64, skew: Option<(f64, f64, f64)>) -> FlsModel<f64> {
    FlsModel::new(FlsConfig {
        shape,
        k,
        skew,
        order: QuadratureOrder::DEFAULT,
    })
    .unwrap()
}

fn cross(o: &FlsPoint<f64>, a: &FlsPoint<f64>, b: &FlsPoint<f64>) -> f64 {
    (a.f - o.f) * (b.m - o.m) - (a.m - o.m) * (b.f - o.f)
}

/// Checks monotonicity, convexity and the ellipse bound on a sweep.
fn check_sweep(m: &FlsModel<f64>) {
    check_sweep_with(m, true)
}

fn check_sweep_with(m: &FlsModel<f64>, inside_ellipse: bool) {
    let table = FlsTable::<f64, 200>::sweep(m, 160).unwrap();
    assert!(table.is_star_shaped());
    let pts = table.points();
    let pitch = table.pitch();
    for w in pts.windows(2) {
        assert!(w[1].f > w[0].f, "f̃ must rise: {:?} -> {:?}", w[0], w[1]);
        assert!(w[1].m < w[0].m, "m̃ must fall: {:?} -> {:?}", w[0], w[1]);
    }
    // Convex: going from (0, pitch) to (1, 0) the curve turns clockwise at every sample.
    for w in pts.windows(3) {
        let c = cross(&w[0], &w[1], &w[2]);
        assert!(c <= 1e-12, "not convex at {:?}: {c:e}", w[1]);
    }
    // Inside the Eq. 10 ellipse (touching it only at the two ends).
    for p in pts.iter().filter(|_| inside_ellipse) {
        let r = p.f.hypot(p.m);
        let re = ellipse_radius(pitch, p.f, p.m);
        assert!(r <= re + 1e-12, "outside the ellipse at {p:?}");
    }
}

#[test]
fn paper_cases_are_monotone_convex_and_inside_the_ellipse() {
    for k in [1.0, 2.0, 4.0, 50.0, f64::INFINITY] {
        check_sweep(&model(Shape::Rect { aspect: 1.0 }, k, None));
        check_sweep(&model(Shape::Disc, k, None));
    }
    // The paper's skewed cases (Figs. 9-11: k = 2, 4, 50 with Δ/a = 0.9, α = 1.1).
    for k in [2.0, 4.0, 50.0] {
        check_sweep(&model(
            Shape::Rect { aspect: 1.0 },
            k,
            Some((0.9, 1.1, 0.45)),
        ));
    }
}

#[test]
fn on_the_disc_the_circular_locus_bends_the_surface_near_pure_torsion() {
    // On the disc the locus (Eq. 16) moves the peak sideways like sqrt(d) near d = 0, far
    // faster than the centre of rotation moves. The offset between the two makes a force
    // that first rises like sqrt(d) and then dips, while m̃ rises a little above the pitch:
    // the swept curve is not star-shaped there. The pitch itself (d = 0) is unchanged, and
    // the table says it cannot be looked up exactly.
    for k in [2.0, 4.0] {
        let m = model(Shape::Disc, k, Some((0.9, 1.1, 0.45)));
        let pitch = m.pitch();
        let near = m.point(0.005);
        assert!(
            near.m > pitch && near.m < pitch * 1.01,
            "k = {k}: {near:?} vs {pitch}"
        );
        let ratio = m.point(1e-5).f / m.point(1e-6).f;
        assert!(
            (ratio - 10f64.sqrt()).abs() < 0.3,
            "f̃ grows like sqrt(d), not d: {ratio}"
        );
        let table = FlsTable::<f64, 200>::sweep(&m, 160).unwrap();
        if k == 2.0 {
            assert!(!table.is_star_shaped(), "k = {k}");
        }
        // Without the sideways move (locus 0) the disc behaves like the rectangle.
        let straight = model(Shape::Disc, k, Some((0.9, 1.1, 0.0)));
        check_sweep(&straight);
        assert!(FlsTable::<f64, 200>::sweep(&straight, 160)
            .unwrap()
            .is_star_shaped());
    }
}

#[test]
fn thin_rectangles_leave_the_ellipse_near_pure_torsion() {
    // For l/a → 0 the patch is a line across the sliding direction: f̃ ~ d ln(1/d) while
    // m̃ falls only like d² ln(1/d), so the curve runs outside f̃² + (m̃/pitch)² = 1.
    // Measured: the excursion is 0 for l/a >= 0.5 and reaches about 0.04 at l/a = 0.05.
    for (aspect, outside) in [
        (0.05, true),
        (0.2, true),
        (0.5, false),
        (1.0, false),
        (5.0, false),
    ] {
        let m = model(Shape::Rect { aspect }, 2.0, None);
        let table = FlsTable::<f64, 300>::sweep(&m, 256).unwrap();
        let gap = RadialGap::find(&m, &table);
        assert_eq!(gap.max_outside > 1e-9, outside, "l/a = {aspect}: {gap:?}");
    }
}

#[test]
fn a_strong_skew_can_leave_the_ellipse_and_the_gap_report_says_so() {
    // k = 1 with Δ/a = 0.9: the skew grows faster than the torsion fades, and near pure
    // torsion the skewed surface pokes outside Eq. 10. The report must show it, not hide it.
    let m = model(Shape::Rect { aspect: 1.0 }, 1.0, Some((0.9, 1.1, 0.45)));
    let table = FlsTable::<f64, 80>::sweep(&m, 64).unwrap();
    let gap = RadialGap::find(&m, &table);
    assert!(gap.max_outside > 0.0, "{gap:?}");
    let plain = model(Shape::Rect { aspect: 1.0 }, 1.0, None);
    let table = FlsTable::<f64, 80>::sweep(&plain, 64).unwrap();
    assert_eq!(RadialGap::find(&plain, &table).max_outside, 0.0);
}

#[test]
fn the_gap_to_the_ellipse_is_a_few_percent_and_found_exactly() {
    let m = model(Shape::Rect { aspect: 1.0 }, 2.0, None);
    let table = FlsTable::<f64, 80>::sweep(&m, 64).unwrap();
    let gap = RadialGap::find(&m, &table);
    // docs/model.md: "inside this ellipse by a few per cent near the diagonal".
    assert!(
        gap.max_relative_gap > 0.01 && gap.max_relative_gap < 0.15,
        "{gap:?}"
    );
    // The refinement beats every sample of a much finer sweep.
    let fine = FlsTable::<f64, 2100>::sweep(&m, 2048).unwrap();
    let pitch = fine.pitch();
    let best = fine
        .points()
        .iter()
        .map(|p| ellipse_radius(pitch, p.f, p.m) - p.f.hypot(p.m))
        .fold(f64::MIN, f64::max);
    assert!(gap.max_gap >= best - 1e-12, "{} < {best}", gap.max_gap);
    assert!(gap.max_gap - best < 1e-6);
    // The least-squares ellipse sits between the curve and Eq. 10.
    let fit = EllipseFit::fit(table.points()).unwrap();
    assert!(fit.f_semi_axis < 1.0 && fit.m_semi_axis < pitch);
    assert!(fit.f_semi_axis > 0.9 && fit.m_semi_axis > 0.9 * pitch);
}

#[test]
fn skew_keeps_the_pitch_and_its_sign_does_not_matter() {
    for shape in [Shape::Rect { aspect: 1.0 }, Shape::Disc] {
        let plain = model(shape, 2.0, None);
        let skewed = model(shape, 2.0, Some((0.9, 1.1, 0.45)));
        assert!((plain.pitch() - skewed.pitch()).abs() < 1e-14);
    }
    // Reflecting y -> -y: the rectangle's skewed integrals for a peak at +δ and at −δ agree.
    // The model only takes δ >= 0, so check through the pressure symmetry on a fine sweep:
    // a skew law with locus 0 and one with the circular locus agree on the rectangle.
    let a = model(Shape::Rect { aspect: 1.0 }, 2.0, Some((0.9, 1.1, 0.0)));
    let b = model(Shape::Rect { aspect: 1.0 }, 2.0, Some((0.9, 1.1, 0.45)));
    for d in [0.1, 0.7, 2.0] {
        assert_eq!(
            a.point(d),
            b.point(d),
            "Δx must not matter on the rectangle"
        );
    }
}

#[test]
fn skew_moves_the_surface_and_we_report_which_way() {
    // docs/model.md asks to report honestly what the skew does. Under its reading the skewed
    // surface of the paper's case (k = 2, Δ/a = 0.9, α = 1.1) lies *outside* the symmetric
    // one in m̃ at mid sweep; this pins the direction so a change is noticed.
    let plain = model(Shape::Rect { aspect: 1.0 }, 2.0, None);
    let skewed = model(Shape::Rect { aspect: 1.0 }, 2.0, Some((0.9, 1.1, 0.45)));
    let (p, s) = (plain.point(1.0), skewed.point(1.0));
    assert!(s.m > p.m && s.f < p.f, "{p:?} vs {s:?}");
}

#[test]
fn more_uniform_pressure_raises_the_pitch() {
    let mut last = 0.0;
    for k in [1.0, 1.5, 2.0, 4.0, 10.0, 50.0, 1e6, f64::INFINITY] {
        let p = model(Shape::Rect { aspect: 1.0 }, k, None).pitch();
        assert!(p > last, "k = {k}: {p} <= {last}");
        last = p;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn any_symmetric_profile_gives_a_monotone_convex_sweep_inside_the_ellipse(
        k in 1.0f64..60.0,
        aspect in 0.05f64..20.0,
        disc in any::<bool>(),
    ) {
        // Thin strips across the sliding direction (l/a below about 0.45) leave the
        // ellipse near pure torsion: f̃ rises like d·ln(1/d) there. See the next test.
        let shape = if disc { Shape::Disc } else { Shape::Rect { aspect } };
        check_sweep_with(&model(shape, k, None), disc || aspect >= 0.5);
    }

    #[test]
    fn any_skewed_profile_gives_a_star_shaped_sweep_with_rising_force(
        k in 1.0f64..60.0,
        aspect in 0.05f64..20.0,
        delta in 0.01f64..0.95,
        alpha in 0.1f64..5.0,
        disc in any::<bool>(),
    ) {
        // m̃ need not fall monotonically under a fast, strong skew (it can rise slightly at
        // mid sweep), but the direction turns monotonically, which the table lookup needs.
        // The disc is taken with the peak moving along y only (locus 0): a sideways locus
        // moves the pressure centroid off the x = 0 line, and then the moment about the patch
        // centre can pass through zero (see docs/core.md), which is not star-shaped.
        let (shape, locus) = if disc { (Shape::Disc, 0.0) } else { (Shape::Rect { aspect }, delta / 2.0) };
        let m = model(shape, k, Some((delta, alpha, locus)));
        let table = FlsTable::<f64, 40>::sweep(&m, 32).unwrap();
        for w in table.points().windows(2) {
            prop_assert!(w[1].f > w[0].f, "{:?} {:?}", w[0], w[1]);
            prop_assert!(w[0].f * w[1].m - w[0].m * w[1].f < 0.0, "{:?} {:?}", w[0], w[1]);
        }
        for p in table.points() {
            prop_assert!(p.f.is_finite() && p.m.is_finite());
        }
    }
}
