//! The patch under the finger: a grid of square-cornered elements on the plane `z = 0`,
//! `elements × elements`, covering `|x| ≤ L` (hemicylinder; `|x| ≤ Y` for the
//! hemisphere) by `|y| ≤ Y` (`Y` the mesh half-width). Each element holds its centre, its
//! undeformed gap to the finger surface and its friction coefficients.
//!
//! Gap: hemicylinder `g = R − sqrt(R² − y²)`, hemisphere `g = R − sqrt(R² − x² − y²)`
//! (elements beyond the sphere's rim get an infinite gap and never touch).
//!
//! Accuracy: each element's pressure is taken at its centre (the midpoint rule), so sums
//! over the patch converge as the element side `Δ` shrinks, at about `O(Δ²)` (the
//! contact's edge, where the penetration has a kink, can add an `O(Δ²)` term that
//! oscillates with where the edge falls); `host-sim/tests/brush_plant.rs` measures it. Cost:
//! built once, `elements²` elements of five f64, and their [`Groups`] (a hash of each
//! element's inputs to the pressure).

use super::params::{BrushParams, BrushShape};

/// The elements of the patch, in structure-of-arrays form.
#[derive(Debug, Clone)]
pub struct Patch {
    /// Element centres along the axis \[m\].
    pub x_m: Vec<f64>,
    /// Element centres across the axis \[m\].
    pub y_m: Vec<f64>,
    /// Undeformed gap to the finger surface \[m\] (`+∞` where the finger is absent).
    pub gap_m: Vec<f64>,
    /// Static friction coefficient of each element [-].
    pub mu_static: Vec<f64>,
    /// Kinetic friction coefficient of each element [-].
    pub mu_kinetic: Vec<f64>,
    /// Element area \[m²\].
    pub area_m2: f64,
    /// Element side across the axis \[m\].
    pub dy_m: f64,
    /// Half-extent of the mesh across the axis \[m\].
    pub half_width_m: f64,
    /// Each row's centre across the axis \[m\], ascending (a row: the elements of one `y`).
    pub row_y_m: Vec<f64>,
    /// Each row's least gap \[m\].
    pub row_gap_m: Vec<f64>,
    /// The elements grouped by their inputs to the pressure ([`Groups`]).
    pub groups: Groups,
}

/// The elements grouped by their centre across the axis, their gap and their friction
/// coefficients, bit for bit: the elements of a group have the same penetration
/// `δ + β·y − gap` at every indentation and tilt, so the same pressure, and the same
/// friction limits under it; the foundation computes the pressure (a `powf` for `n ≠ 1`)
/// and the bristles their limits once per group. The hemicylinder's groups are its rows;
/// the hemisphere's pair up the elements mirrored along the axis where their gaps come
/// out equal.
#[derive(Debug, Clone, Default)]
pub struct Groups {
    /// Each element's group.
    pub of: Vec<u32>,
    /// Each group's first element.
    pub first: Vec<u32>,
    /// Each group's centre across the axis \[m\].
    pub y_m: Vec<f64>,
    /// Each group's gap \[m\].
    pub gap_m: Vec<f64>,
}

impl Groups {
    /// The groups of the patch's elements, numbered in the order they first appear.
    fn new(patch: &Patch) -> Self {
        let mut index = std::collections::HashMap::new();
        let mut g = Groups::default();
        for i in 0..patch.len() {
            let (y, gap) = (patch.y_m[i], patch.gap_m[i]);
            let key = [y, gap, patch.mu_static[i], patch.mu_kinetic[i]].map(f64::to_bits);
            let next = g.y_m.len() as u32;
            let k = *index.entry(key).or_insert(next);
            if k == next {
                g.first.push(i as u32);
                g.y_m.push(y);
                g.gap_m.push(gap);
            }
            g.of.push(k);
        }
        g
    }

    /// Number of groups.
    pub fn len(&self) -> usize {
        self.y_m.len()
    }

    /// Whether there are no groups.
    pub fn is_empty(&self) -> bool {
        self.y_m.is_empty()
    }
}

impl Patch {
    /// The grid for `p` (checked parameters).
    pub fn new(p: &BrushParams) -> Self {
        let n = p.elements.max(1);
        let hy = p.mesh_half_width_m;
        let hx = match p.shape {
            BrushShape::Hemicylinder => p.half_length_m,
            BrushShape::Hemisphere => hy,
        };
        let (dx, dy) = (2.0 * hx / n as f64, 2.0 * hy / n as f64);
        let r2 = p.radius_m * p.radius_m;
        let cap = n * n;
        let mut patch = Self {
            x_m: Vec::with_capacity(cap),
            y_m: Vec::with_capacity(cap),
            gap_m: Vec::with_capacity(cap),
            mu_static: Vec::with_capacity(cap),
            mu_kinetic: Vec::with_capacity(cap),
            area_m2: dx * dy,
            dy_m: dy,
            half_width_m: hy,
            row_y_m: Vec::with_capacity(n),
            row_gap_m: vec![f64::INFINITY; n],
            groups: Groups::default(),
        };
        for i in 0..n {
            let x = -hx + (i as f64 + 0.5) * dx;
            for j in 0..n {
                let y = -hy + (j as f64 + 0.5) * dy;
                let rho2 = match p.shape {
                    BrushShape::Hemicylinder => y * y,
                    BrushShape::Hemisphere => x * x + y * y,
                };
                let gap = if rho2 < r2 {
                    p.radius_m - (r2 - rho2).sqrt()
                } else {
                    f64::INFINITY
                };
                let scale = (1.0 + p.mu_gradient_per_m * y).max(0.0);
                patch.x_m.push(x);
                patch.y_m.push(y);
                patch.gap_m.push(gap);
                patch.mu_static.push(p.mu_static * scale);
                patch.mu_kinetic.push(p.mu_kinetic * scale);
                if i == 0 {
                    patch.row_y_m.push(y);
                }
                patch.row_gap_m[j] = patch.row_gap_m[j].min(gap);
            }
        }
        patch.groups = Groups::new(&patch);
        patch
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.x_m.len()
    }

    /// Whether the patch has no elements.
    pub fn is_empty(&self) -> bool {
        self.x_m.is_empty()
    }

    /// The least gap \[m\] (where the finger first touches).
    pub fn min_gap_m(&self) -> f64 {
        self.gap_m.iter().copied().fold(f64::INFINITY, f64::min)
    }
}
