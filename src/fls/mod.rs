//! The friction limit surface (FLS): normalised force and moment `(f̃, m̃)` that a sliding
//! patch transmits for each position `d = d_c/a` of its centre of rotation (docs/model.md,
//! "Sliding, friction and the limit surface"; the paper's Eq. 11–21).
//!
//! - [`FlsModel`] evaluates one point of the surface, by tanh-sinh quadrature split at every
//!   singular point of the integrand (see [`rect`](self) and [`disc`](self) for the closed
//!   forms that reduce the symmetric cases to 1-D integrals).
//! - [`SweepMap`] maps `d ∈ [0, ∞)` onto `t ∈ [0, 1]`, and a sweep is stored in a
//!   fixed-capacity [`FlsTable`] (module `sweep`).
//! - [`EllipseFit`] gives the pitch (Eq. 22), the least-squares ellipse and the gap to
//!   Eq. 10 ([`RadialGap`]); [`InscribedEllipse`] the one inside the exact surfaces (module
//!   `ellipse`).
//! - [`AspectGrid`] precomputes pitches and tables over a range of aspect ratios `l/a`
//!   (module `aspect_grid`).
//!
//! Accuracy at [`QuadratureOrder::DEFAULT`] in f64: within 1e-9 of the converged integral
//! for every `d` including 0, 1e-12, the patch edge and 1e12 (`tests/fls_accuracy.rs`), and
//! within 1e-8 of an independent brute force (`tests/fls_brute_force.rs`). In f32 within
//! 2e-6. Cost on the project's x86-64 VM (`cargo bench --bench fls`, medians): a symmetric
//! rectangle point 1.9 µs, a skewed rectangle point 5.4 µs, a symmetric disc point 5.5 µs,
//! a skewed disc point (a 2-D integral) 186 µs.

mod disc;
mod rect;

mod aspect_grid;
mod ellipse;
mod sweep;

pub use aspect_grid::{AspectEntry, AspectGrid, GridPosition};
pub use ellipse::{ellipse_radius, EllipseFit, InscribedEllipse, RadialGap};
pub use sweep::{FlsTable, SweepMap};

use crate::error::{check, ConfigError};
use crate::pressure::KProfile;
use crate::quadrature::{QuadratureOrder, TanhSinh, MAX_NODES_PER_SIDE};
use crate::real::{Real, SqrtFn};
use crate::skew::SkewLaw;

/// Beyond this `d = d_c/a` (times the patch's radius of gyration) a point is returned as the
/// translation limit `(1, 0)`: the exact values differ from it by less than 1e-15.
pub const FAR_FIELD_D: f64 = 1e15;

/// The patch shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// Hemicylindrical fingertip: the rectangle `[-l, l] × [-a, a]`, with aspect `l/a > 0`.
    Rect {
        /// `λ = l/a`.
        aspect: f64,
    },
    /// Hemispherical fingertip: the disc of radius `a`.
    Disc,
}

impl Shape {
    /// The shape's name as the command line spells it.
    pub fn name(&self) -> &'static str {
        match self {
            Shape::Rect { .. } => "rect",
            Shape::Disc => "disc",
        }
    }
}

/// A point of the limit surface.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FlsPoint<T> {
    /// Centre-of-rotation distance `d_c/a` (`+∞` for pure translation).
    pub d: T,
    /// `f̃ = |f_t|/(μN)`.
    pub f: T,
    /// `m̃ = |m_n|/(μNa)`.
    pub m: T,
}

/// What one limit surface depends on, before validation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlsConfig {
    /// Patch shape (and aspect for the rectangle).
    pub shape: Shape,
    /// Pressure exponent `k ≥ 1` (`f64::INFINITY` for uniform).
    pub k: f64,
    /// Skew `(Δ/a, α, h/a)`, or `None` for the symmetric profile.
    pub skew: Option<(f64, f64, f64)>,
    /// Quadrature order.
    pub order: QuadratureOrder,
}

impl Default for FlsConfig {
    /// The paper's base case: rectangle, `l = a`, `k = 2`, no skew.
    fn default() -> Self {
        Self {
            shape: Shape::Rect { aspect: 1.0 },
            k: 2.0,
            skew: None,
            order: QuadratureOrder::DEFAULT,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Patch<T> {
    Rect { lambda: T },
    Disc,
}

/// A validated limit-surface model, ready to evaluate points. Build it once at start-up;
/// [`FlsModel::point`] cannot fail.
#[derive(Debug, Clone)]
pub struct FlsModel<T> {
    config: FlsConfig,
    patch: Patch<T>,
    profile: KProfile<T>,
    skew: Option<SkewLaw<T>>,
    rule: TanhSinh<T>,
    rect_cache: [T; 2 * MAX_NODES_PER_SIDE + 1],
    far_d: T,
    sqrt: SqrtFn<T>,
}

impl<T: Real> FlsModel<T> {
    /// Validates the configuration (parameter names `aspect`, `k`, `skew`, `alpha`, `locus`)
    /// and precomputes the quadrature rule.
    pub fn new(config: FlsConfig) -> Result<Self, ConfigError> {
        let mut model = Self::unfilled(config)?;
        model.fill();
        Ok(model)
    }

    /// [`FlsModel::new`] into `slot`, in place: the quadrature rule and the cached pressure
    /// values (2 KB in f32) are computed where they lie rather than moved there (the
    /// controller's start-up, whose peak stack this is part of). On an error `slot` is
    /// unchanged.
    pub(crate) fn build_in(
        slot: &mut Option<Self>,
        config: FlsConfig,
    ) -> Result<&mut Self, ConfigError> {
        let model = slot.insert(Self::unfilled(config)?);
        model.fill();
        Ok(model)
    }

    /// The validated model with an empty rule and cache.
    #[inline(always)]
    fn unfilled(config: FlsConfig) -> Result<Self, ConfigError> {
        let profile = KProfile::new(config.k)?;
        let patch = match config.shape {
            Shape::Rect { aspect } => {
                check(
                    "aspect",
                    aspect,
                    aspect > 0.0 && aspect.is_finite(),
                    "aspect > 0",
                )?;
                Patch::Rect {
                    lambda: T::of(aspect),
                }
            }
            Shape::Disc => Patch::Disc,
        };
        let skew = match config.skew {
            None => None,
            Some((delta, alpha, h)) => {
                let law = SkewLaw::new(delta, alpha, h)?;
                if matches!(patch, Patch::Disc) {
                    let reach = law.max_peak_radius();
                    check(
                        "locus",
                        h,
                        reach < 1.0,
                        "a locus that keeps the peak inside the disc",
                    )?;
                }
                (delta > 0.0).then_some(law)
            }
        };
        let far_d = T::of(FAR_FIELD_D) * SweepMap::<T>::for_shape(config.shape).scale();
        Ok(Self {
            config,
            patch,
            profile,
            skew,
            rule: TanhSinh::empty(),
            rect_cache: [T::zero(); 2 * MAX_NODES_PER_SIDE + 1],
            far_d,
            sqrt: SqrtFn::LIBM,
        })
    }

    /// Computes the rule and the cache of an [`FlsModel::unfilled`] model.
    fn fill(&mut self) {
        self.rule.set_order(self.config.order);
        rect::shape_cache(&self.rule, &self.profile, &mut self.rect_cache);
    }

    /// Makes `sqrt` the kernels' square root (see [`SqrtFn`]): the same points bit for
    /// bit, at another cost.
    pub(crate) fn set_sqrt(&mut self, sqrt: SqrtFn<T>) {
        self.sqrt = sqrt;
    }

    /// The configuration this model was built from.
    pub fn config(&self) -> &FlsConfig {
        &self.config
    }

    /// The same model for another aspect ratio `l/a` (rectangle only; the disc ignores it).
    /// A copy of the model (about 2 KB in f32): the start-up uses
    /// [`FlsModel::set_aspect`] instead.
    pub fn with_aspect(&self, aspect: f64) -> Result<Self, ConfigError> {
        let mut next = self.clone();
        next.set_aspect(aspect)?;
        Ok(next)
    }

    /// Changes the aspect ratio `l/a` in place (rectangle only; the disc ignores it). The
    /// quadrature rule and the cached pressure values do not depend on it. On an error
    /// (parameter `aspect`: not positive and finite) the model is unchanged.
    pub fn set_aspect(&mut self, aspect: f64) -> Result<(), ConfigError> {
        if let Patch::Rect { .. } = self.patch {
            check(
                "aspect",
                aspect,
                aspect > 0.0 && aspect.is_finite(),
                "aspect > 0",
            )?;
            self.patch = Patch::Rect {
                lambda: T::of(aspect),
            };
            self.config.shape = Shape::Rect { aspect };
            self.far_d = T::of(FAR_FIELD_D) * SweepMap::<T>::for_shape(self.config.shape).scale();
        }
        Ok(())
    }

    /// The pressure profile.
    pub fn profile(&self) -> &KProfile<T> {
        &self.profile
    }

    /// The skew law, if the profile is skewed.
    pub fn skew(&self) -> Option<&SkewLaw<T>> {
        self.skew.as_ref()
    }

    /// The limit-surface point for the centre of rotation at `d = d_c/a`.
    ///
    /// Total: `d` is taken by magnitude (the surface is symmetric), NaN reads as 0, and
    /// `d ≥ FAR_FIELD_D` times the radius of gyration (including `+∞`) gives `(1, 0)`.
    pub fn point(&self, d: T) -> FlsPoint<T> {
        let d = if d.is_nan() { T::zero() } else { d.abs() };
        if d >= self.far_d {
            return FlsPoint {
                d,
                f: T::one(),
                m: T::zero(),
            };
        }
        let (f, m) = match self.patch {
            Patch::Rect { lambda } => {
                let delta = self.skew.map_or(T::zero(), |s| s.delta_y(d));
                let cache = (delta <= T::zero()).then_some(&self.rect_cache[..]);
                rect::point(
                    &self.rule,
                    &self.profile,
                    lambda,
                    delta,
                    d,
                    cache,
                    self.sqrt,
                )
            }
            Patch::Disc => match self.skew {
                None => disc::symmetric_point(&self.rule, &self.profile, d),
                Some(law) => disc::skewed_point(&self.rule, &self.profile, law.peak(d), d),
            },
        };
        FlsPoint { d, f, m }
    }

    /// The characteristic pitch (Eq. 22): `m̃` at `d = 0`, where the skew law puts the peak
    /// at the centre, so the skew cannot change it.
    pub fn pitch(&self) -> T {
        self.point(T::zero()).m
    }
}

/// The closed-form pitch where one exists (docs/model.md's reference values): the disc for any
/// `k`, and the uniform rectangle. `None` otherwise.
pub fn closed_form_pitch(shape: Shape, k: f64) -> Option<f64> {
    match shape {
        Shape::Disc => {
            Some(crate::pressure::disc_moment(k, 2.0) / crate::pressure::disc_moment(k, 1.0))
        }
        Shape::Rect { aspect } if k.is_infinite() => {
            // (1/(4λ)) ∫∫ sqrt(x² + y²) over [-λ, λ] × [-1, 1].
            let l = aspect;
            let r = libm::hypot(l, 1.0);
            let quarter = (2.0 * l * r + libm::asinh(l) + l * l * l * libm::asinh(1.0 / l)) / 6.0;
            Some(quarter / l)
        }
        Shape::Rect { .. } => None,
    }
}
