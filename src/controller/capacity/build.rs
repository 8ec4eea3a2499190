//! Start-up: the grid of moment arms, table mode's surfaces and ellipse mode's inscribed
//! ellipse (see the parent module's docs for what they are and their accuracy).

use super::{at, Capacity, DIRECTIONS, MAX_ASPECTS, MAX_FORCE_NODES, MAX_TABLE_SAMPLES};
use crate::contact::ContactSize;
use crate::controller::config::{ControllerConfig, FingerShape, Mode};
use crate::error::{check, ConfigError};
use crate::fls::{FlsConfig, FlsModel, FlsTable, InscribedEllipse};
use crate::quadrature::QuadratureOrder;
use crate::real::{Real, SqrtFn};

impl<T: Real> Capacity<T> {
    /// Precomputes the grid for `cfg` (already validated by
    /// [`ControllerConfig::validate`]), computing in `P` and storing in `T`.
    pub fn build<P: Real>(cfg: &ControllerConfig) -> Result<Self, ConfigError> {
        let mut cap = Self::blank();
        cap.build_into::<P>(cfg, SqrtFn::LIBM)?;
        Ok(cap)
    }

    /// [`Capacity::build`] into `self`, in place (no copy of the grid on the stack: the
    /// device builds its controllers this way). On an error `self` is left half-built
    /// and must be built again before use. `sqrt` is the limit-surface kernels' square
    /// root (see [`SqrtFn`]).
    pub(crate) fn build_into<P: Real>(
        &mut self,
        cfg: &ControllerConfig,
        sqrt: SqrtFn<P>,
    ) -> Result<(), ConfigError> {
        let nodes = usize::from(cfg.force_nodes);
        if !(2..=MAX_FORCE_NODES).contains(&nodes) {
            return Err(ConfigError::Capacity {
                param: "force_nodes",
                requested: nodes,
                limit: if nodes < 2 { 2 } else { MAX_FORCE_NODES },
            });
        }
        let contact = ContactSize::<P>::new(cfg.c_m_per_n_gamma, cfg.gamma)?;
        let mut slot = None;
        let model = FlsModel::<P>::build_in(
            &mut slot,
            FlsConfig {
                shape: cfg.fls_shape(1.0),
                k: cfg.k,
                skew: cfg.skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
                order: QuadratureOrder::new(usize::from(cfg.quadrature_order))?,
            },
        )?;
        model.set_sqrt(sqrt);
        let varying = cfg.shape == FingerShape::Rect && cfg.gamma > 0.0;
        let aspect_of = |a: P| (P::of(cfg.half_length_m) / a).to_f64();
        let fixed_pitch = if varying {
            P::zero()
        } else {
            let a = contact.half_width_m(P::of(cfg.n_min_n));
            model.set_aspect(aspect_of(a))?;
            model.pitch()
        };

        self.clear();
        self.mode = cfg.mode;
        self.nodes = nodes;
        self.arm_linear_below = cfg.gamma > 0.0;
        self.fill_arms(cfg, model, &contact, varying, fixed_pitch)?;
        self.fill_inv_width();
        check_range(cfg, self)?;
        self.fill_surface(cfg, model, &contact, varying)?;
        self.check_stored(cfg)
    }

    /// The node forces `N_j` \[N\] (log-spaced from `N_min` to `N_max`, the ends exact)
    /// and the moment arms `R_j = a(N_j)·pitch` \[m\] with their inverses, computed in `P`.
    /// `fixed_pitch` is the pitch when the aspect does not vary with the force.
    fn fill_arms<P: Real>(
        &mut self,
        cfg: &ControllerConfig,
        model: &mut FlsModel<P>,
        contact: &ContactSize<P>,
        varying: bool,
        fixed_pitch: P,
    ) -> Result<(), ConfigError> {
        let nodes = self.nodes;
        let aspect_of = |a: P| (P::of(cfg.half_length_m) / a).to_f64();
        let ln_n_min = P::of(cfg.n_min_n).libm_ln();
        let ln_step = (P::of(cfg.n_max_n).libm_ln() - ln_n_min) / P::of_usize(nodes - 1);
        for j in 0..nodes {
            let n = if j + 1 == nodes {
                P::of(cfg.n_max_n)
            } else if j == 0 {
                P::of(cfg.n_min_n)
            } else {
                (ln_n_min + ln_step * P::of_usize(j)).libm_exp()
            };
            let a = contact.half_width_m(n);
            let pitch = if varying {
                model.set_aspect(aspect_of(a))?;
                model.pitch()
            } else {
                fixed_pitch
            };
            let arm = a * pitch;
            if let (Some(f), Some(r), Some(ir)) = (
                self.force_n.get_mut(j),
                self.arm_m.get_mut(j),
                self.inv_arm_per_m.get_mut(j),
            ) {
                *f = T::of(n.to_f64());
                *r = T::of(arm.to_f64());
                *ir = T::of(arm.recip().to_f64());
            }
        }
        Ok(())
    }

    /// The mode's surface: table mode's rows of inverse radii, or ellipse mode's demand
    /// scales `(1/A, 1/B)` from the inscribed ellipse.
    fn fill_surface<P: Real>(
        &mut self,
        cfg: &ControllerConfig,
        model: &mut FlsModel<P>,
        contact: &ContactSize<P>,
        varying: bool,
    ) -> Result<(), ConfigError> {
        match cfg.mode {
            Mode::Table => self.build_shapes(cfg, model, contact, varying)?,
            Mode::Ellipse => {
                let e = inscribed_ellipse(cfg, model, contact, varying)?;
                self.demand_scale = [
                    T::of(e.x_semi_axis.recip().to_f64()),
                    T::of(e.y_semi_axis.recip().to_f64()),
                ];
            }
        }
        Ok(())
    }

    /// The grid as stored in `T` must itself be valid (increasing finite forces, positive
    /// finite arms and radii): a configuration valid in f64 can round to zeros or
    /// infinities in f32.
    fn check_stored(&self, cfg: &ControllerConfig) -> Result<(), ConfigError> {
        if Self::check_tables(cfg, &self.tables()).is_err() {
            return Err(ConfigError::OutOfRange {
                param: "n_min_n",
                value: cfg.n_min_n,
                expected: "forces and contact sizes the tick's precision can represent",
            });
        }
        Ok(())
    }

    /// Table mode: each node's aspect position, and per aspect ratio a row of inverse L1
    /// radii at the [`DIRECTIONS`] load directions (then raised by `inflate_rows`).
    fn build_shapes<P: Real>(
        &mut self,
        cfg: &ControllerConfig,
        model: &mut FlsModel<P>,
        contact: &ContactSize<P>,
        varying: bool,
    ) -> Result<(), ConfigError> {
        let samples = usize::from(cfg.table_samples);
        let shapes = if varying {
            usize::from(cfg.aspect_count)
        } else {
            1
        };
        if !(2..=MAX_ASPECTS).contains(&shapes) && varying {
            return Err(ConfigError::Capacity {
                param: "aspect_count",
                requested: shapes,
                limit: if shapes < 2 { 2 } else { MAX_ASPECTS },
            });
        }
        if !(2..=MAX_TABLE_SAMPLES).contains(&samples) {
            return Err(ConfigError::Capacity {
                param: "table_samples",
                requested: samples,
                limit: if samples < 2 { 2 } else { MAX_TABLE_SAMPLES },
            });
        }
        self.shapes = shapes;
        let l = P::of(cfg.half_length_m);
        // Aspect ratios fall as the force rises: the first node has the largest.
        let ln_hi = (l / contact.half_width_m(P::of(cfg.n_min_n))).libm_ln();
        let ln_lo = (l / contact.half_width_m(P::of(cfg.n_max_n))).libm_ln();
        let ln_step = if shapes > 1 {
            (ln_hi - ln_lo) / P::of_usize(shapes - 1)
        } else {
            P::zero()
        };
        for j in 0..self.nodes {
            let pos = if shapes > 1 && ln_step > P::zero() {
                let n = P::of(at(&self.force_n, j).to_f64());
                ((l / contact.half_width_m(n)).libm_ln() - ln_lo) / ln_step
            } else {
                P::zero()
            };
            if let Some(p) = self.aspect_pos.get_mut(j) {
                *p = T::of(pos.to_f64());
            }
        }
        // One table, swept again for each aspect: the stack peak's lever in
        // docs/decisions/firmware-size-levers.md.
        let mut table = FlsTable::<P, { MAX_TABLE_SAMPLES + 1 }>::empty(model.config().shape);
        for e in 0..shapes {
            let aspect = if varying {
                (ln_lo + ln_step * P::of_usize(e)).libm_exp()
            } else {
                l / contact.half_width_m(P::of(cfg.n_min_n))
            };
            model.set_aspect(aspect.to_f64())?;
            table.resweep(model, samples)?;
            if !table.is_star_shaped() {
                let locus = cfg.skew.map_or(0.0, |s| s.locus_over_a);
                return Err(ConfigError::OutOfRange {
                    param: "locus",
                    value: locus,
                    expected: "a star-shaped surface for table mode (locus 0 on a skewed disc)",
                });
            }
            let pitch = table.pitch();
            if let Some(row) = self.inv_radius.get_mut(e) {
                for (i, w) in row.iter_mut().enumerate() {
                    let t = P::of_usize(i) / P::of_usize(DIRECTIONS - 1);
                    *w = T::of(table.utilisation(P::one() - t, t * pitch).to_f64());
                }
            }
        }
        self.inflate_rows(shapes);
        Ok(())
    }

    /// Makes the interpolation between aspect rows conservative. Along a row the chords
    /// already are (the polygon lies inside the convex surface), but the linear blend of
    /// two rows can fall below the surface in between by up to `h²·|w''|/8`. The rows'
    /// second differences estimate `h²·w''`; every row is raised by twice the largest such
    /// estimate over 8 (relative), plus 1 % of the largest first difference (the aspect
    /// position is blended linearly in `N` rather than `ln N` between force nodes) and
    /// four rounding units of `T`. With two rows (no second difference) the raise is half
    /// their largest relative difference. `tests/conservative.rs` checks the result against
    /// the exact surface; for the default finger the raise is about 1e-3.
    fn inflate_rows(&mut self, shapes: usize) {
        let rows = self.inv_radius.get(..shapes).unwrap_or(&[]);
        let (mut curve, mut slope) = (0.0f64, 0.0f64);
        for i in 0..DIRECTIONS {
            let w = |e: usize| rows.get(e).map_or(1.0, |r| at(r, i).to_f64());
            for e in 1..shapes {
                slope = slope.max((w(e) - w(e - 1)).abs() / w(e).min(w(e - 1)));
            }
            for e in 1..shapes.saturating_sub(1) {
                let d2 = w(e + 1) - 2.0 * w(e) + w(e - 1);
                curve = curve.max(d2.abs() / w(e));
            }
        }
        let raise = if shapes > 2 {
            curve / 4.0 + slope * 0.01
        } else {
            slope * 0.5
        } + 4.0 * T::epsilon().to_f64();
        let k = T::of(1.0 + raise);
        for row in self.inv_radius.iter_mut().take(shapes) {
            for w in row.iter_mut() {
                *w = *w * k;
            }
        }
    }
}

/// Centres of rotation per sweep for ellipse mode's inscribed ellipse.
pub const INSCRIBED_SAMPLES: usize = 32;

/// Ellipse mode's start-up fit: the ellipse inscribed in the exact surfaces (with the
/// configured skew) at the largest, the smallest and the middle (in `ln`) aspect ratio of
/// the force range, fitted at the largest (the exact surface lies furthest inside Eq. 10
/// for long patches) and shrunk into all three. Cost: three sweeps of
/// [`INSCRIBED_SAMPLES`] (one for the disc and `γ = 0`).
fn inscribed_ellipse<P: Real>(
    cfg: &ControllerConfig,
    model: &mut FlsModel<P>,
    contact: &ContactSize<P>,
    varying: bool,
) -> Result<InscribedEllipse<P>, ConfigError> {
    let l = P::of(cfg.half_length_m);
    let aspect = |n: f64| (l / contact.half_width_m(P::of(n))).to_f64();
    let (hi, lo) = (aspect(cfg.n_min_n), aspect(cfg.n_max_n));
    let mut sweep = |a: f64| -> Result<FlsTable<P, { INSCRIBED_SAMPLES + 1 }>, ConfigError> {
        model.set_aspect(a)?;
        FlsTable::sweep(model, INSCRIBED_SAMPLES)
    };
    let first = sweep(hi)?;
    let fitted = if varying {
        let mid = sweep(libm::sqrt(hi * lo))?;
        let last = sweep(lo)?;
        InscribedEllipse::fit_within(
            first.points(),
            &[first.points(), mid.points(), last.points()],
        )
    } else {
        InscribedEllipse::fit_within(first.points(), &[first.points()])
    };
    // The unit circle's scale is the fallback only if no ellipse fits the samples, which
    // the validated domain does not produce; refuse rather than under-ask.
    let e = fitted.ok_or(ConfigError::OutOfRange {
        param: "k",
        value: cfg.k,
        expected: "a limit surface an ellipse can be fitted into",
    })?;
    // Up to rounding: the surface crosses the axes at exactly 1.
    let inside = |x: P| x <= P::of(1.0 + 1e-6);
    if !(inside(e.x_semi_axis) && inside(e.y_semi_axis)) {
        return Err(ConfigError::OutOfRange {
            param: "k",
            value: cfg.k,
            expected: "a limit surface inside Eq. 10's ellipse",
        });
    }
    // Degraded sampling shrinks the fit (more force, safe); one too small asks infinite force
    // every tick, so it is refused (the fuzz finding of
    // `tests/controller.rs::an_aspect_the_start_up_cannot_sample_is_refused_by_name`).
    let plausible = |x: P| x >= P::of(INSCRIBED_SEMI_AXIS_MIN);
    if plausible(e.x_semi_axis) && plausible(e.y_semi_axis) {
        Ok(e)
    } else {
        Err(ConfigError::OutOfRange {
            param: "half_length_m",
            value: cfg.half_length_m,
            expected: "an aspect ratio l/a over [N_min, N_max] whose limit surface the start-up can sample (the fitted ellipse came out absurdly small)",
        })
    }
}

/// The least semi-axis of the inscribed ellipse the start-up accepts. Real limit surfaces
/// lie a few per cent inside Eq. 10's unit circle; a degraded sampling gives smaller fits
/// (wasteful but safe, up to a thousandfold force); below this the configuration is
/// refused.
pub const INSCRIBED_SEMI_AXIS_MIN: f64 = 1e-3;

/// Refuses sensor ranges whose worst demand would overflow `T` in the tick.
pub(crate) fn check_range<T: Real>(
    cfg: &ControllerConfig,
    cap: &Capacity<T>,
) -> Result<(), ConfigError> {
    let scale = cfg.safety / cfg.mu;
    let f = T::of(scale * cfg.force_range_n * core::f64::consts::SQRT_2);
    // The tick scales a round patch's moment once more (`DISC_TORSION_SAFETY_FACTOR`).
    let m = T::of(scale * cfg.torsion_factor() * cfg.moment_range_nm);
    let inv0 = at(&cap.inv_arm_per_m, 0);
    let n0 = at(&cap.force_n, 0);
    let y = m * inv0 * n0.max(T::one());
    let worst = f * f + y * y;
    let n_max = T::of(cfg.n_max_n);
    let ok = worst.is_finite() && (worst * T::of(16.0)).is_finite() && (n_max * n_max).is_finite();
    check(
        "force_range_n",
        cfg.force_range_n,
        ok,
        "a sensor range whose worst load does not overflow the tick's precision",
    )
}
