//! 95 % intervals: Student's t quantile and the Wald interval of a least-squares
//! estimate, `θ̂ ± t_{0.975, df}·se`, with the small dense algebra they need (why Wald:
//! docs/decisions/calibration-fit.md); and the F distribution's tail, for the test of a
//! fit the rows contradict ([`crate::lack_of_fit`]).
//!
//! The fits are nonlinear least squares on log-scale residuals; their covariance is
//! `σ²(JᵀJ)⁻¹` at the optimum (Gauss–Newton), each file's residuals weighted by its own
//! estimated `σ`. Cost: a `p × p` inverse, `p ≤ 5`.

/// `t_{0.975, df}`: the two-sided 95 % quantile of Student's t with `df` degrees of
/// freedom. Tabulated (4 digits) for `df ≤ 6`, else the Cornish–Fisher expansion
/// (Abramowitz & Stegun 26.7.5, four terms), within 6e-4 for `df ≥ 7`. The 95 % level:
/// docs/decisions/calibration-fit.md.
pub fn t975(df: usize) -> f64 {
    const EXACT: [f64; 7] = [f64::INFINITY, 12.706, 4.303, 3.182, 2.776, 2.571, 2.447];
    if let Some(&t) = EXACT.get(df) {
        return t;
    }
    let z: f64 = 1.959_963_985;
    let n = df as f64;
    let (z3, z5, z7, z9) = (z.powi(3), z.powi(5), z.powi(7), z.powi(9));
    z + (z3 + z) / (4.0 * n)
        + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * n.powi(2))
        + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * n.powi(3))
        + (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z) / (92160.0 * n.powi(4))
}

/// The inverse of the symmetric positive-definite `a` (`n × n`, row-major): scaled to unit
/// diagonal, then Gauss–Jordan elimination with partial pivoting; `None` when singular
/// (a pivot under 1e-12 of the scaled matrix, or a zero diagonal).
pub fn invert(a: &[f64], n: usize) -> Option<Vec<f64>> {
    let d: Vec<f64> = (0..n).map(|i| a[i * n + i].sqrt()).collect();
    if d.iter().any(|x| !(*x > 0.0 && x.is_finite())) {
        return None;
    }
    let mut m: Vec<f64> = (0..n * n)
        .map(|ij| a[ij] / (d[ij / n] * d[ij % n]))
        .collect();
    let mut inv = vec![0.0; n * n];
    for i in 0..n {
        inv[i * n + i] = 1.0;
    }
    for col in 0..n {
        let piv =
            (col..n).max_by(|&x, &y| m[x * n + col].abs().total_cmp(&m[y * n + col].abs()))?;
        if !(m[piv * n + col].abs() > 1e-12) {
            return None;
        }
        for j in 0..n {
            m.swap(col * n + j, piv * n + j);
            inv.swap(col * n + j, piv * n + j);
        }
        let p = m[col * n + col];
        for j in 0..n {
            m[col * n + j] /= p;
            inv[col * n + j] /= p;
        }
        for r in 0..n {
            if r != col {
                let f = m[r * n + col];
                for j in 0..n {
                    m[r * n + j] -= f * m[col * n + j];
                    inv[r * n + j] -= f * inv[col * n + j];
                }
            }
        }
    }
    Some(
        (0..n * n)
            .map(|ij| inv[ij] / (d[ij / n] * d[ij % n]))
            .collect(),
    )
}

/// Solves `a x = b` for the `n × n` matrix `a`; `None` when singular.
pub fn solve(a: &[f64], b: &[f64], n: usize) -> Option<Vec<f64>> {
    let inv = invert(a, n)?;
    Some(
        (0..n)
            .map(|i| (0..n).map(|j| inv[i * n + j] * b[j]).sum())
            .collect(),
    )
}

/// The Wald interval `value ± t·se`, clamped into `[lo, hi]`.
pub fn wald(value: f64, se: f64, t: f64, lo: f64, hi: f64) -> (f64, f64) {
    (
        (value - t * se).clamp(lo, hi),
        (value + t * se).clamp(lo, hi),
    )
}

/// `ln Γ(x)` for `x > 0`: Lanczos' approximation (`g = 7`, nine terms), within about
/// 1e-15 relative.
fn ln_gamma(x: f64) -> f64 {
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    let x = x - 1.0;
    let t = x + 7.5;
    let series = C[1..]
        .iter()
        .enumerate()
        .fold(C[0], |acc, (i, c)| acc + c / (x + i as f64 + 1.0));
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + series.ln()
}

/// The continued fraction of the incomplete beta function (modified Lentz), for
/// `x < (a + 1)/(a + b + 2)`, where it converges fast.
fn beta_fraction(x: f64, a: f64, b: f64) -> f64 {
    let tiny = 1e-300;
    let guard = |v: f64| if v.abs() < tiny { tiny } else { v };
    let mut c = 1.0;
    let mut d = 1.0 / guard(1.0 - (a + b) * x / (a + 1.0));
    let mut h = d;
    for m in 1..=300 {
        let m = f64::from(m);
        let even = m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m));
        d = 1.0 / guard(1.0 + even * d);
        c = guard(1.0 + even / c);
        h *= d * c;
        let odd = -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0));
        d = 1.0 / guard(1.0 + odd * d);
        c = guard(1.0 + odd / c);
        let step = d * c;
        h *= step;
        if (step - 1.0).abs() < 1e-15 {
            break;
        }
    }
    h
}

/// The regularised incomplete beta function `I_x(a, b)`.
fn incomplete_beta(x: f64, a: f64, b: f64) -> f64 {
    if !(x > 0.0) {
        return 0.0;
    }
    if !(x < 1.0) {
        return 1.0;
    }
    let front =
        (ln_gamma(a + b) - ln_gamma(a) - ln_gamma(b) + a * x.ln() + b * (1.0 - x).ln()).exp();
    if x < (a + 1.0) / (a + b + 2.0) {
        front * beta_fraction(x, a, b) / a
    } else {
        1.0 - front * beta_fraction(1.0 - x, b, a) / b
    }
}

/// `P(F > f)` for Fisher's F with `d1` and `d2` degrees of freedom (both ≥ 1): 1 at
/// `f ≤ 0`, 0 at `f = ∞`.
pub fn f_tail(f: f64, d1: usize, d2: usize) -> f64 {
    if !(f > 0.0) {
        return 1.0;
    }
    let (d1, d2) = (d1.max(1) as f64, d2.max(1) as f64);
    incomplete_beta(d2 / (d2 + d1 * f), d2 / 2.0, d1 / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn t_quantiles() {
        // The quantiles below are printed t tables'.
        for (df, t) in [
            (5, 2.5706),
            (7, 2.3646),
            (10, 2.2281),
            (30, 2.0423),
            (100, 1.9840),
        ] {
            assert!((t975(df) - t).abs() < 6e-4, "{df}: {}", t975(df));
        }
    }

    #[test]
    fn inverse() {
        let a = [4.0, 1.0, 1.0, 3.0];
        let inv = invert(&a, 2).unwrap();
        let det = 11.0;
        let want = [3.0 / det, -1.0 / det, -1.0 / det, 4.0 / det];
        for (x, y) in inv.iter().zip(want) {
            assert!((x - y).abs() < 1e-15);
        }
        assert!(invert(&[1.0, 2.0, 2.0, 4.0], 2).is_none());
    }

    #[test]
    fn f_tails() {
        // Upper quantiles of F from printed tables, and a closed form: with 2 and 2
        // degrees of freedom P(F > f) = 1/(1 + f).
        for (f, d1, d2, p) in [
            (3.098, 3, 20, 0.05),
            (5.636, 5, 10, 0.01),
            (8.754, 10, 10, 0.001),
            (2.01, 40, 30, 0.025),
        ] {
            let got = f_tail(f, d1, d2);
            assert!((got / p - 1.0).abs() < 5e-3, "{f} {d1} {d2}: {got}");
        }
        for f in [0.1, 1.0, 7.0, 300.0] {
            assert!((f_tail(f, 2, 2) - 1.0 / (1.0 + f)).abs() < 1e-13);
        }
        assert_eq!(f_tail(f64::INFINITY, 3, 4), 0.0);
        assert_eq!(f_tail(0.0, 3, 4), 1.0);
    }
}
