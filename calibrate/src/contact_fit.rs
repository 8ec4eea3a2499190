//! The contact-size law `a = c·N^γ` from indentation: ordinary least squares of
//! `ln a = ln c + γ ln N`, with `γ` clamped to the core's range `[0, 1/2]` (then `ln c`
//! refitted at the clamped `γ`). Exact data give the exact `c` and `γ` (to rounding).
//! Cost: one pass over the rows.
//!
//! This closed form starts the joint fit ([`crate::friction_fit`]) and gives the
//! indentation file's residual scale `σ`; the intervals come from the joint fit.

use crate::lab_csv::Indentation;

/// The fitted law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactFit {
    /// `c` [m/N^γ].
    pub c_m_per_n_gamma: f64,
    /// `γ`, in `[0, 1/2]`.
    pub gamma: f64,
    /// Residual standard deviation of `ln a` (`n − p` degrees of freedom; 0 when there
    /// are none).
    pub sigma_ln: f64,
    /// Whether `γ` was fitted (at least two distinct forces) or held.
    pub gamma_fitted: bool,
}

/// Whether the rows have at least two distinct normal forces (relative difference over
/// 1e-9).
pub fn distinct_forces(rows: &[Indentation]) -> usize {
    let mut ln: Vec<f64> = rows.iter().map(|r| r.normal_force_n.ln()).collect();
    ln.sort_by(f64::total_cmp);
    ln.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    ln.len()
}

/// Fits `c` and `γ` to `rows` (at least one), holding `γ` at `gamma_held` when the rows
/// have a single force.
pub fn fit_contact(rows: &[Indentation], gamma_held: f64) -> ContactFit {
    let n = rows.len() as f64;
    let xs: Vec<f64> = rows.iter().map(|r| r.normal_force_n.ln()).collect();
    let ys: Vec<f64> = rows.iter().map(|r| r.half_width_m.ln()).collect();
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let gamma_fitted = distinct_forces(rows) >= 2 && sxx > 0.0;
    let gamma = if gamma_fitted {
        (sxy / sxx).clamp(0.0, 0.5)
    } else {
        gamma_held
    };
    let ln_c = my - gamma * mx;
    let sse: f64 = xs
        .iter()
        .zip(&ys)
        .map(|(x, y)| (y - ln_c - gamma * x).powi(2))
        .sum();
    let df = rows.len().saturating_sub(if gamma_fitted { 2 } else { 1 });
    ContactFit {
        c_m_per_n_gamma: ln_c.exp(),
        gamma,
        sigma_ln: if df > 0 {
            (sse / df as f64).sqrt()
        } else {
            0.0
        },
        gamma_fitted,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(c: f64, gamma: f64, forces: &[f64]) -> Vec<Indentation> {
        forces
            .iter()
            .map(|&n| Indentation {
                normal_force_n: n,
                half_width_m: c * n.powf(gamma),
            })
            .collect()
    }

    #[test]
    fn exact_data_give_the_exact_law() {
        let fit = fit_contact(&rows(2.5e-3, 0.37, &[0.3, 1.0, 2.0, 7.5]), 0.0);
        assert!(
            (fit.c_m_per_n_gamma / 2.5e-3 - 1.0).abs() < 1e-12,
            "{fit:?}"
        );
        assert!((fit.gamma - 0.37).abs() < 1e-12 && fit.sigma_ln < 1e-12);
        // Clamped: a law steeper than the core allows is fitted at γ = 1/2.
        let steep = fit_contact(&rows(1e-3, 0.8, &[1.0, 2.0, 4.0]), 0.0);
        assert_eq!(steep.gamma, 0.5);
        // One force: γ held, c exact at that force.
        let one = fit_contact(&rows(2e-3, 0.5, &[4.0, 4.0, 4.0]), 0.0);
        assert!(!one.gamma_fitted && one.gamma == 0.0);
        assert!((one.c_m_per_n_gamma - 4e-3).abs() < 1e-15);
    }
}
