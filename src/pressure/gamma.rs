//! `Γ` for the profile's normalising constants (`C_k`, `B_k` and the disc's moments): on
//! `[1, 171]`, by the recurrence `Γ(1 + y) = y Γ(y)` down to `[1, 2]` and a polynomial
//! for `1/Γ(1 + x)` on `x ∈ [0, 1]` there.
//!
//! The polynomial is the Taylor series of `1/Γ(1 + x)` at `x = 1/2`, cut after 20 terms,
//! whose remainder is below `1e-18` on `[0, 1]` (`1/Γ` is entire, so the series
//! converges everywhere). The coefficients are mpmath's at 50 digits, rounded to `f64`:
//! `mpmath.taylor(lambda x: mpmath.rgamma(1 + x), 0.5, 19)`; the accuracy this buys is
//! recorded in docs/decisions/firmware-size-levers.md.
//!
//! Accuracy (the tests below): within 4e-16 relative of `Γ(1 + y)` at mpmath's 40-digit
//! values and at the closed forms (factorials, half-integers) on `[0, 4]`, the arguments
//! the profile needs (`1 + j/k ≤ 5`), and within 2e-15 of libm's `tgamma` there (partly
//! `tgamma`'s own error, over 5e-16 at a test point, partly its rounding of `1 + y`). Each recurrence step adds up to half an ulp.
//! Cost: 20 multiply-adds, a division and one multiplication per recurrence step, in f64.
//!
//! It replaces `libm`'s `tgamma` and `lgamma`, which handle arguments the profile never
//! has (negative, huge or near poles); the flash it saves is in
//! docs/decisions/firmware-size-levers.md.

/// Taylor coefficients of `1/Γ(1 + x)` at `x = 1/2`, lowest order first.
const RGAMMA_1P_AT_HALF: [f64; 20] = [
    core::f64::consts::FRAC_2_SQRT_PI, // 1/Γ(3/2) = 2/√π
    -0.0411745264452831,
    -0.5266544355255445,
    0.17510202604393457,
    0.050966860247706074,
    -0.042155169368535604,
    0.006612897826824127,
    0.002120731442572938,
    -0.0011107302545948906,
    0.00015235762076747688,
    2.5355204923814165e-05,
    -1.3896805717913756e-05,
    2.1562032905141724e-06,
    5.7942640540526726e-08,
    -8.913551118311116e-08,
    1.7103469415915374e-08,
    -9.313686445241901e-10,
    -2.6804741033496623e-10,
    7.458932233316326e-11,
    -8.012807061414718e-12,
];

/// `1/Γ(1 + x)` for `x ∈ [0, 1]` (accurate to 2 ulp there).
fn rgamma_1p(x: f64) -> f64 {
    let t = x - 0.5;
    RGAMMA_1P_AT_HALF
        .iter()
        .rev()
        .fold(0.0, |acc, &c| acc * t + c)
}

/// `Γ(1 + y)` for `y ∈ [0, 170]`: `y! ` for integers, `+∞` above 170 (`170!` is the last
/// factorial an `f64` holds), NaN for NaN. Negative `y` is outside its domain (the profile's
/// arguments are `j/k ≥ 0`) and gives `1/rgamma(1 + y)` of the polynomial, not `Γ`.
pub(crate) fn gamma_1p(y: f64) -> f64 {
    if y.is_nan() {
        return y;
    }
    if y > 170.0 {
        return f64::INFINITY;
    }
    // Γ(1 + y) = y Γ(y) = y Γ(1 + (y − 1)); each `y − 1` is exact (Sterbenz above 2,
    // and below 2 the result keeps y's exponent or a smaller one).
    let mut x = y;
    let mut scale = 1.0;
    while x > 1.0 {
        scale *= x;
        x -= 1.0;
    }
    scale / rgamma_1p(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    #[test]
    fn closed_forms() {
        let sqrt_pi = core::f64::consts::PI.sqrt();
        let cases = [
            (0.0, 1.0),
            (1.0, 1.0),
            (2.0, 2.0),
            (3.0, 6.0),
            (4.0, 24.0),
            (10.0, 3_628_800.0),
            (0.5, sqrt_pi / 2.0),
            (1.5, 3.0 * sqrt_pi / 4.0),
            (2.5, 15.0 * sqrt_pi / 8.0),
            (3.5, 105.0 * sqrt_pi / 16.0),
        ];
        for (y, exact) in cases {
            assert!(
                rel(gamma_1p(y), exact) < 4e-16,
                "Γ(1 + {y}) = {}",
                gamma_1p(y)
            );
        }
        // Γ(1 + x) near x = 0: 1 − γ x.
        let euler = 0.577_215_664_901_532_9;
        assert!(rel(gamma_1p(1e-12), 1.0 - euler * 1e-12) < 2.3e-16);
    }

    /// Against mpmath at 40 digits, at the `f64` arguments themselves
    /// (`mpmath.gamma(1 + mpmath.mpf(y))` for the float `y`), at points between the closed
    /// forms. `2.007` is near this function's largest error on `[0, 4]`, `2.328` near
    /// libm's `tgamma`'s (both found on a grid of 8 001 points against mpmath), where
    /// `tgamma` is more than 5e-16 off: the larger part of what `agrees_with_libm_tgamma`
    /// allows. docs/decisions/firmware-size-levers.md rests on this test.
    #[test]
    #[allow(clippy::excessive_precision)] // mpmath's digits as it prints them
    fn agrees_with_mpmath() {
        let cases = [
            (0.1, 0.951_350_769_866_873_181_39),
            (0.3, 0.897_470_696_306_277_190_18),
            (0.7, 0.908_638_732_853_290_441_56),
            (1.3, 1.166_711_905_198_160_376_1),
            (2.007, 2.012_980_255_252_831_773_3),
            (2.2, 2.423_965_479_935_368_442_2),
            (2.328, 2.762_709_026_311_557_548_5),
            (3.9, 20.667_385_961_857_845_532),
        ];
        for (y, exact) in cases {
            let d = rel(gamma_1p(y), exact);
            assert!(d < 4e-16, "Γ(1 + {y}): relative error {d:e}");
        }
        // `1 + y` is exact here, so this is libm's own error.
        let libm_err = rel(libm::tgamma(1.0 + 2.328), 2.762_709_026_311_557_548_5);
        assert!(libm_err > 5e-16, "libm's tgamma at 3.328: {libm_err:e}");
    }

    /// Against libm's `tgamma` on the profile's range and well beyond it (the two differ
    /// by up to 2e-15 on `[1, 5]`, where `tgamma(1 + y)` also rounds its argument `1 + y`).
    #[test]
    fn agrees_with_libm_tgamma() {
        let mut worst: f64 = 0.0;
        for i in 0..=40_000 {
            let y = 4.0 * i as f64 / 40_000.0;
            worst = worst.max(rel(gamma_1p(y), libm::tgamma(1.0 + y)));
        }
        assert!(
            worst < 2e-15,
            "worst relative difference {worst:e} on [0, 4]"
        );
        for i in 0..=1_000 {
            let y = 170.0 * i as f64 / 1_000.0;
            let d = rel(gamma_1p(y), libm::tgamma(1.0 + y));
            assert!(d < 1e-13, "Γ(1 + {y}): relative difference {d:e}");
        }
    }

    #[test]
    fn the_recurrence_holds() {
        for i in 100..=500 {
            let y = i as f64 / 100.0;
            assert!(rel(gamma_1p(y), y * gamma_1p(y - 1.0)) < 5e-16, "y = {y}");
        }
    }

    #[test]
    fn edges() {
        assert!(gamma_1p(f64::NAN).is_nan());
        assert_eq!(gamma_1p(f64::INFINITY), f64::INFINITY);
        assert_eq!(gamma_1p(171.0), f64::INFINITY);
        assert!(gamma_1p(170.0).is_finite());
    }
}
