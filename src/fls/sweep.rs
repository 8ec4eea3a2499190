//! The sweep of the centre of rotation over `[0, ∞)`, and the lookup table of one sweep
//! (`fls` on the host; the controller's start-up samples its surfaces from such sweeps, and
//! its tick reads only its own tables, `controller::capacity`).
//!
//! `d = L · t/(1 − t)` maps `t ∈ [0, 1]` onto `d ∈ [0, ∞]`, with `L` the patch's radius of
//! gyration in units of `a` (`sqrt((λ² + 1)/3)` for the rectangle, `sqrt(1/2)` for the disc):
//! the length on which the surface turns from torsion to translation. Near `t = 0`, `f̃`
//! grows linearly in `t`; near `t = 1`, `m̃ ~ 1/d` falls linearly in `1 − t`. Uniform steps in
//! `t` therefore spread the samples evenly along the curve at both ends, and no sample is
//! spent on the far field.

use crate::error::ConfigError;
use crate::fls::{FlsModel, FlsPoint, Shape};
use crate::real::Real;
use heapless::Vec;

/// The map `d = L · t/(1 − t)` between the sweep parameter and the centre of rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepMap<T> {
    scale: T,
}

impl<T: Real> SweepMap<T> {
    /// The map for a shape, with `L` its radius of gyration over `a`.
    pub fn for_shape(shape: Shape) -> Self {
        let scale = match shape {
            Shape::Rect { aspect } => libm::sqrt((aspect * aspect + 1.0) / 3.0),
            Shape::Disc => core::f64::consts::FRAC_1_SQRT_2,
        };
        Self {
            scale: T::of(scale),
        }
    }

    /// `L`.
    pub fn scale(&self) -> T {
        self.scale
    }

    /// `d` at `t` (`t ≥ 1` gives `+∞`, `t ≤ 0` gives 0).
    pub fn d_of(&self, t: T) -> T {
        if t >= T::one() {
            return T::infinity();
        }
        let t = t.max(T::zero());
        self.scale * t / (T::one() - t)
    }

    /// `t` at `d` (`d = ∞` gives 1).
    pub fn t_of(&self, d: T) -> T {
        if d.is_infinite() {
            return T::one();
        }
        let d = d.abs();
        d / (d + self.scale)
    }
}

/// A sweep of the limit surface stored for lookup: up to `CAP` points, ordered from
/// `(0, pitch)` at `d = 0` to `(1, 0)` at `d = ∞`, that is by decreasing angle in the
/// `(f̃, m̃)` plane.
///
/// Lookup joins neighbouring samples by chords. The exact surface is convex, so the chords
/// lie inside it: a query can only overstate the utilisation, never understate it. With 65
/// points the chords are within about 1e-4 of the curve for the paper's cases (the gap is
/// measured in `tests/fls_tables.rs`). Cost of a lookup: a binary search of `log2(CAP)`
/// steps, two cross products and one division.
#[derive(Debug, Clone)]
pub struct FlsTable<T, const CAP: usize> {
    points: Vec<FlsPoint<T>, CAP>,
    map: SweepMap<T>,
}

impl<T: Real, const CAP: usize> FlsTable<T, CAP> {
    /// Sweeps `model` at `samples` values of `t = i/samples`, `i = 0 … samples − 1`, and
    /// closes the table with the exact translation limit `(1, 0)` at `t = 1`: the table holds
    /// `samples + 1` points. Fails (parameter `samples`) unless `2 ≤ samples < CAP`.
    pub fn sweep(model: &FlsModel<T>, samples: usize) -> Result<Self, ConfigError> {
        let mut table = Self::empty(model.config().shape);
        table.resweep(model, samples)?;
        Ok(table)
    }

    /// A table with no points, to [`FlsTable::resweep`] into.
    pub(crate) fn empty(shape: Shape) -> Self {
        Self {
            points: Vec::new(),
            map: SweepMap::for_shape(shape),
        }
    }

    /// [`FlsTable::sweep`] in place, replacing the points (the start-up sweeps one table
    /// per aspect ratio into the same storage). On an error the table is left empty.
    pub(crate) fn resweep(
        &mut self,
        model: &FlsModel<T>,
        samples: usize,
    ) -> Result<(), ConfigError> {
        self.points.clear();
        if samples < 2 || samples >= CAP {
            return Err(ConfigError::Capacity {
                param: "samples",
                requested: samples,
                limit: if samples < 2 {
                    2
                } else {
                    CAP.saturating_sub(1)
                },
            });
        }
        self.map = SweepMap::for_shape(model.config().shape);
        for i in 0..samples {
            let t = T::of_usize(i) / T::of_usize(samples);
            let p = model.point(self.map.d_of(t));
            self.points.push(p).map_err(|_| capacity(samples, CAP))?;
        }
        let end = FlsPoint {
            d: T::infinity(),
            f: T::one(),
            m: T::zero(),
        };
        self.points.push(end).map_err(|_| capacity(samples, CAP))?;
        Ok(())
    }

    /// The stored points, from `d = 0` to `d = ∞`.
    pub fn points(&self) -> &[FlsPoint<T>] {
        &self.points
    }

    /// The sweep map the points were taken on.
    pub fn map(&self) -> SweepMap<T> {
        self.map
    }

    /// Whether every ray from the origin meets the swept curve once, i.e. the direction
    /// turns monotonically from the `m̃` axis to the `f̃` axis. [`FlsTable::utilisation`] is
    /// exact (up to the chords) only then. The symmetric profiles and the skewed rectangle
    /// always are; the skewed disc with a sideways locus is not near pure torsion.
    pub fn is_star_shaped(&self) -> bool {
        self.points.windows(2).all(|w| match w {
            [a, b] => a.f * b.m - a.m * b.f < T::zero(),
            _ => true,
        })
    }

    /// The pitch, `m̃` at `d = 0`.
    pub fn pitch(&self) -> T {
        self.points.first().map_or(T::zero(), |p| p.m)
    }

    /// How far the load `(f̃, m̃)` is along its ray to the surface: `< 1` holds, `≥ 1` slips.
    /// Signs are ignored (the surface is symmetric in both). `(0, 0)` gives 0; NaN gives NaN.
    pub fn utilisation(&self, f: T, m: T) -> T {
        let (f, m) = (f.abs(), m.abs());
        if f.is_nan() || m.is_nan() {
            return T::nan();
        }
        if f == T::zero() && m == T::zero() {
            return T::zero();
        }
        let cross = |p: &FlsPoint<T>| p.f * m - p.m * f;
        let pts = self.points.as_slice();
        let i = pts
            .partition_point(|p| cross(p) < T::zero())
            .clamp(1, pts.len().saturating_sub(1).max(1));
        let (Some(p0), Some(p1)) = (pts.get(i - 1), pts.get(i)) else {
            return T::infinity();
        };
        let (df, dm) = (p1.f - p0.f, p1.m - p0.m);
        let num = df * m - dm * f;
        let den = df * p0.m - dm * p0.f;
        if den == T::zero() {
            return T::infinity();
        }
        num / den
    }

    /// The surface's radius (distance from the origin) in the direction of `(f̃, m̃)`.
    pub fn radius(&self, f: T, m: T) -> T {
        let u = self.utilisation(f, m);
        f.libm_hypot(m) / u
    }
}

fn capacity(samples: usize, cap: usize) -> ConfigError {
    ConfigError::Capacity {
        param: "samples",
        requested: samples,
        limit: cap.saturating_sub(1),
    }
}
