//! The reference values of docs/model.md: the paper's Eq. 22 pitches to every printed digit, and
//! the closed forms to 1e-9 (in practice to about 1e-14).

use softgrip::fls::closed_form_pitch;
use softgrip::pressure::{disc_moment, rect_constant};
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};

fn pitch(shape: Shape, k: f64) -> f64 {
    FlsModel::<f64>::new(FlsConfig {
        shape,
        k,
        skew: None,
        order: QuadratureOrder::DEFAULT,
    })
    .unwrap()
    .pitch()
}

/// Truncates to `digits` decimals, as the paper prints them.
fn truncated(x: f64, digits: i32) -> f64 {
    let s = 10f64.powi(digits);
    (x * s).floor() / s
}

#[test]
fn paper_eq22_pitches_to_every_printed_digit() {
    let square = Shape::Rect { aspect: 1.0 };
    // k = 2 and k = 4 are printed rounded; k = 50 is printed truncated (0.76496 -> 0.7649).
    assert_eq!((pitch(square, 2.0) * 1e4).round() / 1e4, 0.7114);
    assert_eq!((pitch(square, 4.0) * 1e4).round() / 1e4, 0.7442);
    assert_eq!(truncated(pitch(square, 50.0), 4), 0.7649);
    assert_eq!(truncated(pitch(square, 50.0), 5), 0.76495);
}

#[test]
fn uniform_rectangle_pitch_matches_closed_form() {
    let exact = (2f64.sqrt() + 1f64.asinh()) / 3.0;
    let square = Shape::Rect { aspect: 1.0 };
    assert!((closed_form_pitch(square, f64::INFINITY).unwrap() - exact).abs() < 1e-15);
    let got = pitch(square, f64::INFINITY);
    assert!((got - exact).abs() < 1e-12, "{got} vs {exact}");
    // Other aspects against the closed form (1/(4λ)) ∫∫ r over [-λ, λ] × [-1, 1].
    for aspect in [0.01, 0.3, 2.5, 40.0] {
        let shape = Shape::Rect { aspect };
        let exact = closed_form_pitch(shape, f64::INFINITY).unwrap();
        let got = pitch(shape, f64::INFINITY);
        assert!(
            (got - exact).abs() < 1e-11,
            "aspect {aspect}: {got} vs {exact}"
        );
    }
}

#[test]
fn disc_pitches_match_closed_forms() {
    let hertz = 3.0 * std::f64::consts::PI / 16.0;
    assert!((pitch(Shape::Disc, 2.0) - hertz).abs() < 1e-12);
    assert!((pitch(Shape::Disc, f64::INFINITY) - 2.0 / 3.0).abs() < 1e-12);
    for k in [1.0, 1.5, 3.0, 7.0, 50.0, 1e4] {
        let exact = disc_moment(k, 2.0) / disc_moment(k, 1.0);
        let got = pitch(Shape::Disc, k);
        assert!((got - exact).abs() < 1e-11, "k = {k}: {got} vs {exact}");
    }
    // The general closed form agrees with the special cases.
    assert!((closed_form_pitch(Shape::Disc, 2.0).unwrap() - hertz).abs() < 1e-14);
}

#[test]
fn normalising_constants_have_their_known_values() {
    // C_2 = π Γ(1)·2 / Γ(1/2)² = 2; C_1 = π/Γ(1)²·1·Γ(2) = π; C_∞ = π/2.
    assert!((rect_constant(2.0) - 2.0).abs() < 1e-14);
    assert!((rect_constant(1.0) - std::f64::consts::PI).abs() < 1e-14);
    assert!((rect_constant(f64::INFINITY) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert!((rect_constant(1e12) - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    // B_2 = ∫ t sqrt(1 − t²) dt = 1/3; B_∞ = 1/2.
    assert!((disc_moment(2.0, 1.0) - 1.0 / 3.0).abs() < 1e-15);
    assert!((disc_moment(f64::INFINITY, 1.0) - 0.5).abs() < 1e-15);
}

#[test]
fn translation_and_spin_limits() {
    for shape in [
        Shape::Rect { aspect: 1.0 },
        Shape::Rect { aspect: 0.2 },
        Shape::Disc,
    ] {
        for skew in [None, Some((0.9, 1.1, 0.45))] {
            let m = FlsModel::<f64>::new(FlsConfig {
                shape,
                k: 2.0,
                skew,
                order: QuadratureOrder::DEFAULT,
            })
            .unwrap();
            let spin = m.point(0.0);
            assert_eq!(spin.f, 0.0);
            let far = m.point(1e7);
            assert!((far.f - 1.0).abs() < 1e-12, "{shape:?} {skew:?}: {far:?}");
            assert!(far.m < 1e-6, "{far:?}");
            assert_eq!(m.point(f64::INFINITY).f, 1.0);
        }
    }
}
