//! Tanh-sinh (double-exponential) quadrature with fixed, precomputed nodes.
//!
//! The limit-surface integrands have singularities only at places we know in advance: the
//! patch edge (`g ~ (1 − s)^(1/k)`), the pressure peak (a kink), the row or ring through the
//! centre of rotation (`y ln|y|`, `ln|r − d|`). Splitting the domain there puts every
//! singularity at an interval end, where the tanh-sinh substitution makes the integrand decay
//! double-exponentially: the error falls like `exp(−c·n/ln n)` in the node count, whatever
//! the algebraic or logarithmic end behaviour (Takahasi & Mori 1974; Bailey, Jeyabalan & Li
//! 2005). Each node carries its distance to *both* ends, computed without cancellation, so an
//! integrand can evaluate `(1 − s)^(1/k)` at 1e-300 from the edge with full relative accuracy.
//!
//! Cost: `2n + 1` integrand evaluations per interval, `n` = [`QuadratureOrder::nodes_per_side`].

use crate::error::ConfigError;
use crate::real::Real;

/// Largest number of nodes on each side of the centre that a rule can hold.
pub const MAX_NODES_PER_SIDE: usize = 128;

/// Node count of a tanh-sinh rule: `2n + 1` evaluations per interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QuadratureOrder {
    nodes_per_side: usize,
}

impl QuadratureOrder {
    /// The default: 28 nodes on each side (57 per interval). At this order the limit-surface
    /// point is within 1e-9 of the converged integral in f64 over the tested domain (see
    /// `tests/fls_accuracy.rs`).
    pub const DEFAULT: Self = Self { nodes_per_side: 28 };

    /// Validates `4 ≤ n ≤ MAX_NODES_PER_SIDE` (parameter name `order`).
    pub fn new(nodes_per_side: usize) -> Result<Self, ConfigError> {
        if !(4..=MAX_NODES_PER_SIDE).contains(&nodes_per_side) {
            return Err(ConfigError::Capacity {
                param: "order",
                requested: nodes_per_side,
                limit: if nodes_per_side < 4 {
                    4
                } else {
                    MAX_NODES_PER_SIDE
                },
            });
        }
        Ok(Self { nodes_per_side })
    }

    /// Nodes on each side of the centre.
    pub fn nodes_per_side(&self) -> usize {
        self.nodes_per_side
    }
}

impl Default for QuadratureOrder {
    fn default() -> Self {
        Self::DEFAULT
    }
}

#[derive(Debug, Clone, Copy, Default)]
struct Node<T> {
    /// `1 − x_j`, the node's distance from the end of `[-1, 1]`.
    comp: T,
    /// Weight times the step.
    weight: T,
}

/// A tanh-sinh rule on `[-1, 1]`, mapped onto any `[lo, hi]` by [`TanhSinh::integrate`].
#[derive(Debug, Clone)]
pub(crate) struct TanhSinh<T> {
    nodes: [Node<T>; MAX_NODES_PER_SIDE + 1],
    len: usize,
}

/// A point handed to the integrand: its position and its distances to both interval ends.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadPoint<T> {
    /// Position in `[lo, hi]`.
    pub x: T,
    /// `x − lo`, accurate even when tiny.
    pub from_lo: T,
    /// `hi − x`, accurate even when tiny.
    pub to_hi: T,
}

impl<T: Real> TanhSinh<T> {
    /// A rule with no nodes (every integral 0), to [`TanhSinh::set_order`] into.
    #[inline(always)]
    pub fn empty() -> Self {
        Self {
            nodes: [Node::default(); MAX_NODES_PER_SIDE + 1],
            len: 0,
        }
    }

    /// Builds the rule of `order` in place (the start-up builds it where it lies rather
    /// than moving it): nodes computed in f64, stored in `T`. The truncation point `t_max`
    /// is where the weights fall below the precision of `T` (3.2 for f64, 2.4 for f32;
    /// tests/fls_accuracy.rs holds both to their accuracy), and the step is `t_max / n`.
    pub fn set_order(&mut self, order: QuadratureOrder) {
        let n = order.nodes_per_side.min(MAX_NODES_PER_SIDE);
        let t_max = if T::SINGLE { 2.4 } else { 3.2 };
        let h = t_max / n as f64;
        let half_pi = core::f64::consts::FRAC_PI_2;
        self.nodes.fill(Node::default());
        for (j, node) in self.nodes.iter_mut().enumerate().take(n + 1) {
            let t = j as f64 * h;
            let u = half_pi * libm::sinh(t);
            let comp = 2.0 / (libm::exp(2.0 * u) + 1.0);
            let cu = libm::cosh(u);
            let weight = h * half_pi * libm::cosh(t) / (cu * cu);
            *node = Node {
                comp: T::of(comp),
                weight: T::of(weight),
            };
        }
        self.len = n + 1;
    }

    /// `∫_lo^hi f` for a vector-valued integrand of `D` components. Returns zeros for an
    /// empty or reversed interval.
    #[inline]
    pub fn integrate<const D: usize>(
        &self,
        lo: T,
        hi: T,
        mut f: impl FnMut(QuadPoint<T>) -> [T; D],
    ) -> [T; D] {
        let mut acc = [T::zero(); D];
        if hi.partial_cmp(&lo) != Some(core::cmp::Ordering::Greater) {
            return acc;
        }
        let half = (hi - lo) * T::of(0.5);
        let two = T::of(2.0);
        let mut add = |w: T, v: [T; D]| {
            for (a, v) in acc.iter_mut().zip(v) {
                *a = *a + w * v;
            }
        };
        // One call of `f` in the loop, not three (centre, upper and lower point): `f` is
        // inlined here, so this keeps one copy of each integrand in the firmware instead
        // of three. Point `i` is the centre for `i = 0`, then node `(i + 1)/2`'s upper
        // (odd `i`) and lower (even `i`) point, summed in that order.
        let points = (2 * self.len.min(self.nodes.len())).saturating_sub(1);
        for i in 0..points {
            let Some(node) = self.nodes.get(i.div_ceil(2)) else {
                break;
            };
            let p = if i == 0 {
                QuadPoint {
                    x: lo + half,
                    from_lo: half,
                    to_hi: half,
                }
            } else {
                let near = half * node.comp;
                let far = half * (two - node.comp);
                if i % 2 == 1 {
                    QuadPoint {
                        x: hi - near,
                        from_lo: far,
                        to_hi: near,
                    }
                } else {
                    QuadPoint {
                        x: lo + near,
                        from_lo: near,
                        to_hi: far,
                    }
                }
            };
            add(node.weight, f(p));
        }
        for a in acc.iter_mut() {
            *a = *a * half;
        }
        acc
    }

    /// The nodes of the rule mapped onto `[lo, hi]`, in the order [`TanhSinh::integrate`]
    /// visits them, for integrands whose factors can be cached per node.
    pub fn points(&self, lo: T, hi: T) -> impl Iterator<Item = (QuadPoint<T>, T)> + '_ {
        let half = (hi - lo) * T::of(0.5);
        let two = T::of(2.0);
        self.nodes
            .iter()
            .take(self.len)
            .enumerate()
            .flat_map(move |(j, node)| {
                let near = half * node.comp;
                let far = half * (two - node.comp);
                let w = node.weight * half;
                let hi_pt = QuadPoint {
                    x: hi - near,
                    from_lo: far,
                    to_hi: near,
                };
                let lo_pt = QuadPoint {
                    x: lo + near,
                    from_lo: near,
                    to_hi: far,
                };
                let centre = QuadPoint {
                    x: lo + half,
                    from_lo: half,
                    to_hi: half,
                };
                let first = if j == 0 { (centre, w) } else { (hi_pt, w) };
                let second = if j == 0 { None } else { Some((lo_pt, w)) };
                core::iter::once(first).chain(second)
            })
    }
}
