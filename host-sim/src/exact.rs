//! The exact answers `host-sim accuracy` measures against and `host-sim required-force`
//! compares with (a module of its own, so neither command imports the other's), and the
//! "exact integration per tick" rule: docs/model.md's slip-prevention rule evaluated in f64 with no grid at all, the limit
//! surface integrated by [`FlsModel`] at every trial normal force.
//!
//! - [`Finger`]: the contact of a [`ControllerConfig`] (`a = c·N^γ`, `l/a(N)`).
//! - [`ExactSurface`]: the limit surface's radius in a direction, by a bracketed root
//!   search over the sweep parameter `t` (the surfaces measured here are star-shaped, so
//!   the direction of the point turns monotonically with `t`), the exact pitch, and the
//!   least normal force that holds a load under either rule (a bracketed root search in
//!   `ln N`).
//!
//! The reference is an [`ExactSurface`] at quadrature order 128 (converged to about 1e-15,
//! docs/core.md, "Accuracy: what the tests assert") with tolerances near f64 rounding; the
//! per-tick exact rule is the same search at the default order 28 with tolerances fit for a
//! control loop.

use softgrip::contact::ContactSize;
use softgrip::controller::{ControllerConfig, FingerShape};
use softgrip::fls::SweepMap;
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};

/// Which surface a rule tests the scaled load against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rule {
    /// The Eq. 10 ellipse with the exact pitch at `l/a(N)`.
    Ellipse,
    /// The exact limit surface at `l/a(N)`.
    Exact,
}

/// The contact of a controller configuration.
#[derive(Debug, Clone)]
pub struct Finger {
    /// The configuration (shape, `k`, contact law, `l`, `μ`, safety, grid range).
    pub cfg: ControllerConfig,
    contact: ContactSize<f64>,
}

impl Finger {
    /// The contact of `cfg` (which must be valid).
    pub fn new(cfg: ControllerConfig) -> Result<Self, String> {
        let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma)
            .map_err(|e| format!("contact law: {e}"))?;
        Ok(Self { cfg, contact })
    }

    /// The half-width `a(N)` \[m\].
    pub fn a(&self, n: f64) -> f64 {
        self.contact.half_width_m(n)
    }

    /// The core's shape at the normal force `n`.
    pub fn shape(&self, n: f64) -> Shape {
        match self.cfg.shape {
            FingerShape::Rect => Shape::Rect {
                aspect: self.cfg.half_length_m / self.a(n),
            },
            FingerShape::Disc => Shape::Disc,
        }
    }
}

/// A bracketed Illinois (modified regula falsi) search for the root of `g` on `[a, b]`,
/// `g(a) ≤ 0 ≤ g(b)`, down to `|b − a| ≤ tol` (or `max_iter` steps; a step that would
/// leave the bracket bisects). Returns the bracket end nearer the root by `|g|` and the
/// number of evaluations.
pub fn illinois(
    mut a: f64,
    mut b: f64,
    tol: f64,
    max_iter: usize,
    g: impl Fn(f64) -> f64,
) -> (f64, usize) {
    let (mut ga, mut gb) = (g(a), g(b));
    let mut evals = 2;
    if ga >= 0.0 {
        return (a, evals);
    }
    if gb <= 0.0 {
        return (b, evals);
    }
    let mut side = 0i8;
    for _ in 0..max_iter {
        if b - a <= tol {
            break;
        }
        let mut c = b - gb * (b - a) / (gb - ga);
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let gc = g(c);
        evals += 1;
        if gc == 0.0 {
            return (c, evals);
        }
        if gc > 0.0 {
            b = c;
            gb = gc;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        } else {
            a = c;
            ga = gc;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        }
    }
    if -ga < gb {
        (a, evals)
    } else {
        (b, evals)
    }
}

/// The exact limit surface of a [`Finger`] at one quadrature order, with the tolerances of
/// its root searches.
#[derive(Debug, Clone)]
pub struct ExactSurface {
    finger: Finger,
    model: FlsModel<f64>,
    /// Tolerance on the sweep parameter `t` of the radius search.
    tol_t: f64,
    /// Relative tolerance on `N` of the force search.
    tol_n: f64,
}

impl ExactSurface {
    /// The surface of `finger` at quadrature `order`, radius searches to `tol_t` in the
    /// sweep parameter and force searches to `tol_n` relative.
    pub fn new(finger: Finger, order: usize, tol_t: f64, tol_n: f64) -> Result<Self, String> {
        let cfg = &finger.cfg;
        let model = FlsModel::<f64>::new(FlsConfig {
            shape: finger.shape(1.0),
            k: cfg.k,
            skew: cfg.skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
            order: QuadratureOrder::new(order).map_err(|e| e.to_string())?,
        })
        .map_err(|e| e.to_string())?;
        Ok(Self {
            finger,
            model,
            tol_t,
            tol_n,
        })
    }

    /// The reference: order 128, tolerances at f64 rounding.
    pub fn reference(finger: Finger) -> Result<Self, String> {
        Self::new(finger, 128, 1e-15, 1e-14)
    }

    /// The finger.
    pub fn finger(&self) -> &Finger {
        &self.finger
    }

    /// The model at the contact of normal force `n`.
    pub fn model_at(&self, n: f64) -> FlsModel<f64> {
        match self.finger.shape(n) {
            Shape::Rect { aspect } => self
                .model
                .with_aspect(aspect)
                .unwrap_or_else(|_| self.model.clone()),
            Shape::Disc => self.model.clone(),
        }
    }

    /// The model at aspect `l/a` (rectangle; the disc ignores it).
    pub fn model_at_aspect(&self, aspect: f64) -> FlsModel<f64> {
        self.model
            .with_aspect(aspect)
            .unwrap_or_else(|_| self.model.clone())
    }

    /// The radius of `model`'s surface in the direction of `(f, m)` (normalised
    /// coordinates `(f̃, m̃)`, both `≥ 0`, not both 0).
    pub fn radius(&self, model: &FlsModel<f64>, f: f64, m: f64) -> f64 {
        if f <= 0.0 {
            return model.pitch();
        }
        if m <= 0.0 {
            return 1.0;
        }
        let map = SweepMap::<f64>::for_shape(model.config().shape);
        let cross = |t: f64| {
            let p = model.point(map.d_of(t));
            p.f * m - p.m * f
        };
        let (t, _) = illinois(0.0, 1.0, self.tol_t, 400, cross);
        let p = model.point(map.d_of(t));
        p.f.hypot(p.m)
    }

    /// The pitch at the contact of normal force `n`.
    pub fn pitch_at(&self, n: f64) -> f64 {
        self.model_at(n).pitch()
    }

    /// The exact utilisation of the normalised load `(f̃, m̃)` on `model`'s surface.
    pub fn utilisation_normalised(&self, model: &FlsModel<f64>, f: f64, m: f64) -> f64 {
        if f == 0.0 && m == 0.0 {
            return 0.0;
        }
        f.hypot(m) / self.radius(model, f, m)
    }

    /// Utilisation of the demand `F = |f_t|/μ`, `M = |m_n|/μ` at the normal force `n`,
    /// under `rule`.
    pub fn utilisation(&self, rule: Rule, big_f: f64, big_m: f64, n: f64) -> f64 {
        let a = self.finger.a(n);
        let (f, m) = (big_f / n, big_m / (n * a));
        let model = self.model_at(n);
        match rule {
            Rule::Ellipse => f.hypot(m / model.pitch()),
            Rule::Exact => self.utilisation_normalised(&model, f, m),
        }
    }

    /// The least normal force in `[lo, hi]` at which the demand `(F, M)` holds under
    /// `rule` (`lo` if it holds there, `hi` if it does not hold there), and the number of
    /// trial forces.
    pub fn required_in(
        &self,
        rule: Rule,
        big_f: f64,
        big_m: f64,
        lo: f64,
        hi: f64,
    ) -> (f64, usize) {
        if big_f == 0.0 && big_m == 0.0 {
            return (0.0, 0);
        }
        let g = |x: f64| -self.utilisation(rule, big_f, big_m, x.exp()).ln();
        let (x, evals) = illinois(lo.ln(), hi.ln(), self.tol_n, 400, g);
        (x.exp(), evals)
    }

    /// [`ExactSurface::required_in`] on `[N_min/100, 100·N_max]`.
    pub fn required(&self, rule: Rule, big_f: f64, big_m: f64) -> f64 {
        let cfg = &self.finger.cfg;
        self.required_in(rule, big_f, big_m, cfg.n_min_n / 100.0, cfg.n_max_n * 100.0)
            .0
    }
}

/// What one exact tick decides: `N_req(s)`, `N_slip` and the utilisation at the measured
/// force.
#[derive(Debug, Clone, Copy)]
pub struct ExactTick {
    /// `N_req(s)` \[N\].
    pub required_n: f64,
    /// `N_slip` \[N\].
    pub n_slip_n: f64,
    /// Utilisation at the measured normal force.
    pub utilisation: f64,
}

/// One tick of the exact rule: the same three answers the controller's tick gives, with the
/// limit surface integrated at every trial force (docs/model.md's rule with no grid). `N_slip`
/// is searched on `[N_min/100, 100·N_max]`, `N_req(s)` on `[N_slip, s·N_slip]` (docs/model.md:
/// `N_req(s) ≤ s·N_slip`).
pub fn exact_tick(surface: &ExactSurface, fx: f64, fy: f64, mn: f64, n_meas: f64) -> ExactTick {
    let cfg = &surface.finger().cfg;
    let big_f = fx.hypot(fy) / cfg.mu;
    let big_m = mn.abs() / cfg.mu;
    let s = cfg.safety;
    let n_slip = surface.required(Rule::Exact, big_f, big_m);
    let required_n = if n_slip > 0.0 {
        surface
            .required_in(
                Rule::Exact,
                s * big_f,
                s * big_m,
                n_slip,
                s * n_slip * (1.0 + 1e-12),
            )
            .0
    } else {
        0.0
    };
    let utilisation = if n_meas > 0.0 {
        surface.utilisation(Rule::Exact, big_f, big_m, n_meas)
    } else {
        softgrip::controller::UTILISATION_MAX
    };
    ExactTick {
        required_n,
        n_slip_n: n_slip,
        utilisation,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use softgrip::FlsTable;

    fn rect() -> ExactSurface {
        ExactSurface::reference(Finger::new(ControllerConfig::default()).unwrap()).unwrap()
    }

    #[test]
    fn the_radius_meets_the_surface_and_its_axes() {
        let s = rect();
        let model = s.model_at_aspect(1.7);
        assert_eq!(s.radius(&model, 1.0, 0.0), 1.0);
        assert_eq!(s.radius(&model, 0.0, 1.0), model.pitch());
        for d in [0.05, 0.4, 1.0, 3.0, 40.0] {
            let p = model.point(d);
            let r = s.radius(&model, p.f, p.m);
            assert!((r / p.f.hypot(p.m) - 1.0).abs() < 1e-12, "d = {d}");
        }
    }

    #[test]
    fn the_ellipse_rule_solves_to_the_force_it_was_built_at() {
        let s = rect();
        let f = s.finger().clone();
        for (n, psi) in [(0.5, 0.3), (3.0, 1.0), (14.0, 1.5)] {
            let arm = f.a(n) * s.pitch_at(n);
            let (big_f, big_m) = (n * f64::cos(psi), n * arm * f64::sin(psi));
            let got = s.required(Rule::Ellipse, big_f, big_m);
            assert!((got / n - 1.0).abs() < 1e-12, "{got} vs {n}");
            // The exact surface lies inside the ellipse: it asks for more.
            assert!(s.required(Rule::Exact, big_f, big_m) >= got);
        }
    }

    #[test]
    fn the_exact_rule_agrees_with_a_dense_table_bisection() {
        // The idea of tests/controller.rs: bisection on N with a 1024-sample table.
        let s = rect();
        let f = s.finger().clone();
        let (big_f, big_m) = (2.0, 0.012);
        let holds = |n: f64| {
            let model = s.model_at(n);
            let table = FlsTable::<f64, 1025>::sweep(&model, 1024).unwrap();
            table.utilisation(big_f / n, big_m / (n * f.a(n))) <= 1.0
        };
        let (mut lo, mut hi) = (0.1f64, 50.0f64);
        while hi / lo - 1.0 > 1e-9 {
            let mid = (lo * hi).sqrt();
            if holds(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let got = s.required(Rule::Exact, big_f, big_m);
        // The table's chords lie inside: its answer is a little higher.
        assert!(
            hi >= got * (1.0 - 1e-9) && hi < got * (1.0 + 1e-5),
            "{hi} vs {got}"
        );
    }
}
