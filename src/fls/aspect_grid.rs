//! Limit surfaces of the rectangle over a range of aspect ratios `l/a`.
//!
//! On a hemicylinder the contact half-width `a = c·N^γ` grows with the normal force while the
//! half-length `l` stays fixed, so the shape of the limit surface changes with the load. The
//! grid holds the pitch and a sweep table at `A` aspect ratios spaced evenly in `ln(l/a)`; a
//! lookup interpolates in `ln(l/a)` between the two neighbours (and clamps outside the
//! range). For the disc every entry is the same surface. (The controller does not use this
//! grid: its start-up builds its own tables, `controller::capacity`.)

use crate::error::{check, ConfigError};
use crate::fls::{FlsModel, FlsTable};
use crate::real::Real;
use heapless::Vec;

/// One grid entry: aspect, pitch and table.
#[derive(Debug, Clone)]
pub struct AspectEntry<T, const S: usize> {
    /// `l/a`.
    pub aspect: T,
    /// The pitch at this aspect.
    pub pitch: T,
    /// The sweep at this aspect.
    pub table: FlsTable<T, S>,
}

/// Pitches and tables on `A` aspect ratios, `S` table capacity each.
#[derive(Debug, Clone)]
pub struct AspectGrid<T, const A: usize, const S: usize> {
    entries: Vec<AspectEntry<T, S>, A>,
    ln_min: T,
    ln_step: T,
}

/// Where an aspect falls in the grid: the lower entry and the weight of the upper one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPosition<T> {
    /// Index of the lower neighbour.
    pub index: usize,
    /// Weight of the upper neighbour, in `[0, 1]`.
    pub weight: T,
}

impl<T: Real, const A: usize, const S: usize> AspectGrid<T, A, S> {
    /// Builds `count` entries spaced evenly in `ln(l/a)` over `[aspect_min, aspect_max]`
    /// (parameters `aspect_min`, `aspect_max`, `aspect_count`), each with a sweep of
    /// `samples` points. `count = 1` needs `aspect_min = aspect_max`.
    pub fn build(
        model: &FlsModel<T>,
        aspect_min: f64,
        aspect_max: f64,
        count: usize,
        samples: usize,
    ) -> Result<Self, ConfigError> {
        check(
            "aspect_min",
            aspect_min,
            aspect_min > 0.0 && aspect_min.is_finite(),
            "aspect_min > 0",
        )?;
        check(
            "aspect_max",
            aspect_max,
            aspect_max >= aspect_min && aspect_max.is_finite(),
            "aspect_max >= aspect_min",
        )?;
        if count == 0 || count > A || (count == 1 && aspect_max > aspect_min) {
            return Err(ConfigError::Capacity {
                param: "aspect_count",
                requested: count,
                limit: if count == 0 { 1 } else { A },
            });
        }
        let ln_min = libm::log(aspect_min);
        let ln_step = if count > 1 {
            (libm::log(aspect_max) - ln_min) / (count - 1) as f64
        } else {
            0.0
        };
        let mut entries = Vec::new();
        for i in 0..count {
            let aspect = libm::exp(ln_min + ln_step * i as f64);
            let m = model.with_aspect(aspect)?;
            let table = FlsTable::sweep(&m, samples)?;
            let entry = AspectEntry {
                aspect: T::of(aspect),
                pitch: table.pitch(),
                table,
            };
            if entries.push(entry).is_err() {
                return Err(ConfigError::Capacity {
                    param: "aspect_count",
                    requested: count,
                    limit: A,
                });
            }
        }
        Ok(Self {
            entries,
            ln_min: T::of(ln_min),
            ln_step: T::of(ln_step),
        })
    }

    /// The entries, by increasing aspect.
    pub fn entries(&self) -> &[AspectEntry<T, S>] {
        &self.entries
    }

    /// Where `aspect` falls (clamped into the grid; NaN reads as the lowest entry).
    pub fn position(&self, aspect: T) -> GridPosition<T> {
        let last = self.entries.len().saturating_sub(1);
        if last == 0 || !(self.ln_step > T::zero()) {
            return GridPosition {
                index: 0,
                weight: T::zero(),
            };
        }
        let x = (aspect.libm_ln() - self.ln_min) / self.ln_step;
        if !(x > T::zero()) {
            return GridPosition {
                index: 0,
                weight: T::zero(),
            };
        }
        let top = T::of_usize(last);
        if x >= top {
            return GridPosition {
                index: last - 1,
                weight: T::one(),
            };
        }
        let floor = x.floor();
        let index = floor.to_usize().unwrap_or(0).min(last - 1);
        GridPosition {
            index,
            weight: x - floor,
        }
    }

    /// The pitch at `aspect`, interpolated linearly in `ln(pitch)` against `ln(l/a)` (a
    /// local power law: the pitch grows like `l/a` on long patches and tends to a constant
    /// on short ones). Cost: one `ln`, one `exp`.
    pub fn pitch(&self, aspect: T) -> T {
        self.pitch_at(self.position(aspect))
    }

    fn pitch_at(&self, pos: GridPosition<T>) -> T {
        let lo = self.entries.get(pos.index).map_or(T::zero(), |e| e.pitch);
        let hi = self.entries.get(pos.index + 1).map_or(lo, |e| e.pitch);
        if pos.weight == T::zero() || !(lo > T::zero() && hi > T::zero()) {
            return lo;
        }
        if pos.weight == T::one() {
            return hi;
        }
        (lo.libm_ln() + (hi.libm_ln() - lo.libm_ln()) * pos.weight).libm_exp()
    }

    /// Utilisation of the load `(f̃, m̃)` at `aspect`.
    ///
    /// The neighbouring surfaces are compared in coordinates `(f̃, m̃/pitch)`, where their
    /// shapes differ far less than in `(f̃, m̃)` (the moment scale grows like `l/a`): the
    /// radius along the load's ray is interpolated linearly in `ln(l/a)` there, and the
    /// moment axis is scaled by the interpolated pitch. Cost: two table lookups, one `ln`.
    pub fn utilisation(&self, aspect: T, f: T, m: T) -> T {
        let pos = self.position(aspect);
        let Some(lo) = self.entries.get(pos.index) else {
            return T::infinity();
        };
        let Some(hi) = self.entries.get(pos.index + 1) else {
            return lo.table.utilisation(f, m);
        };
        let w = pos.weight;
        let pitch = self.pitch_at(pos);
        if !(pitch > T::zero()) {
            return T::infinity();
        }
        let u_lo = lo.table.utilisation(f, m * (lo.pitch / pitch));
        let u_hi = hi.table.utilisation(f, m * (hi.pitch / pitch));
        if u_lo == T::zero() || u_hi == T::zero() {
            return T::zero();
        }
        // r = (1−w) r_lo + w r_hi with r_i = |q|/u_i.
        ((T::one() - w) / u_lo + w / u_hi).recip()
    }
}
