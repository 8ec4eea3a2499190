//! Normal pressure: an elastic (Winkler) foundation, each element pressed independently,
//! `p = K·max(0, s)^n` with the penetration `s = δ + β·y − gap`: the indentation `δ` of the
//! finger and a small tilt `β` \[rad\] of the foundation about the axis. `K = E/h^n`
//! ([`BrushParams::foundation_modulus`](super::params::BrushParams::foundation_modulus)).
//!
//! [`Foundation::solve`] finds `(δ, β)` such that `Σ p·A = N` and `Σ p·A·y = M_y`, the
//! moment that balances the tangential force acting at the finger's height
//! (`M_y = F_y·H`). A Newton iteration in both unknowns (warm-started, step-halving on the
//! residual, at most [`NEWTON_ITERATIONS`]) and, should it fail, nested bisection (outer on
//! `β`, inner on `δ`, each [`BISECTIONS`] halvings): bounded, and it never panics (a NaN or
//! infinite input gives the unloaded state). The moment is clamped so the pressure centre
//! moves at most [`MAX_CENTRE_SHIFT`] of the untilted contact half-width.
//!
//! Accuracy: the residual is below `1e-10·N` (force) and `1e-10·N·Y` (moment) when the
//! Newton iteration converges, and within `2^-50` of the bracket otherwise. Cost: each
//! iteration is one pass: the pressure once per loaded element group
//! ([`Groups`](super::geometry::Groups): a row of the hemicylinder, a mirrored pair of the
//! hemisphere; one `powf` each for `n ≠ 1`, none for `n = 1`), then a sum over the
//! elements in their order. Warm-started solves take 1–4 passes, the first of them the
//! last solve's last, kept in the contact's [`Scratch`].

use super::geometry::Patch;

/// Most Newton iterations per solve.
pub const NEWTON_ITERATIONS: usize = 40;
/// Halvings of each bisection in the fallback.
pub const BISECTIONS: usize = 50;
/// Largest shift of the pressure centre the tilt may make, as a fraction of the untilted
/// contact half-width.
pub const MAX_CENTRE_SHIFT: f64 = 0.7;

/// The foundation law `p = K·s^n`.
#[derive(Debug, Clone, Copy)]
pub struct Foundation {
    /// `K` [Pa/m^n].
    pub modulus: f64,
    /// `n ≥ 1`.
    pub exponent: f64,
}

/// The finger's indentation and tilt.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Indentation {
    /// Indentation `δ` at `y = 0` \[m\].
    pub delta_m: f64,
    /// Tilt about the axis \[rad\] (penetration grows by `β·y`).
    pub beta_rad: f64,
}

/// Sums over the loaded elements: `Σ p A y^k` and their derivatives `Σ p' A y^k`.
#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    f: [f64; 2],
    d: [f64; 3],
}

/// A contact's working space for the foundation's passes, kept from one solve to the
/// next so that a pass allocates nothing: each element group's pressure and its
/// derivative ([`Groups`](super::geometry::Groups)), and the last point a pass was made
/// at with its sums (a warm-started solve begins where the last one ended, so its first
/// pass is that one's last). For one patch and one foundation law: the sums are a
/// function of the indentation alone, so a repeated point gives the same bits.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    terms: Vec<Option<(f64, f64)>>,
    pressure_pa: Vec<f64>,
    last: Option<(Indentation, Sums)>,
}

impl Scratch {
    /// Each element group's pressure \[Pa\] as the last fill made in this scratch left it.
    pub(super) fn group_pressures(&self) -> &[f64] {
        &self.pressure_pa
    }
}

fn same_point(a: Indentation, b: Indentation) -> bool {
    a.delta_m.to_bits() == b.delta_m.to_bits() && a.beta_rad.to_bits() == b.beta_rad.to_bits()
}

impl Foundation {
    /// Pressure at penetration `s` \[Pa\].
    #[inline]
    pub fn pressure_pa(&self, s_m: f64) -> f64 {
        if s_m <= 0.0 {
            0.0
        } else if self.exponent == 1.0 {
            self.modulus * s_m
        } else {
            self.modulus * s_m.powf(self.exponent)
        }
    }

    /// The sums at `ind`: the pressure and its derivative once per element group, then
    /// summed element by element in the elements' order (the same terms added in the
    /// same order as one element at a time, so the same bits).
    fn sums(&self, patch: &Patch, ind: Indentation, scratch: &mut Scratch) -> Sums {
        if let Some((at, s)) = scratch.last {
            if same_point(at, ind) {
                return s;
            }
        }
        let n = self.exponent;
        let groups = &patch.groups;
        scratch.terms.clear();
        scratch
            .terms
            .extend(groups.y_m.iter().zip(&groups.gap_m).map(|(y, g)| {
                let pen = ind.delta_m + ind.beta_rad * y - g;
                (pen > 0.0).then(|| {
                    if n == 1.0 {
                        (self.modulus * pen, self.modulus)
                    } else {
                        let q = self.modulus * pen.powf(n - 1.0);
                        (q * pen, n * q)
                    }
                })
            }));
        let mut s = Sums::default();
        for (&k, y) in groups.of.iter().zip(&patch.y_m) {
            if let Some((p, dp)) = scratch.terms[k as usize] {
                s.f[0] += p;
                s.f[1] += p * y;
                s.d[0] += dp;
                s.d[1] += dp * y;
                s.d[2] += dp * y * y;
            }
        }
        let a = patch.area_m2;
        s.f = s.f.map(|v| v * a);
        s.d = s.d.map(|v| v * a);
        scratch.last = Some((ind, s));
        s
    }

    /// Total force `Σ p A` at `ind` \[N\].
    pub fn force_n(&self, patch: &Patch, ind: Indentation) -> f64 {
        self.sums(patch, ind, &mut Scratch::default()).f[0]
    }

    /// The indentation at tilt `beta` carrying `normal_n`, by bisection (monotone).
    fn delta_for(&self, patch: &Patch, normal_n: f64, beta: f64, scratch: &mut Scratch) -> f64 {
        let lo0 = patch
            .y_m
            .iter()
            .zip(&patch.gap_m)
            .map(|(y, g)| g - beta * y)
            .fold(f64::INFINITY, f64::min);
        let (mut lo, mut step) = (lo0, patch.dy_m.max(1e-9));
        let mut at = |d: f64| {
            let ind = Indentation {
                delta_m: d,
                beta_rad: beta,
            };
            self.sums(patch, ind, scratch).f[0]
        };
        let mut hi = lo + step;
        let mut k = 0;
        while at(hi) < normal_n && k < 80 {
            lo = hi;
            step *= 2.0;
            hi += step;
            k += 1;
        }
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (lo + hi);
            if at(mid) < normal_n {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The untilted indentation carrying `normal_n` \[m\] (bisection).
    pub fn untilted(&self, patch: &Patch, normal_n: f64) -> Indentation {
        self.untilted_in(patch, normal_n, &mut Scratch::default())
    }

    fn untilted_in(&self, patch: &Patch, normal_n: f64, scratch: &mut Scratch) -> Indentation {
        if !(normal_n > 0.0 && normal_n.is_finite()) {
            return Indentation::default();
        }
        Indentation {
            delta_m: self.delta_for(patch, normal_n, 0.0, scratch),
            beta_rad: 0.0,
        }
    }

    /// Solves `Σ p A = normal_n`, `Σ p A y = moment_y_nm` from `warm` (see the module
    /// docs). `half_width0_m` is the untilted contact's half-width, for the clamp.
    pub fn solve(
        &self,
        patch: &Patch,
        normal_n: f64,
        moment_y_nm: f64,
        half_width0_m: f64,
        warm: Indentation,
    ) -> Indentation {
        let load = [normal_n, moment_y_nm, half_width0_m];
        self.solve_in(patch, load, warm, &mut Scratch::default())
    }

    /// [`Foundation::solve`] for `[normal_n, moment_y_nm, half_width0_m]`, its passes in
    /// `scratch` (kept by the caller for this patch and law).
    pub(super) fn solve_in(
        &self,
        patch: &Patch,
        [normal_n, moment_y_nm, half_width0_m]: [f64; 3],
        warm: Indentation,
        scratch: &mut Scratch,
    ) -> Indentation {
        if !(normal_n > 0.0 && normal_n.is_finite()) {
            return Indentation::default();
        }
        let cap = MAX_CENTRE_SHIFT * half_width0_m.max(patch.dy_m) * normal_n;
        let m = if moment_y_nm.is_finite() {
            moment_y_nm.clamp(-cap, cap)
        } else {
            0.0
        };
        let warm = if warm.delta_m.is_finite() && warm.beta_rad.is_finite() && warm.delta_m > 0.0 {
            warm
        } else {
            self.untilted_in(patch, normal_n, scratch)
        };
        match self.newton(patch, normal_n, m, warm, scratch) {
            Some(ind) => ind,
            None => self.nested(patch, normal_n, m, scratch),
        }
    }

    fn newton(
        &self,
        patch: &Patch,
        n: f64,
        m: f64,
        mut x: Indentation,
        scratch: &mut Scratch,
    ) -> Option<Indentation> {
        let ly = patch.half_width_m;
        let norm = |s: &Sums| ((s.f[0] - n) / n).hypot((s.f[1] - m) / (n * ly));
        let mut s = self.sums(patch, x, scratch);
        let mut r = norm(&s);
        for _ in 0..NEWTON_ITERATIONS {
            if r < 1e-10 {
                return Some(x);
            }
            let det = s.d[0] * s.d[2] - s.d[1] * s.d[1];
            if !(det > 0.0 && det.is_finite()) {
                return None;
            }
            let (e0, e1) = (n - s.f[0], m - s.f[1]);
            let dd = (s.d[2] * e0 - s.d[1] * e1) / det;
            let db = (s.d[0] * e1 - s.d[1] * e0) / det;
            let mut t = 1.0;
            loop {
                let trial = Indentation {
                    delta_m: x.delta_m + t * dd,
                    beta_rad: x.beta_rad + t * db,
                };
                let st = self.sums(patch, trial, scratch);
                let rt = norm(&st);
                if rt < r || t < 1e-3 {
                    (x, s, r) = (trial, st, rt);
                    break;
                }
                t *= 0.5;
            }
        }
        (r < 1e-10).then_some(x)
    }

    fn nested(&self, patch: &Patch, n: f64, m: f64, scratch: &mut Scratch) -> Indentation {
        let d0 = self.delta_for(patch, n, 0.0, scratch);
        let mut moment = |beta: f64| {
            let d = self.delta_for(patch, n, beta, scratch);
            let ind = Indentation {
                delta_m: d,
                beta_rad: beta,
            };
            (ind, self.sums(patch, ind, scratch).f[1])
        };
        let mut hi = d0.max(patch.dy_m) / patch.half_width_m * m.signum();
        let mut k = 0;
        while (moment(hi).1 - m) * m.signum() < 0.0 && k < 40 {
            hi *= 2.0;
            k += 1;
        }
        let mut lo = 0.0;
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (lo + hi);
            if (moment(mid).1 - m) * m.signum() < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        moment(0.5 * (lo + hi)).0
    }

    /// Fills `pressure_pa` (one per element) at `ind`.
    pub fn fill(&self, patch: &Patch, ind: Indentation, pressure_pa: &mut [f64]) {
        self.fill_in(patch, ind, pressure_pa, &mut Scratch::default());
    }

    /// [`Foundation::fill`], each element group's pressure computed once, in `scratch`.
    pub(super) fn fill_in(
        &self,
        patch: &Patch,
        ind: Indentation,
        pressure_pa: &mut [f64],
        scratch: &mut Scratch,
    ) {
        let groups = &patch.groups;
        scratch.pressure_pa.clear();
        scratch.pressure_pa.extend(
            groups
                .y_m
                .iter()
                .zip(&groups.gap_m)
                .map(|(y, g)| self.pressure_pa(ind.delta_m + ind.beta_rad * y - g)),
        );
        for (p, &k) in pressure_pa.iter_mut().zip(&groups.of) {
            *p = scratch.pressure_pa[k as usize];
        }
    }

    /// The contact's extent across the axis, `(y_min, y_max)` \[m\]: the outermost loaded
    /// rows of elements, refined by linear interpolation of the penetration towards their
    /// first unloaded neighbour row (so it moves continuously with the load); a loaded
    /// row at the mesh's edge counts half an element beyond its centre. `(0, 0)` unloaded.
    /// One pass over the rows.
    pub fn extent_m(&self, patch: &Patch, ind: Indentation) -> (f64, f64) {
        let pen = |j: usize| ind.delta_m + ind.beta_rad * patch.row_y_m[j] - patch.row_gap_m[j];
        let rows = patch.row_y_m.len();
        let Some(first) = (0..rows).find(|&j| pen(j) > 0.0) else {
            return (0.0, 0.0);
        };
        let last = (0..rows).rev().find(|&j| pen(j) > 0.0).unwrap_or(first);
        let half = 0.5 * patch.dy_m;
        let edge = |j: usize, next: Option<usize>, dir: f64| {
            let y = patch.row_y_m[j];
            match next {
                Some(o) if pen(o) <= 0.0 => {
                    let (si, so) = (pen(j), pen(o));
                    y + dir * 2.0 * half * si / (si - so)
                }
                _ => y + dir * half,
            }
        };
        let below = first.checked_sub(1);
        let above = (last + 1 < rows).then_some(last + 1);
        (edge(first, below, -1.0), edge(last, above, 1.0))
    }
}
