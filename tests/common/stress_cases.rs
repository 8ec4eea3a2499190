//! References for the stress suite (`tests/stress.rs`, `tests/properties_domain.rs`):
//! closed forms written here from docs/model.md, independently of the crate's own closed forms,
//! and the slip-prevention rule evaluated without any grid.
//!
//! Included with `#[path = "common/stress_cases.rs"] mod stress_cases;` (the brute-force
//! reference the suites also use is the `softgrip-reference` crate, reference/).
#![allow(dead_code)]

use softgrip::contact::ContactSize;
use softgrip::controller::{ControllerConfig, FingerShape, Mode};
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};

/// The force grid at the corners of the domain: 64 nodes over 1e-9 to 1e6 N (5.6 times the
/// default's spacing in `ln N`), 12 aspects, sensor ranges wide enough for every load.
pub fn corner_grid_config(shape: FingerShape, mode: Mode, gamma: f64) -> ControllerConfig {
    ControllerConfig {
        shape,
        mode,
        gamma,
        n_min_n: 1e-9,
        n_max_n: 1e6,
        fault_force_n: 1.0,
        force_nodes: 64,
        aspect_count: 12,
        force_range_n: 1e7,
        moment_range_nm: 1e4,
        ..ControllerConfig::default()
    }
}

/// The Euler beta function `B(a, b) = Γ(a)Γ(b)/Γ(a+b)`, through `ln Γ` (finite for the tiny
/// arguments `j/k` with `k` up to 1e6 and beyond).
pub fn beta(a: f64, b: f64) -> f64 {
    (libm::lgamma(a) + libm::lgamma(b) - libm::lgamma(a + b)).exp()
}

/// `∫₀¹ t^j (1 − t^k)^(1/k) dt = B((j+1)/k, 1 + 1/k)/k`; `1/(j+1)` for `k = ∞`.
pub fn profile_moment(k: f64, j: f64) -> f64 {
    if k.is_infinite() {
        return 1.0 / (j + 1.0);
    }
    beta((j + 1.0) / k, 1.0 + 1.0 / k) / k
}

/// The disc's pitch for any `k` (docs/model.md's table): `B(3/k, 1+1/k) / B(2/k, 1+1/k)`, i.e.
/// `E[r]` under the disc's pressure.
pub fn disc_pitch(k: f64) -> f64 {
    profile_moment(k, 2.0) / profile_moment(k, 1.0)
}

/// The uniform rectangle's pitch `(1/(4λ)) ∫∫ sqrt(x² + y²)` over `[−λ, λ] × [−1, 1]`, from
/// the primitive of `sqrt(x² + y²)` over `[0, A] × [0, B]`:
/// `(2ABD + A³ ln((B + D)/A) + B³ ln((A + D)/B))/6`, `D = sqrt(A² + B²)`.
pub fn rect_uniform_pitch(aspect: f64) -> f64 {
    let (a, b) = (aspect, 1.0f64);
    let d = a.hypot(b);
    let quarter =
        (2.0 * a * b * d + a.powi(3) * ((b + d) / a).ln() + b.powi(3) * ((a + d) / b).ln()) / 6.0;
    quarter / aspect
}

/// `E[y²]` under the symmetric rectangle's pressure (`y` in units of `a`): the far-field
/// slope, `m̃ · d → E[y²]` as `d → ∞`.
pub fn rect_y2(k: f64) -> f64 {
    profile_moment(k, 2.0) / profile_moment(k, 0.0)
}

/// `E[|y|]` under the symmetric rectangle's pressure: the pitch of a vanishingly thin strip
/// (`l/a → 0`).
pub fn rect_abs_y(k: f64) -> f64 {
    profile_moment(k, 1.0) / profile_moment(k, 0.0)
}

/// `E[y²] = E[r²]/2` under the symmetric disc's pressure: the far-field slope on the disc.
pub fn disc_y2(k: f64) -> f64 {
    0.5 * profile_moment(k, 3.0) / profile_moment(k, 1.0)
}

/// A limit-surface model (panics on a bad configuration: the tests pass valid ones).
pub fn model(shape: Shape, k: f64, skew: Option<(f64, f64, f64)>, order: usize) -> FlsModel<f64> {
    FlsModel::new(FlsConfig {
        shape,
        k,
        skew,
        order: QuadratureOrder::new(order).unwrap(),
    })
    .unwrap()
}

/// The highest quadrature order: converged to about 1e-15 (tests/fls_accuracy.rs).
pub const REFERENCE_ORDER: usize = 128;

/// The limit-surface model the controller uses at the contact half-width `a` [m].
pub fn model_at(cfg: &ControllerConfig, a: f64, order: usize) -> FlsModel<f64> {
    model(
        match cfg.shape {
            FingerShape::Rect => Shape::Rect {
                aspect: cfg.half_length_m / a,
            },
            FingerShape::Disc => Shape::Disc,
        },
        cfg.k,
        cfg.skew.map(|p| (p.delta_over_a, p.alpha, p.locus_over_a)),
        order,
    )
}

/// docs/model.md's rule evaluated without any grid: the least `N` (geometric bisection over
/// `[1e-14, 1e10]` N to 1e-13 relative) at which `s` times the load lies inside the limit
/// surface of the contact at `N`, with the exact pitch (and in table mode a 1024-sample sweep)
/// at `l/a(N)` recomputed for every trial `N`.
pub fn exact_required(cfg: &ControllerConfig, f: f64, m: f64, s: f64) -> f64 {
    let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma).unwrap();
    // A fixed contact needs one model; a growing one needs a model per trial force.
    let fixed = (cfg.shape == FingerShape::Disc || cfg.gamma == 0.0)
        .then(|| model_at(cfg, contact.half_width_m(1.0), 28));
    let fixed_table = match (&fixed, cfg.mode) {
        (Some(m), Mode::Table) => Some(Box::new(FlsTable::<f64, 1025>::sweep(m, 1024).unwrap())),
        _ => None,
    };
    let holds = |n: f64| {
        let a = contact.half_width_m(n);
        let owned;
        let model = match &fixed {
            Some(m) => m,
            None => {
                owned = model_at(cfg, a, 28);
                &owned
            }
        };
        let x = s * f / (cfg.mu * n);
        let y = s * m / (cfg.mu * n * a);
        match cfg.mode {
            Mode::Ellipse => x * x + (y / model.pitch()).powi(2) <= 1.0,
            Mode::Table => match &fixed_table {
                Some(t) => t.utilisation(x, y) <= 1.0,
                None => {
                    FlsTable::<f64, 1025>::sweep(model, 1024)
                        .unwrap()
                        .utilisation(x, y)
                        <= 1.0
                }
            },
        }
    };
    let (mut lo, mut hi) = (1e-14f64, 1e10f64);
    for _ in 0..300 {
        let mid = (lo * hi).sqrt();
        if holds(mid) {
            hi = mid
        } else {
            lo = mid
        }
        if hi / lo - 1.0 < 1e-13 {
            break;
        }
    }
    hi
}

/// SplitMix64: a fixed, reproducible stream for table-driven spreads.
#[derive(Debug, Clone)]
pub struct SplitMix(pub u64);

impl SplitMix {
    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Log-uniform in `[lo, hi)`, `lo > 0`.
    pub fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (self.uniform(lo.ln(), hi.ln())).exp()
    }
}

/// A random valid controller configuration spread over the whole documented domain
/// (symmetric profile unless `skewed`). Table sizes at their defaults or above.
pub fn random_config(rng: &mut SplitMix, skewed: bool) -> ControllerConfig {
    use softgrip::controller::SkewParams;
    let shape = if rng.uniform(0.0, 1.0) < 0.3 {
        FingerShape::Disc
    } else {
        FingerShape::Rect
    };
    let k = if rng.uniform(0.0, 1.0) < 0.1 {
        f64::INFINITY
    } else {
        rng.log_uniform(1.0, 1e6)
    };
    let gamma = match rng.next_u64() % 4 {
        0 => 0.0,
        1 => 0.5,
        2 => 1.0 / 3.0,
        _ => rng.uniform(0.0, 0.5),
    };
    let n_min = rng.log_uniform(1e-3, 1.0);
    let n_max = n_min * rng.log_uniform(10.0, 1e4);
    let skew = skewed.then(|| {
        let delta = rng.uniform(0.0, 0.999);
        SkewParams {
            delta_over_a: delta,
            alpha: rng.log_uniform(0.01, 100.0),
            locus_over_a: if shape == FingerShape::Rect {
                delta / 2.0
            } else {
                0.0
            },
        }
    });
    ControllerConfig {
        mu: rng.log_uniform(0.05, 3.0),
        shape,
        k,
        skew,
        c_m_per_n_gamma: rng.log_uniform(3e-4, 1e-2),
        gamma,
        half_length_m: rng.log_uniform(1e-3, 5e-2),
        safety: rng.uniform(1.0, 3.0),
        n_min_n: n_min,
        n_max_n: n_max,
        fault_force_n: rng.uniform(n_min, n_max),
        force_nodes: 16 + (rng.next_u64() % 49) as u16,
        table_samples: 48 + (rng.next_u64() % 81) as u16,
        aspect_count: 8 + (rng.next_u64() % 5) as u16,
        mode: Mode::Ellipse,
        ..ControllerConfig::default()
    }
}
