//! The grid as plain arrays: export, and import with every check an imported table needs.

use super::{at, Capacity, DIRECTIONS, MAX_ASPECTS, MAX_FORCE_NODES};
use crate::controller::config::{ControllerConfig, FingerShape, Mode};
use crate::real::Real;

/// The precomputed grid as plain arrays, for export ([`Capacity::tables`]) and for
/// building a controller without precomputation ([`Capacity::from_tables`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tables<'a, T> {
    /// Node forces `N_j` \[N\], increasing, from `N_min` to `N_max`.
    pub force_n: &'a [T],
    /// Moment arms `R_j = a(N_j)·pitch(l/a(N_j))` \[m\].
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

impl<T: Real> Capacity<T> {
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
        let mut cap = Self::blank();
        cap.fill_from_tables(cfg, t)?;
        Ok(cap)
    }

    /// [`Capacity::from_tables`] into `self`, in place (no copy of the grid on the stack:
    /// the device builds its controllers this way). On an error `self` is unchanged.
    pub(crate) fn fill_from_tables(
        &mut self,
        cfg: &ControllerConfig,
        t: &Tables<'_, T>,
    ) -> Result<(), TableError> {
        let shapes = Self::check_tables(cfg, t)?;
        self.clear();
        self.mode = cfg.mode;
        self.nodes = t.force_n.len();
        self.shapes = shapes.max(1);
        self.arm_linear_below = cfg.gamma > 0.0;
        self.demand_scale = t.demand_scale;
        for (dst, src) in [
            (&mut self.force_n, t.force_n),
            (&mut self.arm_m, t.arm_m),
            (&mut self.inv_arm_per_m, t.inv_arm_per_m),
            (&mut self.aspect_pos, t.aspect_pos),
        ] {
            for (d, s) in dst.iter_mut().zip(src) {
                *d = *s;
            }
        }
        for (d, s) in self.inv_radius.iter_mut().zip(t.inv_radius) {
            *d = *s;
        }
        self.fill_inv_width();
        Ok(())
    }

    /// The checks of [`Capacity::from_tables`], without building anything; returns the
    /// number of table-mode rows (0 in ellipse mode).
    pub(crate) fn check_tables(
        cfg: &ControllerConfig,
        t: &Tables<'_, T>,
    ) -> Result<usize, TableError> {
        let shapes = Self::check_sizes(cfg, t)?;
        Self::check_forces(cfg, t.force_n)?;
        Self::check_arms(t.arm_m, t.inv_arm_per_m)?;
        Self::check_aspect_pos(t.aspect_pos, shapes)?;
        Self::check_surface(cfg, t)?;
        Ok(shapes)
    }

    /// Every table's length against `cfg`'s node and aspect counts; returns the number of
    /// table-mode rows (0 in ellipse mode).
    fn check_sizes(cfg: &ControllerConfig, t: &Tables<'_, T>) -> Result<usize, TableError> {
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
        Ok(shapes)
    }

    /// The node forces \[N\]: finite, strictly increasing from above 0, and ending at
    /// `cfg`'s `N_min` and `N_max` (as `T`).
    fn check_forces(cfg: &ControllerConfig, force_n: &[T]) -> Result<(), TableError> {
        let mut prev = T::zero();
        for (i, &n) in force_n.iter().enumerate() {
            if !(n > prev && n.is_finite()) {
                return Err(TableError::Invalid {
                    what: "force_n",
                    index: i,
                });
            }
            prev = n;
        }
        if force_n.first() != Some(&T::of(cfg.n_min_n)) {
            return Err(TableError::Mismatch { param: "n_min_n" });
        }
        if force_n.last() != Some(&T::of(cfg.n_max_n)) {
            return Err(TableError::Mismatch { param: "n_max_n" });
        }
        Ok(())
    }

    /// The moment arms \[m\] and their stored inverses: positive, finite, each pair's
    /// product 1 (to f32 rounding), the arms not falling with the force.
    fn check_arms(arm_m: &[T], inv_arm_per_m: &[T]) -> Result<(), TableError> {
        for (what, v) in [("arm_m", arm_m), ("inv_arm_per_m", inv_arm_per_m)] {
            if let Some(i) = v.iter().position(|&x| !(x > T::zero() && x.is_finite())) {
                return Err(TableError::Invalid { what, index: i });
            }
        }
        // The arm and its stored inverse agree (to f32 rounding); the arm grows with the
        // force (a = c·N^γ, γ ≥ 0).
        let tol = T::of(1e-5);
        for (i, (&r, &ir)) in arm_m.iter().zip(inv_arm_per_m).enumerate() {
            if !((r * ir - T::one()).abs() <= tol) {
                return Err(TableError::Inconsistent {
                    check: "arm_m × inv_arm_per_m = 1",
                    index: i,
                });
            }
        }
        for (i, w) in arm_m.windows(2).enumerate() {
            if let [a, b] = w {
                if *b < *a * (T::one() - tol) {
                    return Err(TableError::Inconsistent {
                        check: "arm_m does not fall with the force",
                        index: i + 1,
                    });
                }
            }
        }
        Ok(())
    }

    /// The aspect positions: not rising with the force (the aspect l/a falls as the arm
    /// grows), and within `[0, shapes − 1]` up to rounding.
    fn check_aspect_pos(aspect_pos: &[T], shapes: usize) -> Result<(), TableError> {
        let tol = T::of(1e-5);
        for (i, w) in aspect_pos.windows(2).enumerate() {
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
        if let Some(i) = aspect_pos
            .iter()
            .position(|&x| !(x >= -slack && x <= last_pos))
        {
            return Err(TableError::Invalid {
                what: "aspect_pos",
                index: i,
            });
        }
        Ok(())
    }

    /// The surface: every inverse radius positive and finite, and the demand scales at
    /// least 1 (exactly 1 in table mode).
    fn check_surface(cfg: &ControllerConfig, t: &Tables<'_, T>) -> Result<(), TableError> {
        let bad = |what, index| Err(TableError::Invalid { what, index });
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
        Ok(())
    }

    pub(super) fn fill_inv_width(&mut self) {
        for j in 0..self.nodes.saturating_sub(1) {
            let width = at(&self.force_n, j + 1) - at(&self.force_n, j);
            if let Some(w) = self.inv_width_per_n.get_mut(j) {
                *w = width.recip();
            }
        }
    }
}
