//! A small bounded Levenberg–Marquardt solver for the fits: a few parameters, at most
//! some hundreds of residuals, a forward/central-difference Jacobian (one-sided at a
//! bound). Converges in 5–20 iterations on the calibration's problems; each costs
//! `2p + 1` residual evaluations.

use crate::interval::solve;

/// A parameter's box and finite-difference step.
#[derive(Debug, Clone, Copy)]
pub struct Param {
    /// Start value.
    pub value: f64,
    /// Least value.
    pub lo: f64,
    /// Greatest value.
    pub hi: f64,
    /// Finite-difference step.
    pub step: f64,
    /// Whether the fit moves it (else it stays at `value`).
    pub free: bool,
}

/// The optimum.
#[derive(Debug, Clone)]
pub struct LsqFit {
    /// Every parameter (the fixed ones at their value).
    pub values: Vec<f64>,
    /// Residuals at the optimum.
    pub residuals: Vec<f64>,
    /// Jacobian of the residuals in the free parameters, row-major `n × free`.
    pub jacobian: Vec<f64>,
    /// Indices of the free parameters, the Jacobian's columns.
    pub free: Vec<usize>,
}

fn sse(r: &[f64]) -> f64 {
    r.iter().map(|x| x * x).sum()
}

/// The Jacobian at `p` in the free parameters `free`.
fn jacobian(
    f: &dyn Fn(&[f64]) -> Vec<f64>,
    p: &[f64],
    params: &[Param],
    free: &[usize],
) -> Vec<f64> {
    let n = f(p).len();
    let mut jac = vec![0.0; n * free.len()];
    for (col, &i) in free.iter().enumerate() {
        let pr = params[i];
        let (up, down) = ((p[i] + pr.step).min(pr.hi), (p[i] - pr.step).max(pr.lo));
        let (mut pu, mut pd) = (p.to_vec(), p.to_vec());
        pu[i] = up;
        pd[i] = down;
        let (ru, rd) = (f(&pu), f(&pd));
        let h = up - down;
        for row in 0..n {
            jac[row * free.len() + col] = if h > 0.0 {
                (ru[row] - rd[row]) / h
            } else {
                0.0
            };
        }
    }
    jac
}

/// Minimises `Σ f(p)²` over the free parameters within their boxes.
pub fn minimise(f: &dyn Fn(&[f64]) -> Vec<f64>, params: &[Param]) -> LsqFit {
    let free: Vec<usize> = (0..params.len()).filter(|&i| params[i].free).collect();
    let m = free.len();
    let mut p: Vec<f64> = params.iter().map(|q| q.value.clamp(q.lo, q.hi)).collect();
    let mut r = f(&p);
    let mut cost = sse(&r);
    let mut lambda = 1e-3;
    for _ in 0..100 {
        if m == 0 {
            break;
        }
        let jac = jacobian(f, &p, params, &free);
        let (jtj, jtr) = normal_equations(&jac, &r, m);
        let mut improved = false;
        for _ in 0..12 {
            let mut a = jtj.clone();
            for d in 0..m {
                a[d * m + d] += lambda * jtj[d * m + d].max(1e-12);
            }
            let Some(delta) = solve(&a, &jtr.iter().map(|x| -x).collect::<Vec<_>>(), m) else {
                lambda *= 10.0;
                continue;
            };
            let mut trial = p.clone();
            for (d, &i) in free.iter().enumerate() {
                trial[i] = (p[i] + delta[d]).clamp(params[i].lo, params[i].hi);
            }
            let rt = f(&trial);
            let ct = sse(&rt);
            if ct.is_finite() && ct <= cost {
                let gain = cost - ct;
                p = trial;
                r = rt;
                cost = ct;
                lambda = (lambda * 0.2).max(1e-12);
                improved = gain > 1e-13 * cost.max(1e-300);
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    let jacobian = jacobian(f, &p, params, &free);
    LsqFit {
        values: p,
        residuals: r,
        jacobian,
        free,
    }
}

/// `JᵀJ` and `Jᵀr` for the `n × m` Jacobian `jac`.
pub fn normal_equations(jac: &[f64], r: &[f64], m: usize) -> (Vec<f64>, Vec<f64>) {
    let mut jtj = vec![0.0; m * m];
    let mut jtr = vec![0.0; m];
    for (row, &ri) in jac.chunks(m.max(1)).zip(r) {
        for a in 0..m {
            jtr[a] += row[a] * ri;
            for b in 0..m {
                jtj[a * m + b] += row[a] * row[b];
            }
        }
    }
    (jtj, jtr)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fits_an_exponential_exactly() {
        let xs: Vec<f64> = (0..10).map(f64::from).collect();
        let f = |p: &[f64]| {
            xs.iter()
                .map(|x| p[0] * (p[1] * x).exp() - 2.0 * (-0.3 * x).exp())
                .collect()
        };
        let param = |value| Param {
            value,
            lo: -10.0,
            hi: 10.0,
            step: 1e-7,
            free: true,
        };
        let fit = minimise(&f, &[param(1.0), param(0.0)]);
        assert!(
            (fit.values[0] - 2.0).abs() < 1e-8 && (fit.values[1] + 0.3).abs() < 1e-8,
            "{:?}",
            fit.values
        );
    }
}
