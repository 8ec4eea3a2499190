//! What the contact can hold at each normal force: the start-up grid the tick searches.
//!
//! docs/model.md's rule asks, for a load `(f_t, m_n)` and safety factor `s`, for the least `N`
//! with the scaled load inside the limit surface of the contact at `N`. Write `F = s f_t/μ`
//! and `M = s m_n/μ`, and `R(N) = a(N) · pitch(l/a(N))`, the contact's *moment arm* [m].
//! In coordinates `(x, y) = (f̃, m̃/pitch) = (F/N, M/(N R))` the Eq. 10 ellipse is the
//! unit circle and the exact surfaces of all aspects are nearly so. The rule becomes
//!
//! - ellipse mode: `φ(N) = N² − F² − (M/R)² ≥ 0`;
//! - table mode: `φ(N) = N − (F + M/R) · w(t) ≥ 0`, with `t = y/(x + y)` the load's
//!   direction and `w(t)` the inverse L1 radius of the normalised surface there.
//!
//! Both `powf` (in `a = c·N^γ`) and the pitch (a quadrature) are paid here, once: the grid
//! holds `R` at `force_nodes` forces spaced evenly in `ln N`, and, for table mode, `w` at
//! [`DIRECTIONS`] directions on `aspect_count` aspect ratios. A tick then costs a binary
//! search over the nodes and a bracketed Illinois (modified regula falsi) iteration inside
//! one interval, with no elementary function but the square root.
//!
//! Accuracy and its sign:
//! - `R(N)` is concave in `N` (`a ∝ N^γ`, `γ ≤ ½`, and `a·pitch(l/a)` is concave in `a`),
//!   so the linear interpolation between nodes understates it and overstates the force:
//!   the error is conservative, at most `γ(1−γ)/8 · (Δ ln N)²` relative.
//! - `w` along a straight chord is linear in `t`, so the direction table is exactly the
//!   polygon through its samples, which lies inside the convex surface: conservative too.
//!   Between aspect ratios `w` is interpolated linearly in `ln(l/a)` (not guaranteed
//!   conservative; `tests/controller.rs` measures it against the exact surface).
//! - Outside `[N_min, N_max]` the arm is extended by conservative bounds: `R ∝ N` below
//!   (`R` constant for `γ = 0`) and `R = R(N_max)` above. The answers there are closed forms.

use crate::contact::ContactSize;
use crate::controller::config::{ControllerConfig, FingerShape, Mode};
use crate::controller::math::TickMath;
use crate::error::{check, ConfigError};
use crate::fls::{FlsConfig, FlsModel, FlsTable, InscribedEllipse};
use crate::quadrature::QuadratureOrder;
use crate::real::Real;

/// Most normal forces in the start-up grid.
pub const MAX_FORCE_NODES: usize = 64;
/// Most aspect ratios in table mode's grid.
pub const MAX_ASPECTS: usize = 12;
/// Directions `t = i/(DIRECTIONS − 1)` at which table mode stores each surface.
pub const DIRECTIONS: usize = 33;
/// Most centres of rotation in one start-up sweep (table mode).
pub const MAX_TABLE_SAMPLES: usize = 128;
/// Most iterations of the Illinois step in one solve. The tolerance (8 ulp of the answer)
/// is met in 3 to 4 on average and in at most 8 over the 140 000 loads of
/// `tests/controller.rs` (which fails above 12); the cap bounds the worst case.
pub const MAX_ILLINOIS_ITERATIONS: u8 = 16;
/// The largest utilisation a tick reports (a load on a contact with no normal force).
pub const UTILISATION_MAX: f64 = 1e6;

/// A solve's answer and its cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solution<T> {
    /// The least force that holds [N].
    pub force_n: T,
    /// Illinois iterations spent (0 when a node or a closed form answered).
    pub iterations: u8,
    /// The first grid node that holds the load (`force_nodes` when none does).
    pub node: usize,
}

/// The precomputed grid as plain arrays, for export ([`Capacity::tables`]) and for
/// building a controller without precomputation ([`Capacity::from_tables`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tables<'a, T> {
    /// Node forces `N_j` [N], increasing, from `N_min` to `N_max`.
    pub force_n: &'a [T],
    /// Moment arms `R_j = a(N_j)·pitch(l/a(N_j))` [m].
    pub arm_m: &'a [T],
    /// `1/R_j` [1/m], stored so that imported tables give bit-identical ticks.
    pub inv_arm_per_m: &'a [T],
    /// Fractional index of each node's aspect ratio in `inv_radius` (table mode).
    pub aspect_pos: &'a [T],
    /// Per aspect ratio, the inverse L1 radius of the normalised surface at the
    /// [`DIRECTIONS`] load directions (table mode; one row for the disc and `γ = 0`; empty
    /// in ellipse mode).
    pub inv_radius: &'a [[T; DIRECTIONS]],
    /// `(1/A, 1/B)`: what the force and moment demand are multiplied by before the test,
    /// with `A`, `B` the semi-axes of the ellipse inscribed in the exact surface (ellipse
    /// mode; `(1, 1)` in table mode).
    pub demand_scale: [T; 2],
}

/// Why imported tables were refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TableError {
    /// A table has the wrong length for the configuration (`what` names it).
    Size {
        /// The table.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length the configuration asks for.
        expected: usize,
    },
    /// A value is non-finite or out of its domain (`what` names the table).
    Invalid {
        /// The table.
        what: &'static str,
        /// The index of the first bad value.
        index: usize,
    },
    /// The tables contradict themselves (`check` names how: the moment arm and its stored
    /// inverse disagree, the arms fall with the force, the aspect positions rise with it).
    Inconsistent {
        /// The failed check.
        check: &'static str,
        /// The index where it fails.
        index: usize,
    },
    /// The node forces do not match the configuration's `N_min`/`N_max`.
    Mismatch {
        /// The configuration field that disagrees.
        param: &'static str,
    },
}

impl core::fmt::Display for TableError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            TableError::Size {
                what,
                len,
                expected,
            } => {
                write!(
                    f,
                    "tables: {what} has {len} entries, the configuration needs {expected}"
                )
            }
            TableError::Invalid { what, index } => {
                write!(f, "tables: {what}[{index}] is not a valid value")
            }
            TableError::Inconsistent { check, index } => {
                write!(f, "tables: {check} fails at index {index}")
            }
            TableError::Mismatch { param } => {
                write!(f, "tables: they were made for another {param}")
            }
        }
    }
}

impl core::error::Error for TableError {}

/// The precomputed grid. See the module docs.
#[derive(Debug, Clone)]
pub struct Capacity<T> {
    mode: Mode,
    nodes: usize,
    force_n: [T; MAX_FORCE_NODES],
    arm_m: [T; MAX_FORCE_NODES],
    inv_arm_per_m: [T; MAX_FORCE_NODES],
    inv_width_per_n: [T; MAX_FORCE_NODES],
    aspect_pos: [T; MAX_FORCE_NODES],
    shapes: usize,
    inv_radius: [[T; DIRECTIONS]; MAX_ASPECTS],
    arm_linear_below: bool,
    demand_scale: [T; 2],
}

#[inline(always)]
fn at<T: Copy + Default>(a: &[T], i: usize) -> T {
    a.get(i).copied().unwrap_or_default()
}

#[inline(always)]
fn lerp<T: Real>(a: T, b: T, w: T) -> T {
    a + (b - a) * w
}

/// Splits `x ∈ [0, last]` into an index in `[0, last − 1]` and a fraction (NaN reads as 0).
#[inline(always)]
fn split<T: Real>(x: T, last: usize) -> (usize, T) {
    if last == 0 {
        return (0, T::zero());
    }
    let x = x.max(T::zero()).min(T::of_usize(last));
    // `x ≥ 0`, so truncation is the floor (and compiles to one conversion, no libm call).
    let i = x.to_usize().unwrap_or(0).min(last - 1);
    (i, x - T::of_usize(i))
}

impl<T: Real> Capacity<T> {
    /// Precomputes the grid for `cfg` (already validated by
    /// [`ControllerConfig::validate`]), computing in `P` and storing in `T`.
    pub fn build<P: Real>(cfg: &ControllerConfig) -> Result<Self, ConfigError> {
        let nodes = usize::from(cfg.force_nodes);
        if !(2..=MAX_FORCE_NODES).contains(&nodes) {
            return Err(ConfigError::Capacity {
                param: "force_nodes",
                requested: nodes,
                limit: if nodes < 2 { 2 } else { MAX_FORCE_NODES },
            });
        }
        let contact = ContactSize::<P>::new(cfg.c_m_per_n_gamma, cfg.gamma)?;
        let model = FlsModel::<P>::new(FlsConfig {
            shape: cfg.fls_shape(1.0),
            k: cfg.k,
            skew: cfg.skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
            order: QuadratureOrder::new(usize::from(cfg.quadrature_order))?,
        })?;
        let varying = cfg.shape == FingerShape::Rect && cfg.gamma > 0.0;
        let aspect_of = |a: P| (P::of(cfg.half_length_m) / a).to_f64();
        let fixed_pitch = if varying {
            P::zero()
        } else {
            let a = contact.half_width_m(P::of(cfg.n_min_n));
            model.with_aspect(aspect_of(a))?.pitch()
        };

        let mut cap = Self {
            mode: cfg.mode,
            nodes,
            force_n: [T::zero(); MAX_FORCE_NODES],
            arm_m: [T::zero(); MAX_FORCE_NODES],
            inv_arm_per_m: [T::zero(); MAX_FORCE_NODES],
            inv_width_per_n: [T::zero(); MAX_FORCE_NODES],
            aspect_pos: [T::zero(); MAX_FORCE_NODES],
            shapes: 1,
            inv_radius: [[T::zero(); DIRECTIONS]; MAX_ASPECTS],
            arm_linear_below: cfg.gamma > 0.0,
            demand_scale: [T::one(); 2],
        };
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
                model.with_aspect(aspect_of(a))?.pitch()
            } else {
                fixed_pitch
            };
            let arm = a * pitch;
            if let (Some(f), Some(r), Some(ir)) = (
                cap.force_n.get_mut(j),
                cap.arm_m.get_mut(j),
                cap.inv_arm_per_m.get_mut(j),
            ) {
                *f = T::of(n.to_f64());
                *r = T::of(arm.to_f64());
                *ir = T::of(arm.recip().to_f64());
            }
        }
        cap.fill_inv_width();
        check_range(cfg, &cap)?;
        match cfg.mode {
            Mode::Table => cap.build_shapes(cfg, &model, &contact, varying)?,
            Mode::Ellipse => {
                let e = inscribed_ellipse(cfg, &model, &contact, varying)?;
                cap.demand_scale = [
                    T::of(e.x_semi_axis.recip().to_f64()),
                    T::of(e.y_semi_axis.recip().to_f64()),
                ];
            }
        }
        // The grid as stored in `T` must itself be valid (increasing finite forces,
        // positive finite arms and radii): a configuration valid in f64 can round to
        // zeros or infinities in f32.
        if Self::from_tables(cfg, &cap.tables()).is_err() {
            return Err(ConfigError::OutOfRange {
                param: "n_min_n",
                value: cfg.n_min_n,
                expected: "forces and contact sizes the tick's precision can represent",
            });
        }
        Ok(cap)
    }

    fn build_shapes<P: Real>(
        &mut self,
        cfg: &ControllerConfig,
        model: &FlsModel<P>,
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
        for e in 0..shapes {
            let entry = if varying {
                model.with_aspect((ln_lo + ln_step * P::of_usize(e)).libm_exp().to_f64())?
            } else {
                model.with_aspect((l / contact.half_width_m(P::of(cfg.n_min_n))).to_f64())?
            };
            let table = FlsTable::<P, { MAX_TABLE_SAMPLES + 1 }>::sweep(&entry, samples)?;
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

    /// The grid as plain arrays (see [`Tables`]).
    pub fn tables(&self) -> Tables<'_, T> {
        let n = self.nodes;
        let rows = if self.mode == Mode::Table {
            self.shapes
        } else {
            0
        };
        Tables {
            force_n: self.force_n.get(..n).unwrap_or(&[]),
            arm_m: self.arm_m.get(..n).unwrap_or(&[]),
            inv_arm_per_m: self.inv_arm_per_m.get(..n).unwrap_or(&[]),
            aspect_pos: self.aspect_pos.get(..n).unwrap_or(&[]),
            inv_radius: self.inv_radius.get(..rows).unwrap_or(&[]),
            demand_scale: self.demand_scale,
        }
    }

    /// A grid from exported tables, for `cfg` (already validated by
    /// [`ControllerConfig::validate`]): no precomputation. Checks every length against the
    /// configuration, every value's domain, and that the first and last node forces are
    /// the configuration's `N_min` and `N_max` (as `T`). The result ticks bit for bit like
    /// the grid the tables were exported from.
    pub fn from_tables(cfg: &ControllerConfig, t: &Tables<'_, T>) -> Result<Self, TableError> {
        let nodes = usize::from(cfg.force_nodes);
        let size = |what, len: usize, expected: usize| {
            if len == expected {
                Ok(())
            } else {
                Err(TableError::Size {
                    what,
                    len,
                    expected,
                })
            }
        };
        if !(2..=MAX_FORCE_NODES).contains(&nodes) {
            return Err(TableError::Size {
                what: "force_n",
                len: t.force_n.len(),
                expected: nodes,
            });
        }
        size("force_n", t.force_n.len(), nodes)?;
        size("arm_m", t.arm_m.len(), nodes)?;
        size("inv_arm_per_m", t.inv_arm_per_m.len(), nodes)?;
        size("aspect_pos", t.aspect_pos.len(), nodes)?;
        let varying = cfg.shape == FingerShape::Rect && cfg.gamma > 0.0;
        let shapes = match cfg.mode {
            Mode::Ellipse => 0,
            Mode::Table if varying => usize::from(cfg.aspect_count),
            Mode::Table => 1,
        };
        if shapes > MAX_ASPECTS {
            return Err(TableError::Size {
                what: "inv_radius",
                len: t.inv_radius.len(),
                expected: shapes,
            });
        }
        size("inv_radius", t.inv_radius.len(), shapes)?;
        let bad = |what, index| Err(TableError::Invalid { what, index });
        let mut prev = T::zero();
        for (i, &n) in t.force_n.iter().enumerate() {
            if !(n > prev && n.is_finite()) {
                return bad("force_n", i);
            }
            prev = n;
        }
        if t.force_n.first() != Some(&T::of(cfg.n_min_n)) {
            return Err(TableError::Mismatch { param: "n_min_n" });
        }
        if t.force_n.last() != Some(&T::of(cfg.n_max_n)) {
            return Err(TableError::Mismatch { param: "n_max_n" });
        }
        for (what, v) in [("arm_m", t.arm_m), ("inv_arm_per_m", t.inv_arm_per_m)] {
            if let Some(i) = v.iter().position(|&x| !(x > T::zero() && x.is_finite())) {
                return bad(what, i);
            }
        }
        // The arm and its stored inverse agree (to f32 rounding); the arm grows with the
        // force (a = c·N^γ, γ ≥ 0) and the aspect l/a, hence its position, falls.
        let tol = T::of(1e-5);
        for (i, (&r, &ir)) in t.arm_m.iter().zip(t.inv_arm_per_m).enumerate() {
            if !((r * ir - T::one()).abs() <= tol) {
                return Err(TableError::Inconsistent {
                    check: "arm_m × inv_arm_per_m = 1",
                    index: i,
                });
            }
        }
        for (i, w) in t.arm_m.windows(2).enumerate() {
            if let [a, b] = w {
                if *b < *a * (T::one() - tol) {
                    return Err(TableError::Inconsistent {
                        check: "arm_m does not fall with the force",
                        index: i + 1,
                    });
                }
            }
        }
        for (i, w) in t.aspect_pos.windows(2).enumerate() {
            if let [a, b] = w {
                if *b > *a + tol {
                    return Err(TableError::Inconsistent {
                        check: "aspect_pos does not rise with the force",
                        index: i + 1,
                    });
                }
            }
        }
        // Positions computed in f64 and rounded may overshoot the ends by an ulp; the
        // lookup clamps them.
        let slack = T::of(1e-3);
        let last_pos = T::of_usize(shapes.saturating_sub(1)) + slack;
        if let Some(i) = t
            .aspect_pos
            .iter()
            .position(|&x| !(x >= -slack && x <= last_pos))
        {
            return bad("aspect_pos", i);
        }
        for (r, row) in t.inv_radius.iter().enumerate() {
            if row.iter().any(|&x| !(x > T::zero() && x.is_finite())) {
                return bad("inv_radius", r);
            }
        }
        // The inscribed ellipse's semi-axes are at most those of Eq. 10's unit circle (the
        // surface crosses the axes at (1, 0) and (0, 1)): scales below 1 (up to rounding)
        // would ask for less than the exact surface needs. Table mode applies none.
        let scale_ok = |x: T| x >= T::of(1.0 - 1e-6) && x.is_finite();
        let unit = cfg.mode == Mode::Table;
        if let Some(i) = t
            .demand_scale
            .iter()
            .position(|&x| !scale_ok(x) || (unit && x != T::one()))
        {
            return bad("demand_scale", i);
        }
        let mut cap = Self {
            mode: cfg.mode,
            nodes,
            force_n: [T::zero(); MAX_FORCE_NODES],
            arm_m: [T::zero(); MAX_FORCE_NODES],
            inv_arm_per_m: [T::zero(); MAX_FORCE_NODES],
            inv_width_per_n: [T::zero(); MAX_FORCE_NODES],
            aspect_pos: [T::zero(); MAX_FORCE_NODES],
            shapes: shapes.max(1),
            inv_radius: [[T::zero(); DIRECTIONS]; MAX_ASPECTS],
            arm_linear_below: cfg.gamma > 0.0,
            demand_scale: t.demand_scale,
        };
        for (dst, src) in [
            (&mut cap.force_n, t.force_n),
            (&mut cap.arm_m, t.arm_m),
            (&mut cap.inv_arm_per_m, t.inv_arm_per_m),
            (&mut cap.aspect_pos, t.aspect_pos),
        ] {
            for (d, s) in dst.iter_mut().zip(src) {
                *d = *s;
            }
        }
        for (d, s) in cap.inv_radius.iter_mut().zip(t.inv_radius) {
            *d = *s;
        }
        cap.fill_inv_width();
        Ok(cap)
    }

    fn fill_inv_width(&mut self) {
        for j in 0..self.nodes.saturating_sub(1) {
            let width = at(&self.force_n, j + 1) - at(&self.force_n, j);
            if let Some(w) = self.inv_width_per_n.get_mut(j) {
                *w = width.recip();
            }
        }
    }

    /// The mode the grid serves.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The node forces [N], from `N_min` to `N_max`.
    pub fn forces_n(&self) -> &[T] {
        self.force_n.get(..self.nodes).unwrap_or(&[])
    }

    /// The moment arms `a·pitch` [m] at the node forces.
    pub fn arms_m(&self) -> &[T] {
        self.arm_m.get(..self.nodes).unwrap_or(&[])
    }

    /// The inverse L1 radius of the normalised surface in direction `t ∈ [0, 1]` at the
    /// fractional aspect index `pos`.
    #[inline]
    fn inv_radius(&self, t: T, pos: T) -> T {
        let (i, wi) = split(t * T::of_usize(DIRECTIONS - 1), DIRECTIONS - 1);
        let row = |e: usize| {
            self.inv_radius
                .get(e)
                .map_or(T::one(), |r| lerp(at(r, i), at(r, i + 1), wi))
        };
        let (e, we) = split(pos, self.shapes - 1);
        if self.shapes == 1 {
            row(0)
        } else {
            lerp(row(e), row(e + 1), we)
        }
    }

    /// The table-mode demand `(F + M/R)·w(t)` for `y = M/R`.
    #[inline]
    fn table_demand(&self, f: T, y: T, pos: T) -> T {
        let s = f + y;
        if s == T::zero() {
            return T::zero();
        }
        s * self.inv_radius(y / s, pos)
    }

    /// `φ(N)` multiplied by `R²` (ellipse) or `R` (table), which keeps its sign and
    /// spares the divisions: ellipse `R²(N² − F²) − M²`, table `N R − (F R + M)·w(t)` with
    /// `t = M/(F R + M)`.
    #[inline]
    fn phi(&self, f: T, m: T, n: T, arm: T, pos: T) -> T {
        match self.mode {
            Mode::Ellipse => arm * arm * (n * n - f * f) - m * m,
            Mode::Table => {
                let s = f * arm + m;
                if s == T::zero() {
                    return n * arm;
                }
                n * arm - s * self.inv_radius(m / s, pos)
            }
        }
    }

    #[inline]
    fn phi_node(&self, f: T, m: T, j: usize) -> T {
        self.phi(
            f,
            m,
            at(&self.force_n, j),
            at(&self.arm_m, j),
            at(&self.aspect_pos, j),
        )
    }

    /// `R` and the aspect position at the force `n` inside interval `j` (nodes `j`,
    /// `j + 1`).
    #[inline]
    fn interpolate(&self, j: usize, n: T) -> (T, T) {
        let w = (n - at(&self.force_n, j)) * at(&self.inv_width_per_n, j);
        let arm = lerp(at(&self.arm_m, j), at(&self.arm_m, j + 1), w);
        let pos = lerp(at(&self.aspect_pos, j), at(&self.aspect_pos, j + 1), w);
        (arm, pos)
    }

    /// The least normal force [N] at which the (already scaled) demand `f = F`, `m = M`
    /// holds: `N_req`. Inputs must be finite and non-negative (the tick guarantees it).
    /// Cost: `log2(force_nodes)` node tests, then at most [`MAX_ILLINOIS_ITERATIONS`].
    pub fn required_force<M: TickMath<T>>(&self, f: T, m: T) -> Solution<T> {
        let (f, m) = self.scaled(f, m);
        self.solve_from::<M>(f, m, 0, None)
    }

    /// The demand as the test sees it: times [`Tables::demand_scale`] (ellipse mode's
    /// inscribed ellipse; exact identity in table mode).
    #[inline(always)]
    fn scaled(&self, f: T, m: T) -> (T, T) {
        let [sf, sm] = self.demand_scale;
        (f * sf, m * sm)
    }

    /// `(1/A, 1/B)`, see [`Tables::demand_scale`].
    pub fn demand_scale(&self) -> [T; 2] {
        self.demand_scale
    }

    /// [`Capacity::required_force`], trying first the grid interval of a previous answer
    /// (`hint`, its [`Solution::node`]): in a control loop the load moves little from one
    /// tick to the next, and two node tests then replace the binary search. Same answer
    /// for any hint.
    pub fn required_force_near<M: TickMath<T>>(&self, f: T, m: T, hint: usize) -> Solution<T> {
        let (f, m) = self.scaled(f, m);
        self.solve_from::<M>(f, m, 0, Some(hint))
    }

    /// `N_req` for `s` times a load whose `N_slip` solution is `slip`, `s ≥ 1`. No node
    /// below `N_slip` can hold the larger load, so the node search starts at `slip`'s node
    /// and walks up (docs/model.md: `N_req(s) ≤ s·N_slip`, a few nodes at most). Same answer
    /// as [`Capacity::required_force`] on the scaled load, at about half the cost.
    pub fn required_force_scaled<M: TickMath<T>>(
        &self,
        f: T,
        m: T,
        slip: &Solution<T>,
        s: T,
    ) -> Solution<T> {
        let from = if s >= T::one() { slip.node } else { 0 };
        let (f, m) = self.scaled(f, m);
        self.solve_from::<M>(f * s, m * s, from, None)
    }

    fn solve_from<M: TickMath<T>>(
        &self,
        f: T,
        m: T,
        from: usize,
        hint: Option<usize>,
    ) -> Solution<T> {
        let done = |force_n, node| Solution {
            force_n,
            iterations: 0,
            node,
        };
        if f == T::zero() && m == T::zero() {
            return done(T::zero(), 0);
        }
        // The first node at or after `from` that holds (φ is monotone in N): the hint and
        // its neighbour, a short walk, then a binary search. Invariant: no node below `lo`
        // holds; `hi` holds or is `nodes`.
        let (mut lo, mut hi) = (from.min(self.nodes), self.nodes);
        if let Some(h) = hint.filter(|&h| h > lo && h < self.nodes) {
            if self.phi_node(f, m, h) >= T::zero() {
                hi = h;
                if self.phi_node(f, m, h - 1) < T::zero() {
                    lo = h;
                } else {
                    hi = h - 1;
                }
            } else {
                lo = h + 1;
            }
        }
        for _ in 0..3 {
            if lo < hi && self.phi_node(f, m, lo) < T::zero() {
                lo += 1;
            } else {
                hi = lo;
            }
        }
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if self.phi_node(f, m, mid) >= T::zero() {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        if lo == 0 {
            return done(self.below_grid::<M>(f, m), 0);
        }
        if lo >= self.nodes {
            return done(self.above_grid::<M>(f, m), self.nodes);
        }
        let mut sol = self.illinois_in(f, m, lo - 1);
        sol.node = lo;
        sol
    }

    fn illinois_in(&self, f: T, m: T, j: usize) -> Solution<T> {
        let (a, b) = (at(&self.force_n, j), at(&self.force_n, j + 1));
        let (fa, fb) = (self.phi_node(f, m, j), self.phi_node(f, m, j + 1));
        Self::illinois((a, fa), (b, fb), |c| {
            let (arm, pos) = self.interpolate(j, c);
            self.phi(f, m, c, arm, pos)
        })
    }

    /// Illinois (modified regula falsi) on `[a, b]` with `φ(a) < 0 ≤ φ(b)`: the bracket is
    /// kept at every step (a step that would leave it bisects instead), and the upper end,
    /// where the load holds, is returned once the bracket is within 8 ulp or after
    /// [`MAX_ILLINOIS_ITERATIONS`].
    fn illinois(
        (mut a, mut fa): (T, T),
        (mut b, mut fb): (T, T),
        phi: impl Fn(T) -> T,
    ) -> Solution<T> {
        let tol = T::epsilon() * T::of(8.0);
        let mut side = 0i8;
        let mut iterations = 0u8;
        while iterations < MAX_ILLINOIS_ITERATIONS {
            if fb == T::zero() || b - a <= tol * b {
                break;
            }
            iterations += 1;
            // The secant point, kept at least half the tolerance inside the bracket: a
            // root within an ulp of one end is then settled by the next test instead of
            // by halving the bracket bit by bit.
            let step = tol * b * T::of(0.5);
            let mut c = (b - fb * (b - a) / (fb - fa)).max(a + step).min(b - step);
            if !(c > a && c < b) {
                c = a + (b - a) * T::of(0.5);
            }
            let fc = phi(c);
            if fc >= T::zero() {
                b = c;
                fb = fc;
                if side == 1 {
                    fa = fa * T::of(0.5);
                }
                side = 1;
            } else {
                a = c;
                fa = fc;
                if side == -1 {
                    fb = fb * T::of(0.5);
                }
                side = -1;
            }
        }
        Solution {
            force_n: b,
            iterations,
            node: 0,
        }
    }

    /// Below `N_min`: `R = R₀ (N/N₀)^β`, `β = 1` for `γ > 0` (a lower bound of the concave
    /// arm), `β = 0` for `γ = 0` (exact). Closed forms; the answer is at most `N₀`.
    fn below_grid<M: TickMath<T>>(&self, f: T, m: T) -> T {
        let n0 = at(&self.force_n, 0);
        let inv0 = at(&self.inv_arm_per_m, 0);
        let pos0 = at(&self.aspect_pos, 0);
        let two = T::of(2.0);
        let n = match (self.mode, self.arm_linear_below) {
            (Mode::Ellipse, false) => {
                let y = m * inv0;
                M::sqrt(f * f + y * y)
            }
            (Mode::Ellipse, true) => {
                let q = m * n0 * inv0;
                let h = f * f / two;
                M::sqrt(h + M::sqrt(h * h + q * q))
            }
            (Mode::Table, false) => self.table_demand(f, m * inv0, pos0),
            (Mode::Table, true) => {
                let y0 = m * inv0;
                let w0 = self.inv_radius(y0 / (f + y0), pos0);
                let b = f * w0;
                let c = m * n0 * inv0 * w0;
                (b + M::sqrt(b * b + two * two * c)) / two
            }
        };
        n.min(n0)
    }

    /// Above `N_max`: `R = R(N_max)` (a lower bound of the increasing arm). Closed form;
    /// the answer is at least `N_max`.
    fn above_grid<M: TickMath<T>>(&self, f: T, m: T) -> T {
        let last = self.nodes - 1;
        let y = m * at(&self.inv_arm_per_m, last);
        let n = match self.mode {
            Mode::Ellipse => M::sqrt(f * f + y * y),
            Mode::Table => self.table_demand(f, y, at(&self.aspect_pos, last)),
        };
        n.max(at(&self.force_n, last))
    }

    /// `R` and the aspect position at any force `n > 0`.
    fn arm_at(&self, n: T) -> (T, T) {
        let last = self.nodes - 1;
        let n0 = at(&self.force_n, 0);
        if n <= n0 {
            let arm0 = at(&self.arm_m, 0);
            let arm = if self.arm_linear_below {
                arm0 * n / n0
            } else {
                arm0
            };
            return (arm, at(&self.aspect_pos, 0));
        }
        if n >= at(&self.force_n, last) {
            return (at(&self.arm_m, last), at(&self.aspect_pos, last));
        }
        let j = self
            .forces_n()
            .partition_point(|&x| x <= n)
            .saturating_sub(1)
            .min(last - 1);
        self.interpolate(j, n)
    }

    /// How far the demand `(f, m)` (unscaled: `|f_t|/μ`, `|m_n|/μ`) is along its ray to the
    /// limit surface of the contact at the normal force `n`: `< 1` holds, `≥ 1` slips.
    /// Capped at [`UTILISATION_MAX`]; a load on `n ≤ 0` gets the cap, no load gets 0.
    pub fn utilisation<M: TickMath<T>>(&self, f: T, m: T, n: T) -> T {
        let cap = T::of(UTILISATION_MAX);
        if f == T::zero() && m == T::zero() {
            return T::zero();
        }
        if !(n > T::zero()) {
            return cap;
        }
        let (f, m) = self.scaled(f, m);
        let (arm, pos) = self.arm_at(n);
        let fr = f * arm;
        // The demand times R: ellipse |(F R, M)|, table (F R + M)·w(t).
        let demand = match self.mode {
            Mode::Ellipse => M::sqrt(fr * fr + m * m),
            Mode::Table => {
                let s = fr + m;
                s * self.inv_radius(m / s, pos)
            }
        };
        let u = demand / (arm * n);
        if u.is_nan() {
            cap
        } else {
            u.min(cap)
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
    model: &FlsModel<P>,
    contact: &ContactSize<P>,
    varying: bool,
) -> Result<InscribedEllipse<P>, ConfigError> {
    let l = P::of(cfg.half_length_m);
    let aspect = |n: f64| (l / contact.half_width_m(P::of(n))).to_f64();
    let (hi, lo) = (aspect(cfg.n_min_n), aspect(cfg.n_max_n));
    let sweep = |a: f64| -> Result<FlsTable<P, { INSCRIBED_SAMPLES + 1 }>, ConfigError> {
        FlsTable::sweep(&model.with_aspect(a)?, INSCRIBED_SAMPLES)
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
    let unit = |x: P| x > P::zero() && x <= P::of(1.0 + 1e-6);
    if unit(e.x_semi_axis) && unit(e.y_semi_axis) {
        Ok(e)
    } else {
        Err(ConfigError::OutOfRange {
            param: "k",
            value: cfg.k,
            expected: "a limit surface inside Eq. 10's ellipse",
        })
    }
}

/// Refuses sensor ranges whose worst demand would overflow `T` in the tick.
pub(crate) fn check_range<T: Real>(
    cfg: &ControllerConfig,
    cap: &Capacity<T>,
) -> Result<(), ConfigError> {
    let scale = cfg.safety / cfg.mu;
    let f = T::of(scale * cfg.force_range_n * core::f64::consts::SQRT_2);
    let m = T::of(scale * cfg.moment_range_nm);
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
