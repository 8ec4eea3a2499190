//! The ground truth: whether the true load lies inside the true limit surface, computed
//! by the high-accuracy core in f64 with the effects the scene enables (the true skew, the
//! true contact size).
//!
//! The surfaces are precomputed once per run on a fine grid: 256 centres of rotation per
//! sweep and, for a rectangle whose contact grows with the load, 24 aspect ratios spaced
//! in `ln(l/a)` over the forces the run can reach. A step then costs two table lookups.

use crate::sim::scene::{Scene, SceneError};
use softgrip::contact::ContactSize;
use softgrip::controller::{FingerShape, SkewParams};
use softgrip::fls::AspectGrid;
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};
use std::sync::Arc;

const ASPECTS: usize = 24;
const SAMPLES: usize = 256;

/// The true contact's limit surfaces (cheap to clone: the surfaces are shared).
#[derive(Debug, Clone)]
pub struct Truth {
    mu: f64,
    half_length_m: f64,
    rect: bool,
    contact: ContactSize<f64>,
    grid: Arc<AspectGrid<f64, ASPECTS, { SAMPLES + 1 }>>,
}

/// The true state of the contact at one step.
#[derive(Debug, Clone, Copy)]
pub struct TrueLoad {
    /// `f̃ = f_t/(μN)`.
    pub f_norm: f64,
    /// `m̃ = m_n/(μNa)`.
    pub m_norm: f64,
    /// The pitch at the present aspect.
    pub pitch: f64,
    /// The utilisation (≥ 1 slips); `+∞` for a load on no normal force.
    pub utilisation: f64,
}

impl Truth {
    /// Builds the surfaces for normal forces in `[n_lo, n_hi]` (clamped outside).
    pub fn build(
        scene: &Scene,
        skew: Option<SkewParams>,
        n_lo: f64,
        n_hi: f64,
    ) -> Result<Self, SceneError> {
        let f = &scene.finger;
        let err = |e: softgrip::ConfigError| SceneError(format!("finger: {e}"));
        let contact = ContactSize::<f64>::new(f.c, f.gamma).map_err(err)?;
        let rect = f.shape == FingerShape::Rect;
        let model = FlsModel::<f64>::new(FlsConfig {
            shape: if rect {
                Shape::Rect { aspect: 1.0 }
            } else {
                Shape::Disc
            },
            k: f.k,
            skew: skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
            order: QuadratureOrder::DEFAULT,
        })
        .map_err(err)?;
        let aspect = |n: f64| f.half_length_m / contact.half_width_m(n);
        let (lo, hi) = (aspect(n_hi), aspect(n_lo));
        let grid = if rect && f.gamma > 0.0 {
            AspectGrid::build(&model, lo, hi, ASPECTS, SAMPLES)
        } else {
            AspectGrid::build(&model, hi, hi, 1, SAMPLES)
        }
        .map_err(err)?;
        Ok(Self {
            mu: f.mu,
            half_length_m: f.half_length_m,
            rect,
            contact,
            grid: Arc::new(grid),
        })
    }

    /// The same surfaces with another true friction coefficient `mu` [-] (the surfaces in
    /// `(f̃, m̃)` do not depend on μ).
    pub fn with_mu(&self, mu: f64) -> Self {
        Self { mu, ..self.clone() }
    }

    /// The true friction coefficient [-].
    pub fn mu(&self) -> f64 {
        self.mu
    }

    /// The equilibrium half-width `c·N^γ` \[m\].
    pub fn half_width_m(&self, normal_n: f64) -> f64 {
        self.contact.half_width_m(normal_n)
    }

    /// The pitch at half-width `a`.
    pub fn pitch(&self, half_width_m: f64) -> f64 {
        self.grid.pitch(self.half_length_m / half_width_m)
    }

    /// The surface at half-width `a` in `(f̃, m̃/pitch)`, from pure torsion to pure
    /// translation, for plots.
    pub fn normalised_surface(&self, half_width_m: f64) -> Vec<(f64, f64)> {
        let pitch = self.pitch(half_width_m);
        (0..=90)
            .map(|i| {
                let th = f64::from(i) * std::f64::consts::FRAC_PI_2 / 90.0;
                let (f, m) = (th.sin(), th.cos() * pitch);
                let u = self
                    .grid
                    .utilisation(self.half_length_m / half_width_m, f, m);
                (f / u, m / u / pitch)
            })
            .collect()
    }

    /// The true load state for a contact load `(f_t, m_n)` at normal force `N` and
    /// half-width `a`.
    pub fn evaluate(&self, ft_n: f64, mn_nm: f64, normal_n: f64, half_width_m: f64) -> TrueLoad {
        let aspect = if self.rect {
            self.half_length_m / half_width_m
        } else {
            1.0
        };
        let pitch = self.grid.pitch(aspect);
        let cap = self.mu * normal_n;
        if !(cap > 0.0 && half_width_m > 0.0) {
            let loaded = ft_n != 0.0 || mn_nm != 0.0;
            return TrueLoad {
                f_norm: if loaded { f64::INFINITY } else { 0.0 },
                m_norm: 0.0,
                pitch,
                utilisation: if loaded { f64::INFINITY } else { 0.0 },
            };
        }
        let f_norm = ft_n.abs() / cap;
        let m_norm = mn_nm.abs() / (cap * half_width_m);
        TrueLoad {
            f_norm,
            m_norm,
            pitch,
            utilisation: self.grid.utilisation(aspect, f_norm, m_norm),
        }
    }
}
