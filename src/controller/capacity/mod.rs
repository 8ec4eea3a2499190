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
//!
//! The module is split by what each part does: `build` precomputes the grid at
//! start-up (the moment arms, table mode's surfaces, ellipse mode's inscribed ellipse),
//! `tables` exports and imports it as plain arrays and checks imported ones, and this file
//! holds the grid and the per-tick solve.

mod build;
mod tables;

pub(crate) use build::check_range;
pub use tables::{TableError, Tables};

use crate::controller::config::Mode;
use crate::controller::math::{lesser, TickMath};
use crate::real::Real;

/// Most normal forces in the start-up grid.
pub const MAX_FORCE_NODES: usize = 64;
/// Most aspect ratios in table mode's grid.
pub const MAX_ASPECTS: usize = 12;
/// Directions `t = i/(DIRECTIONS − 1)` at which table mode stores each surface.
pub const DIRECTIONS: usize = 33;
/// Most centres of rotation in one start-up sweep (table mode).
pub const MAX_TABLE_SAMPLES: usize = 128;
/// Most iterations of the Illinois step in one solve in f64; it bounds the worst case. The
/// tolerance (8 ulp of the answer) is met well below it: the test fails above 12
/// (`tests/controller.rs::solves_stay_far_below_the_iteration_cap`, which prints the figures).
pub const MAX_ILLINOIS_ITERATIONS: u8 = 16;
/// Most iterations of the Illinois step in one solve in f32, the firmware's precision: one
/// above the most its 8-ulp tolerance needs over the same loads (the test fails above 5,
/// `tests/controller.rs::solves_stay_far_below_the_iteration_cap`). It bounds the worst
/// tick, which docs/firmware-costs.md measures with every solve run to this cap (the
/// `solve-to-cap` feature; docs/decisions/illinois-cap-and-tick-cost.md).
///
/// A solve that reaches a cap returns the upper end of its bracket, where the load holds:
/// more force than the tolerance would give, never less. On a grid far coarser than the
/// default (64 nodes over 1e-9 to 1e6 N) some solves reach it, and ask at most 1 % more
/// force than the converged f64 answer, never less
/// (`tests/controller.rs::the_f32_iteration_cap_costs_at_most_one_percent_of_force_and_never_under_asks`).
pub const MAX_ILLINOIS_ITERATIONS_F32: u8 = 6;

/// The iteration cap of one solve in `T`: [`MAX_ILLINOIS_ITERATIONS_F32`] for f32,
/// [`MAX_ILLINOIS_ITERATIONS`] for f64.
pub fn max_illinois_iterations<T: Real>() -> u8 {
    if T::SINGLE {
        MAX_ILLINOIS_ITERATIONS_F32
    } else {
        MAX_ILLINOIS_ITERATIONS
    }
}
/// The largest utilisation a tick reports (a load on a contact with no normal force).
pub const UTILISATION_MAX: f64 = 1e6;

/// One interval of the grid, between two force nodes: what an Illinois step
/// interpolates.
#[derive(Debug, Clone, Copy)]
struct Interval<T> {
    /// The nodes' forces \[N\].
    force_n: [T; 2],
    /// The moment arms at the nodes \[m\].
    arm_m: [T; 2],
    /// The aspect positions at the nodes (table mode).
    pos: [T; 2],
    /// `1/(force_n[1] − force_n[0])` [1/N].
    inv_width_per_n: T,
}

impl<T: Real> Interval<T> {
    /// `R` and the aspect position at the force `n` inside the interval.
    #[inline(always)]
    fn at(&self, n: T) -> (T, T) {
        let w = (n - self.force_n[0]) * self.inv_width_per_n;
        let arm = lerp(self.arm_m[0], self.arm_m[1], w);
        let pos = lerp(self.pos[0], self.pos[1], w);
        (arm, pos)
    }
}

/// A solve's answer and its cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Solution<T> {
    /// The least force that holds \[N\].
    pub force_n: T,
    /// Illinois iterations spent (0 when a node or a closed form answered).
    pub iterations: u8,
    /// The first grid node that holds the load (`force_nodes` when none does).
    pub node: usize,
}

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

/// `x` clamped to `[lo, hi]` (`lo ≤ hi`) by two comparisons; NaN gives `lo`. The same as
/// `x.max(lo).min(hi)` (up to the sign of a zero), without the M4F's out-of-line
/// `fmaxf`/`fminf` calls (it has no `VMAXNM`): the tick clamps in every `φ` step.
#[inline(always)]
fn clamp<T: Real>(x: T, lo: T, hi: T) -> T {
    if x > lo {
        if x < hi {
            x
        } else {
            hi
        }
    } else {
        lo
    }
}

/// Splits `x ∈ [0, last]` into an index in `[0, last − 1]` and a fraction (NaN reads as 0).
#[inline(always)]
fn split<T: Real>(x: T, last: usize) -> (usize, T) {
    if last == 0 {
        return (0, T::zero());
    }
    let x = clamp(x, T::zero(), T::of_usize(last));
    // `x ≥ 0`, so truncation is the floor (and compiles to one conversion, no libm call).
    let i = x.to_usize().unwrap_or(0).min(last - 1);
    (i, x - T::of_usize(i))
}

impl<T: Real> Capacity<T> {
    /// An empty grid (two nodes at 0 N, no arms): a slot to build into
    /// ([`Capacity::build_into`], [`Capacity::from_tables`]), never solved as it is.
    #[inline(always)]
    pub(crate) fn blank() -> Self {
        Self {
            mode: Mode::Ellipse,
            nodes: 2,
            force_n: [T::zero(); MAX_FORCE_NODES],
            arm_m: [T::zero(); MAX_FORCE_NODES],
            inv_arm_per_m: [T::zero(); MAX_FORCE_NODES],
            inv_width_per_n: [T::zero(); MAX_FORCE_NODES],
            aspect_pos: [T::zero(); MAX_FORCE_NODES],
            shapes: 1,
            inv_radius: [[T::zero(); DIRECTIONS]; MAX_ASPECTS],
            arm_linear_below: false,
            demand_scale: [T::one(); 2],
        }
    }

    /// Back to [`Capacity::blank`], in place.
    pub(crate) fn clear(&mut self) {
        self.mode = Mode::Ellipse;
        self.nodes = 2;
        for a in [
            &mut self.force_n,
            &mut self.arm_m,
            &mut self.inv_arm_per_m,
            &mut self.inv_width_per_n,
            &mut self.aspect_pos,
        ] {
            a.fill(T::zero());
        }
        for row in self.inv_radius.iter_mut() {
            row.fill(T::zero());
        }
        self.shapes = 1;
        self.arm_linear_below = false;
        self.demand_scale = [T::one(); 2];
    }

    /// The mode the grid serves.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The node forces \[N\], from `N_min` to `N_max`.
    pub fn forces_n(&self) -> &[T] {
        self.force_n.get(..self.nodes).unwrap_or(&[])
    }

    /// The moment arms `a·pitch` \[m\] at the node forces.
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
    /// `TABLE` is the mode, fixed for a whole solve ([`Capacity::solve_from`] dispatches
    /// once), so the node tests and Illinois steps carry no mode branch and ellipse mode
    /// reads no aspect position.
    #[inline(always)]
    fn phi<const TABLE: bool>(&self, f: T, m: T, n: T, arm: T, pos: T) -> T {
        if TABLE {
            let s = f * arm + m;
            if s == T::zero() {
                return n * arm;
            }
            n * arm - s * self.inv_radius(m / s, pos)
        } else {
            arm * arm * (n * n - f * f) - m * m
        }
    }

    #[inline(always)]
    fn phi_node<const TABLE: bool>(&self, f: T, m: T, j: usize) -> T {
        let pos = if TABLE {
            at(&self.aspect_pos, j)
        } else {
            T::zero()
        };
        self.phi::<TABLE>(f, m, at(&self.force_n, j), at(&self.arm_m, j), pos)
    }

    /// Interval `j` of the grid (nodes `j`, `j + 1`), read out of the arrays once.
    #[inline(always)]
    fn interval(&self, j: usize) -> Interval<T> {
        let ends = |a: &[T]| [at(a, j), at(a, j + 1)];
        Interval {
            force_n: ends(&self.force_n),
            arm_m: ends(&self.arm_m),
            pos: ends(&self.aspect_pos),
            inv_width_per_n: at(&self.inv_width_per_n, j),
        }
    }

    /// The least normal force \[N\] at which the (already scaled) demand `f = F`, `m = M`
    /// holds: `N_req`. Inputs must be finite and non-negative (the tick guarantees it).
    /// Cost: `log2(force_nodes)` node tests, then at most [`max_illinois_iterations`].
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
        match self.mode {
            Mode::Ellipse => self.solve_in::<M, false>(f, m, from, hint),
            Mode::Table => self.solve_in::<M, true>(f, m, from, hint),
        }
    }

    fn solve_in<M: TickMath<T>, const TABLE: bool>(
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
            if self.phi_node::<TABLE>(f, m, h) >= T::zero() {
                hi = h;
                if self.phi_node::<TABLE>(f, m, h - 1) < T::zero() {
                    lo = h;
                } else {
                    hi = h - 1;
                }
            } else {
                lo = h + 1;
            }
        }
        for _ in 0..3 {
            if lo < hi && self.phi_node::<TABLE>(f, m, lo) < T::zero() {
                lo += 1;
            } else {
                hi = lo;
            }
        }
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if self.phi_node::<TABLE>(f, m, mid) >= T::zero() {
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
        let mut sol = self.illinois_in::<TABLE>(f, m, lo - 1);
        sol.node = lo;
        sol
    }

    /// The Illinois run inside interval `j`. The interval is read once, before the run:
    /// its steps then interpolate from registers instead of reading and bounds-checking
    /// the arrays again, which the M4F's capped ticks need (`host-sim/tests/firmware_costs.rs`;
    /// docs/decisions/illinois-cap-and-tick-cost.md). Same values, same operations: the
    /// same answer bit for bit.
    fn illinois_in<const TABLE: bool>(&self, f: T, m: T, j: usize) -> Solution<T> {
        let iv = self.interval(j);
        let ([a, b], [arm_a, arm_b], [pos_a, pos_b]) = (iv.force_n, iv.arm_m, iv.pos);
        // Ellipse mode's `φ` reads no aspect position, so those reads fold away.
        let phi = |n, arm, pos| self.phi::<TABLE>(f, m, n, arm, pos);
        Self::illinois((a, phi(a, arm_a, pos_a)), (b, phi(b, arm_b, pos_b)), |c| {
            let (arm, pos) = iv.at(c);
            phi(c, arm, pos)
        })
    }

    /// Illinois (modified regula falsi) on `[a, b]` with `φ(a) < 0 ≤ φ(b)`: the bracket is
    /// kept at every step (a step that would leave it bisects instead), and the upper end,
    /// where the load holds, is returned once the bracket is within 8 ulp or after
    /// [`max_illinois_iterations`]. With the `solve-to-cap` feature (a measurement build)
    /// the tolerance is 0, so every solve runs to the cap (each step keeps the bracket, so
    /// the answer still holds the load).
    fn illinois(
        (mut a, mut fa): (T, T),
        (mut b, mut fb): (T, T),
        phi: impl Fn(T) -> T,
    ) -> Solution<T> {
        // 8 ulp; 0 in the measurement build, which keeps the code the same (the constant
        // folds, the test stays) so that its instruction counts are the default's.
        let ulps = if cfg!(feature = "solve-to-cap") {
            0.0
        } else {
            8.0
        };
        let tol = T::epsilon() * T::of(ulps);
        let cap = max_illinois_iterations::<T>();
        let mut side = 0i8;
        let mut iterations = 0u8;
        while iterations < cap {
            if fb == T::zero() || b - a <= tol * b {
                break;
            }
            iterations += 1;
            // The secant point, kept at least half the tolerance inside the bracket: a
            // root within an ulp of one end is then settled by the next test instead of
            // by halving the bracket bit by bit.
            let step = tol * b * T::of(0.5);
            let mut c = clamp(b - fb * (b - a) / (fb - fa), a + step, b - step);
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
        self.interval(j).at(n)
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
        // One comparison, which also sends a NaN to the cap: the same value as
        // `if u.is_nan() { cap } else { u.min(cap) }`, without the M4F's out-of-line
        // `fminf` call.
        lesser(demand / (arm * n), cap)
    }
}
