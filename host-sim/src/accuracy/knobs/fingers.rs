//! The work budget of a run, the loads and grid points it measures at, and the two
//! reference fingers.

use super::*;

/// How much work a run does: the quick run and the full run differ only here.
#[derive(Debug, Clone)]
pub struct Budget {
    /// Whether this is `--quick`.
    pub quick: bool,
    /// Target forces `N*` of the load set, log-spaced \[N\].
    pub load_forces: usize,
    /// Directions of the load set, from pure force to pure torsion.
    pub load_directions: usize,
    /// Forces of the surface-error grid (log-spaced over the grid range).
    pub grid_forces: usize,
    /// Directions of the surface-error grid.
    pub grid_directions: usize,
    /// Timing rounds: each round times every configuration's start-up once and its tick
    /// once (round-robin, so that a burst of load on the shared machine spreads over all
    /// configurations instead of biasing one); the report gives the medians.
    pub rounds: usize,
    /// Passes over the 256 timing loads per tick repetition.
    pub tick_passes: usize,
    /// Loads per round of the exact-per-tick timing.
    pub exact_tick_loads: usize,
    /// Quadrature orders tried.
    pub orders: Vec<u16>,
    /// Centre-of-rotation samples tried.
    pub samples: Vec<u16>,
    /// Aspect grid sizes tried.
    pub aspects: Vec<u16>,
    /// Force-node counts tried.
    pub nodes: Vec<u16>,
}

impl Budget {
    /// The quick run (`--quick`): under a minute on two cores.
    pub fn quick() -> Self {
        Self {
            quick: true,
            load_forces: 4,
            load_directions: 5,
            grid_forces: 6,
            grid_directions: 12,
            rounds: 5,
            tick_passes: 4,
            exact_tick_loads: 8,
            orders: vec![8, 16, 28],
            samples: vec![8, 32, 48],
            aspects: vec![2, 8],
            nodes: vec![8, 48],
        }
    }

    /// The full run.
    pub fn full() -> Self {
        Self {
            quick: false,
            load_forces: 10,
            load_directions: 11,
            grid_forces: 24,
            grid_directions: 64,
            rounds: 21,
            tick_passes: 16,
            exact_tick_loads: 32,
            orders: vec![4, 6, 8, 12, 16, 20, 28, 40],
            samples: vec![8, 16, 24, 32, 48, 64, 96, 128],
            aspects: vec![2, 3, 4, 6, 8, 12],
            nodes: vec![4, 8, 16, 24, 32, 48, 64],
        }
    }
}

/// Median of `v` (0 for an empty set).
pub fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Evenly log-spaced values from `lo` to `hi` inclusive.
pub fn log_space(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    if n <= 1 {
        return vec![lo];
    }
    (0..n)
        .map(|i| (lo.ln() + (hi.ln() - lo.ln()) * i as f64 / (n - 1) as f64).exp())
        .collect()
}

/// One load of the error set, with its exact answers.
#[derive(Debug, Clone, Copy)]
pub struct Load {
    /// Tangential force components \[N\].
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
    /// Torsional moment [N·m].
    pub mn: f64,
    /// Measured normal force \[N\].
    pub n_meas: f64,
    /// `N_req(s)` of the ellipse rule with the exact pitch.
    pub n_ellipse: f64,
    /// `N_req(s)` of the exact surface.
    pub n_exact: f64,
}

/// One point of the surface-error grid: a normalised load at a normal force, with its
/// exact utilisation.
#[derive(Debug, Clone, Copy)]
pub struct GridPoint {
    /// Normal force \[N\].
    pub n: f64,
    /// Tangential force \[N\].
    pub ft: f64,
    /// Torsional moment [N·m].
    pub mn: f64,
    /// Its utilisation on the exact surface.
    pub u_exact: f64,
}

/// One finger with its references.
#[derive(Debug, Clone)]
pub struct FingerRef {
    /// "rectangle" or "disc".
    pub name: &'static str,
    /// The finger and its converged surface.
    pub reference: ExactSurface,
    /// The error loads.
    pub loads: Vec<Load>,
    /// The surface-error grid.
    pub grid: Vec<GridPoint>,
    /// Largest radial gap between the Eq. 10 ellipse and the exact surface over the grid.
    pub ellipse_gap: f64,
}

/// The default rectangle ([`ControllerConfig::default`]).
pub fn rect_config() -> ControllerConfig {
    ControllerConfig::default()
}

/// The disc: a hemispherical fingertip, `k = 2`, Hertzian growth `a ∝ N^⅓`.
pub fn disc_config() -> ControllerConfig {
    ControllerConfig {
        shape: FingerShape::Disc,
        gamma: 1.0 / 3.0,
        ..ControllerConfig::default()
    }
}

impl FingerRef {
    /// Builds the loads, the grid and their exact answers for `cfg`.
    pub fn build(name: &'static str, cfg: ControllerConfig, b: &Budget) -> Result<Self, String> {
        let reference = ExactSurface::reference(Finger::new(cfg)?)?;
        let finger = reference.finger().clone();
        let s = cfg.safety;
        let mut loads = Vec::new();
        let mut i = 0usize;
        for &n_star in &log_space(0.4, 15.0, b.load_forces) {
            let arm = finger.a(n_star) * reference.pitch_at(n_star);
            for j in 0..b.load_directions {
                let psi =
                    std::f64::consts::FRAC_PI_2 * j as f64 / (b.load_directions.max(2) - 1) as f64;
                // On the Eq. 10 ellipse at N*: the ellipse rule's answer is N* itself.
                let ft = cfg.mu * n_star * psi.cos() / s;
                let mn = cfg.mu * n_star * arm * psi.sin() / s;
                let beta = 0.61 * i as f64;
                let (fx, fy) = (ft * beta.cos(), ft * beta.sin());
                // The tick asks for a round patch's moment times its own factor
                // (`DISC_TORSION_SAFETY_FACTOR`): the exact and ellipse answers it is
                // measured against are for that requirement.
                let beta = cfg.torsion_factor();
                let (big_f, big_m) = (s * ft / cfg.mu, s * beta * mn / cfg.mu);
                loads.push(Load {
                    fx,
                    fy,
                    mn,
                    n_meas: n_star * (0.8 + 0.05 * (i % 9) as f64),
                    n_ellipse: reference.required(Rule::Ellipse, big_f, big_m),
                    n_exact: reference.required(Rule::Exact, big_f, big_m),
                });
                i += 1;
            }
        }
        let mut grid = Vec::new();
        let mut ellipse_gap = 0.0f64;
        let forces = log_space(cfg.n_min_n * 1.25, cfg.n_max_n * 0.975, b.grid_forces);
        for &n in &forces {
            let model = reference.model_at(n);
            let pitch = model.pitch();
            let a = finger.a(n);
            for j in 0..b.grid_directions {
                // Directions strictly between the axes, where the tables interpolate.
                let psi = std::f64::consts::FRAC_PI_2 * (j as f64 + 0.5) / b.grid_directions as f64;
                let (f, m) = (0.5 * psi.cos(), 0.5 * pitch * psi.sin());
                let u_exact = reference.utilisation_normalised(&model, f, m);
                // The Eq. 10 ellipse's utilisation here is the probe's scale, by construction.
                ellipse_gap = ellipse_gap.max((u_exact / 0.5 - 1.0).abs());
                grid.push(GridPoint {
                    n,
                    ft: cfg.mu * n * f,
                    mn: cfg.mu * n * a * m,
                    u_exact,
                });
            }
        }
        Ok(Self {
            name,
            reference,
            loads,
            grid,
            ellipse_gap,
        })
    }
}
