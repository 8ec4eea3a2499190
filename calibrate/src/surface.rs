//! The exact limit surface tabulated once over the parameters the fit moves: `κ = 1/k`
//! (0 is uniform pressure, 1 is `k = 1`), the aspect `l/a` (the rectangle; the disc has one
//! surface) and, for the rectangle, the skew's `Δ/a` at a fixed `α` (the locus changes
//! nothing on the rectangle, docs/model.md), with nodes evenly in `(Δ/a)²`, in which the
//! surface moves about linearly (by 1.8 % at most at `Δ/a = 0.9`, `k = 2`, `l = a`:
//! docs/decisions/calibration-fit.md).
//!
//! Each node holds the core's sweep ([`FlsTable`], [`SAMPLES`] centres of rotation: chords
//! within about 6e-5 of the surface). A lookup interpolates multilinearly between the
//! neighbouring nodes the way the core's `AspectGrid` does between aspects: the pitch in
//! `ln(pitch)`, the radius along the load's ray in coordinates `(f̃, m̃/pitch)`. Accuracy
//! against the exact surface: about 1e-4 relative (the fit's data have percent noise).
//! Cost: building is one sweep per node, `KAPPAS × aspects × skews × (SAMPLES + 1)`
//! quadratures (the skew axis multiplies them by [`SKEWS`]); a lookup is at most 8 table
//! lookups.

use crate::error::CalibError;
use softgrip::controller::FingerShape;
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};

/// Centres of rotation per sweep.
pub const SAMPLES: usize = 128;
/// Nodes in `κ = 1/k`, evenly spaced over `[0, 1]`.
pub const KAPPAS: usize = 17;
/// Skews `Δ/a` tabulated for the rectangle: evenly spaced over `[0, MAX_SKEW]`.
pub const SKEWS: usize = 5;
/// The largest skew tabulated (the paper's value).
pub const MAX_SKEW: f64 = 0.9;
/// The skew's rate `α` the tables are built with (the paper's).
pub const SKEW_ALPHA: f64 = 1.1;

type Table = FlsTable<f64, { SAMPLES + 1 }>;

/// The tabulated surfaces of one finger shape and half-length.
#[derive(Debug, Clone)]
pub struct SurfaceGrid {
    shape: FingerShape,
    ln_aspects: Vec<f64>,
    skews: Vec<f64>,
    /// Indexed `[skew][kappa][aspect]`.
    nodes: Vec<(f64, Table)>,
}

/// One axis's bracketing nodes and the upper one's weight.
#[derive(Clone, Copy)]
struct Bracket {
    lo: usize,
    w: f64,
}

fn bracket(x: f64, first: f64, step: f64, count: usize) -> Bracket {
    if count < 2 || !(step > 0.0) {
        return Bracket { lo: 0, w: 0.0 };
    }
    let t = ((x - first) / step).clamp(0.0, (count - 1) as f64);
    let lo = (t.floor() as usize).min(count - 2);
    Bracket {
        lo,
        w: t - lo as f64,
    }
}

impl SurfaceGrid {
    /// Tabulates the surfaces of `shape` for aspects `l/a` in `[aspect_min, aspect_max]`
    /// (`aspects` nodes evenly in `ln(l/a)`; ignored for the disc), with the skew axis if
    /// `with_skew` (the rectangle only).
    pub fn build(
        shape: FingerShape,
        aspect_min: f64,
        aspect_max: f64,
        aspects: usize,
        with_skew: bool,
    ) -> Result<Self, CalibError> {
        let rect = shape == FingerShape::Rect;
        let ln_aspects = if rect {
            let (lo, hi) = (aspect_min.ln(), aspect_max.ln());
            let n = aspects.max(2);
            (0..n)
                .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
                .collect()
        } else {
            vec![0.0]
        };
        let skews: Vec<f64> = if rect && with_skew {
            // Evenly in (Δ/a)²: the surface moves about linearly in it.
            (0..SKEWS)
                .map(|i| MAX_SKEW * (i as f64 / (SKEWS - 1) as f64).sqrt())
                .collect()
        } else {
            vec![0.0]
        };
        let mut nodes = Vec::new();
        for &skew in &skews {
            for i in 0..KAPPAS {
                let kappa = i as f64 / (KAPPAS - 1) as f64;
                for &ln_aspect in &ln_aspects {
                    nodes.push(Self::node(shape, kappa, ln_aspect.exp(), skew)?);
                }
            }
        }
        Ok(Self {
            shape,
            ln_aspects,
            skews,
            nodes,
        })
    }

    fn node(
        shape: FingerShape,
        kappa: f64,
        aspect: f64,
        skew: f64,
    ) -> Result<(f64, Table), CalibError> {
        let err = |e: softgrip::ConfigError| CalibError::Setting(format!("surface: {e}"));
        let model = FlsModel::<f64>::new(FlsConfig {
            shape: match shape {
                FingerShape::Rect => Shape::Rect { aspect },
                FingerShape::Disc => Shape::Disc,
            },
            k: if kappa > 0.0 {
                1.0 / kappa
            } else {
                f64::INFINITY
            },
            skew: (skew > 0.0).then_some((skew, SKEW_ALPHA, skew / 2.0)),
            order: QuadratureOrder::DEFAULT,
        })
        .map_err(err)?;
        let table = Table::sweep(&model, SAMPLES).map_err(err)?;
        Ok((table.pitch(), table))
    }

    /// The shape the grid was built for.
    pub fn shape(&self) -> FingerShape {
        self.shape
    }

    /// Whether the grid has the skew axis.
    pub fn has_skew(&self) -> bool {
        self.skews.len() > 1
    }

    /// The aspect range `(min, max)` tabulated (lookups clamp outside it).
    pub fn aspect_range(&self) -> (f64, f64) {
        let first = self.ln_aspects.first().copied().unwrap_or(0.0);
        let last = self.ln_aspects.last().copied().unwrap_or(0.0);
        (first.exp(), last.exp())
    }

    fn brackets(&self, kappa: f64, aspect: f64, skew: f64) -> [Bracket; 3] {
        let na = self.ln_aspects.len();
        let first = self.ln_aspects.first().copied().unwrap_or(0.0);
        let step = if na > 1 {
            (self.ln_aspects[na - 1] - first) / (na - 1) as f64
        } else {
            0.0
        };
        let ns = self.skews.len();
        let s_step = if ns > 1 {
            MAX_SKEW * MAX_SKEW / (ns - 1) as f64
        } else {
            0.0
        };
        [
            bracket(skew * skew, 0.0, s_step, ns),
            bracket(kappa, 0.0, 1.0 / (KAPPAS - 1) as f64, KAPPAS),
            bracket(aspect.ln(), first, step, na),
        ]
    }

    /// The corners around a point: node index and weight (at most 8, zero weights
    /// skipped).
    fn corners(&self, kappa: f64, aspect: f64, skew: f64) -> Vec<(usize, f64)> {
        let [bs, bk, ba] = self.brackets(kappa, aspect, skew);
        let (na, nk) = (self.ln_aspects.len(), KAPPAS);
        let mut out = Vec::with_capacity(8);
        for (ds, ws) in [(0, 1.0 - bs.w), (1, bs.w)] {
            for (dk, wk) in [(0, 1.0 - bk.w), (1, bk.w)] {
                for (da, wa) in [(0, 1.0 - ba.w), (1, ba.w)] {
                    let w = ws * wk * wa;
                    if w > 0.0 {
                        let idx = ((bs.lo + ds) * nk + bk.lo + dk) * na + ba.lo + da;
                        out.push((idx, w));
                    }
                }
            }
        }
        out
    }

    /// The pitch (`m̃` of pure torsion) at `κ = 1/k` and aspect `l/a` (the skew cannot
    /// change it), interpolated in `ln(pitch)`.
    pub fn pitch(&self, kappa: f64, aspect: f64) -> f64 {
        self.corners(kappa, aspect, 0.0)
            .iter()
            .map(|&(i, w)| w * self.nodes[i].0.ln())
            .sum::<f64>()
            .exp()
    }

    /// Utilisation of the normalised load `(f̃, m̃)` (`≥ 1` slips; homogeneous of degree
    /// one along a ray) at `κ`, aspect and skew `Δ/a` (clamped into the grid).
    pub fn utilisation(&self, kappa: f64, aspect: f64, skew: f64, f: f64, m: f64) -> f64 {
        let corners = self.corners(kappa, aspect, skew);
        let ln_pitch: f64 = corners.iter().map(|&(i, w)| w * self.nodes[i].0.ln()).sum();
        let pitch = ln_pitch.exp();
        // r = Σ w_i r_i with r_i = |q|/u_i, each surface read at m scaled to its pitch.
        let inv: f64 = corners
            .iter()
            .map(|&(i, w)| {
                let (p, table) = &self.nodes[i];
                w / table.utilisation(f, m * p / pitch)
            })
            .sum();
        1.0 / inv
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pitch_matches_the_papers_values() {
        let g = SurfaceGrid::build(FingerShape::Rect, 0.5, 2.0, 9, false).unwrap();
        // The core's pitches at l = a (tests/fls_reference.rs): k = 2: 0.7114; k = 4: 0.7442;
        // uniform 0.76520.
        assert!((g.pitch(0.5, 1.0) - 0.7114).abs() < 2e-4);
        assert!((g.pitch(0.25, 1.0) - 0.7442).abs() < 2e-4);
        assert!((g.pitch(0.0, 1.0) - 0.765_195_7).abs() < 1e-4);
        let d = SurfaceGrid::build(FingerShape::Disc, 1.0, 1.0, 1, false).unwrap();
        assert!((d.pitch(0.5, 3.0) - 3.0 * std::f64::consts::PI / 16.0).abs() < 1e-4);
        // The translation limit and pure torsion.
        assert!((g.utilisation(0.3, 1.3, 0.0, 0.5, 0.0) - 0.5).abs() < 1e-9);
        let p = g.pitch(0.3, 1.3);
        assert!((g.utilisation(0.3, 1.3, 0.0, 0.0, p) - 1.0).abs() < 1e-9);
    }

    /// docs/calibration.md's capacity directions: a lower `k`, no skew and a smaller
    /// contact each shrink the surface along every ray (the utilisation of a fixed load
    /// rises), so they are the conservative ends.
    #[test]
    fn capacity_falls_with_lower_k_no_skew_and_a_smaller_contact() {
        let g = SurfaceGrid::build(FingerShape::Rect, 0.25, 8.0, 11, true).unwrap();
        let l = 0.01;
        for a in [1.5e-3, 3e-3, 6e-3, 1.2e-2] {
            for deg in [0.0f64, 15.0, 30.0, 45.0, 60.0, 75.0, 89.0] {
                // A load in newtons and newton-metres at N = 1, μ = 1.
                let (ft, mn) = (deg.to_radians().sin(), deg.to_radians().cos() * 5e-3);
                let u =
                    |kappa: f64, skew: f64, a: f64| g.utilisation(kappa, l / a, skew, ft, mn / a);
                for kappa in [0.0, 0.25, 0.5, 0.75] {
                    let lower_k = u(kappa + 0.25, 0.0, a);
                    assert!(lower_k >= u(kappa, 0.0, a) * (1.0 - 1e-9), "k at {a} {deg}");
                    assert!(u(kappa, 0.0, a) >= u(kappa, 0.9, a) * (1.0 - 1e-9), "skew");
                    assert!(
                        u(kappa, 0.0, a * 0.8) >= u(kappa, 0.0, a) * (1.0 - 1e-9),
                        "a"
                    );
                }
            }
        }
    }
}
