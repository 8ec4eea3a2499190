//! 95 % intervals: Student's t quantile and the Wald interval of a least-squares
//! estimate, `θ̂ ± t_{0.975, df}·se`, with the small dense algebra they need (why Wald:
//! docs/decisions/calibration-fit.md).
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
}
