//! The `fls` plant: a contact that slips exactly on softgrip's limit surface (docs/model.md)
//! with the contact law `a = c·N^γ`, computed as the ground truth of the simulator does
//! (`sim::truth`): the core's surfaces in f64, 256 centres of rotation per sweep, 24
//! aspects spaced in `ln(l/a)` over the forces asked for (within about 2e-4 of the
//! integrals). Cost: building, 24 sweeps (about 15 ms symmetric, 40 ms skewed; the skewed
//! disc, a 2-D integral, about 1 s); an onset, two table lookups.

use super::Rig;
use softgrip::contact::ContactSize;
use softgrip::controller::{FingerShape, SkewParams};
use softgrip::fls::AspectGrid;
use softgrip::{ConfigError, FlsConfig, FlsModel, QuadratureOrder, Shape};

const ASPECTS: usize = 24;
const SAMPLES: usize = 256;

/// The finger's parameters, as a scene's `[finger]` table and its skew give them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FingerSpec {
    /// Shape.
    pub shape: FingerShape,
    /// Friction coefficient.
    pub mu: f64,
    /// Pressure exponent `k ≥ 1`.
    pub k: f64,
    /// `c` in `a = c·N^γ` [m/N^γ].
    pub c: f64,
    /// `γ ∈ [0, 1/2]`.
    pub gamma: f64,
    /// Half-length `l` \[m\] of the rectangle.
    pub half_length_m: f64,
    /// The skew of the pressure peak, if any.
    pub skew: Option<SkewParams>,
}

/// The exact-surface plant.
#[derive(Debug, Clone)]
pub struct FlsRig {
    spec: FingerSpec,
    contact: ContactSize<f64>,
    grid: Box<AspectGrid<f64, ASPECTS, { SAMPLES + 1 }>>,
}

impl FlsRig {
    /// Builds the surfaces for normal forces in `[n_lo, n_hi]` \[N\] (clamped outside).
    /// Errors name the core's parameter (`k`, `c`, `gamma`, `aspect`, `skew`, ...).
    pub fn new(spec: FingerSpec, n_lo: f64, n_hi: f64) -> Result<Self, ConfigError> {
        let contact = ContactSize::<f64>::new(spec.c, spec.gamma)?;
        let rect = spec.shape == FingerShape::Rect;
        let model = FlsModel::<f64>::new(FlsConfig {
            shape: if rect {
                Shape::Rect { aspect: 1.0 }
            } else {
                Shape::Disc
            },
            k: spec.k,
            skew: spec.skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
            order: QuadratureOrder::DEFAULT,
        })?;
        let aspect = |n: f64| spec.half_length_m / contact.half_width_m(n);
        let (lo, hi) = (aspect(n_hi), aspect(n_lo));
        let grid = if rect && spec.gamma > 0.0 && hi > lo {
            AspectGrid::build(&model, lo, hi, ASPECTS, SAMPLES)
        } else {
            AspectGrid::build(&model, hi, hi, 1, SAMPLES)
        }?;
        Ok(Self {
            spec,
            contact,
            grid: Box::new(grid),
        })
    }

    /// The finger it models.
    pub fn spec(&self) -> &FingerSpec {
        &self.spec
    }

    /// The pitch at normal force `normal_n`.
    pub fn pitch(&self, normal_n: f64) -> f64 {
        self.grid.pitch(self.aspect(normal_n))
    }

    fn aspect(&self, normal_n: f64) -> f64 {
        if self.spec.shape == FingerShape::Rect {
            self.spec.half_length_m / self.contact.half_width_m(normal_n)
        } else {
            1.0
        }
    }
}

impl Rig for FlsRig {
    fn indentation_half_width_m(&self, normal_n: f64) -> f64 {
        self.contact.half_width_m(normal_n)
    }

    fn slip_onset(&self, normal_n: f64, ft_unit_n: f64, mn_unit_nm: f64) -> Option<(f64, f64)> {
        let a = self.contact.half_width_m(normal_n);
        let cap = self.spec.mu * normal_n;
        if !(cap > 0.0 && a > 0.0) || (ft_unit_n == 0.0 && mn_unit_nm == 0.0) {
            return None;
        }
        let u = self.grid.utilisation(
            self.aspect(normal_n),
            ft_unit_n / cap,
            mn_unit_nm / (cap * a),
        );
        (u > 0.0 && u.is_finite()).then(|| (ft_unit_n / u, mn_unit_nm / u))
    }
}
