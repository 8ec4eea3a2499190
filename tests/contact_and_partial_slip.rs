//! Contact size (power law) and Cattaneo–Mindlin partial slip (Eq. 4, 5).

use softgrip::contact::ContactSize;
use softgrip::partial_slip::{deflection_m, stick_radius, Elasticity};

#[test]
fn power_law_contact_size() {
    let c = ContactSize::<f64>::new(0.004, 0.5).unwrap();
    assert!((c.half_width_m(4.0) - 0.008).abs() < 1e-15);
    assert_eq!(c.half_width_m(-1.0), 0.0);
    assert_eq!(c.half_width_m(f64::NAN), 0.0);
    assert!((c.normal_force_n(0.008).unwrap() - 4.0).abs() < 1e-12);
    let fixed = ContactSize::<f64>::new(0.004, 0.0).unwrap();
    assert_eq!(fixed.half_width_m(1e6), 0.004);
    assert_eq!(fixed.normal_force_n(0.1), None);
    assert_eq!(ContactSize::<f64>::new(0.0, 0.5).unwrap_err().param(), "c");
    assert_eq!(
        ContactSize::<f64>::new(1.0, 0.6).unwrap_err().param(),
        "gamma"
    );
    assert_eq!(
        ContactSize::<f64>::new(1.0, f64::NAN).unwrap_err().param(),
        "gamma"
    );
}

#[test]
fn stick_zone_shrinks_to_a_point_at_gross_slip() {
    let a = 0.01f64;
    assert_eq!(stick_radius(a, 0.0), a);
    assert!((stick_radius(a, 0.875) - a * 0.5).abs() < 1e-15);
    assert_eq!(stick_radius(a, 1.0), 0.0);
    assert_eq!(stick_radius(a, 2.0), 0.0);
    assert_eq!(stick_radius(a, f64::NAN), 0.0);
    // Within 1e-15 of gross slip: a · (1e-15)^(1/3) = a · 1e-5, to a few ulp.
    let near = stick_radius(a, 1.0 - 1e-15);
    let exact = a * (1.0f64 - (1.0 - 1e-15)).cbrt();
    assert!((near - exact).abs() <= 1e-12 * exact);
    // Monotone in the load.
    let mut last = a;
    for i in 1..=100 {
        let r = stick_radius(a, i as f64 / 100.0);
        assert!(r < last);
        last = r;
    }
}

#[test]
fn deflection_matches_eq5_and_saturates() {
    let el = Elasticity::<f64>::new(1e6, 0.45).unwrap();
    let g = 1e6 / (2.0 + 2.0 * 0.45);
    assert!((el.shear_modulus_pa - g).abs() < 1e-9);
    let (mu_n, a) = (2.0, 0.01);
    let limit = 3.0 * mu_n / (16.0 * a) * (2.0 - 0.45) / g;
    assert_eq!(deflection_m(&el, mu_n, a, 0.0), 0.0);
    assert!((deflection_m(&el, mu_n, a, 1.0) - limit).abs() < 1e-18);
    assert!((deflection_m(&el, mu_n, a, 5.0) - limit).abs() < 1e-18);
    let half = 1.0 - 0.5f64.powf(2.0 / 3.0);
    assert!((deflection_m(&el, mu_n, a, 0.5) - limit * half).abs() < 1e-15 * limit);
    // Tiny loads keep full relative accuracy: 1 − (1 − x)^(2/3) ≈ 2x/3.
    let tiny = deflection_m(&el, mu_n, a, 1e-12);
    assert!((tiny / limit - 2e-12 / 3.0).abs() < 1e-24);
    assert_eq!(Elasticity::<f64>::new(-1.0, 0.3).unwrap_err().param(), "E");
    assert_eq!(Elasticity::<f64>::new(1e6, 0.7).unwrap_err().param(), "nu");
}
