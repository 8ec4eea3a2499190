//! Tangential stick–slip: one bristle per element, a spring of stiffness `k_t·A`
//! (`k_t = G/h`) from the element's point on the object to its anchor on the finger, with
//! Coulomb friction. A stuck bristle holds until its force exceeds `μ_s·p·A`; it then
//! slips: the anchor jumps so that the force is `μ_k·p·A`, along the stretch, and it
//! keeps sliding at `μ_k·p·A` for as long as the stretch would exceed that; once the
//! stretch falls back (the motion stops or reverses) it sticks again and needs `μ_s`
//! once more to break. An unloaded element (`p = 0`) carries no force: its anchor follows
//! its point. Partial slip (edge elements sliding while the centre sticks), creep (the
//! slid elements' anchors drifting) and gross slip (every loaded element sliding) come
//! out of these rules and nothing else.
//!
//! An element of the object's surface at `(x, y)` is displaced, for the object's pose
//! `(u_x, u_y, θ)` relative to the finger, by `(u_x − θ·y, u_y + θ·x)`.
//!
//! Accuracy: exact for the rules above at the positions it is given (a return mapping;
//! the forces follow the displacement history at the resolution it is stepped). Cost:
//! one pass over the loaded elements per update, with a `hypot` only where the squares of
//! the stretch do not settle that the bristle sticks; per pressure ([`Bristles::load`]),
//! the slip limits once per element group and element by element only where a group is
//! loaded or unloaded (an unloaded element's anchor is set then, not at every update).

use super::geometry::Patch;

/// The object's pose relative to the finger.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Pose {
    /// Translation along the axis \[m\].
    pub ux_m: f64,
    /// Translation across the axis \[m\].
    pub uy_m: f64,
    /// Rotation about the contact normal \[rad\].
    pub theta_rad: f64,
}

/// What the bristles transmit to the object (one contact).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BristleWrench {
    /// Tangential force on the object \[N\]: `(x, y)`.
    pub f_t_n: [f64; 2],
    /// Moment on the object about the contact normal at the patch centre [N·m].
    pub m_n_nm: f64,
    /// Loaded elements (`p > 0`).
    pub loaded: usize,
    /// Loaded elements that stuck in the last update.
    pub stuck: usize,
    /// Stiffness of the loaded bristles `Σ k_t A` [N/m].
    pub stiffness_n_per_m: f64,
    /// Torsional stiffness of the loaded bristles `Σ k_t A r²` [N·m/rad].
    pub torsion_nm_per_rad: f64,
    /// Stiffness of the stuck bristles [N/m].
    pub stuck_stiffness_n_per_m: f64,
    /// Torsional stiffness of the stuck bristles [N·m/rad].
    pub stuck_torsion_nm_per_rad: f64,
    /// First moments of the stuck bristles' stiffness `(Σ k_t A x, Σ k_t A y)` \[N\].
    pub stuck_moment_n: [f64; 2],
    /// Elastic energy stored in the bristles \[J\].
    pub energy_j: f64,
    /// The consistent tangent stiffness `K` (`dW ≈ −K·dq` for a pose change `dq`, from the
    /// same committed anchors), upper triangle `[K11, K12, K13, K22, K23, K33]`: stuck
    /// bristles `k_t A·BᵀB`, sliding ones `k_t A·(s_k/|s|)·Bᵀ(I − ŝŝᵀ)B` (their force turns
    /// with the stretch); filled only by [`Bristles::update`] with `tangent`.
    pub tangent: [f64; 6],
}

/// One element's bristle: where it is anchored on the object, and whether it slid in the
/// last update.
#[derive(Debug, Clone, Copy, Default)]
struct Bristle {
    anchor_m: [f64; 2],
    sliding: bool,
}

/// A loaded element as an update reads it ([`Bristles::load`]): its index, its group
/// (whose pressure and slip limits it carries), its centre \[m\] and its bristle's
/// stiffness `k_t·A` times `x² + y²`, `x` and `y` (the products an update forms, formed
/// once).
#[derive(Debug, Clone, Copy)]
struct Loaded {
    i: usize,
    group: usize,
    x: f64,
    y: f64,
    ka_r2: f64,
    ka_x: f64,
    ka_y: f64,
}

/// The bristles' state: each element's anchor and whether it slid in the last update,
/// and the pressure they are pressed with.
///
/// An unloaded element's anchor follows its point, and an update sets nothing else of
/// it, so only its value after the last update counts: it is set when the element is
/// loaded again ([`Bristles::load`]), to its point at the pose of the last update if an
/// update came since it was unloaded, rather than at every update.
#[derive(Debug, Clone)]
pub struct Bristles {
    /// Stiffness per unit area `k_t` [N/m³].
    pub k_pa_per_m: f64,
    bristles: Vec<Bristle>,
    /// Each element group's pressure `p` \[Pa\] and slip limits of the stretch, static
    /// and kinetic, `μ·p/k_t` \[m\] ([`Bristles::load`]).
    limits: Vec<[f64; 3]>,
    /// Whether each element group is loaded (`p ≤ 0` false).
    group_loaded: Vec<bool>,
    /// The loaded elements, those an update applies the stick–slip rules to, ascending.
    loaded: Vec<Loaded>,
    /// For each unloaded element, the count of updates when it was unloaded.
    unloaded_since: Vec<u64>,
    /// Updates so far, and the pose of the last.
    updates: (u64, Pose),
}

impl Bristles {
    /// Fresh bristles (no stretch anywhere, no pressure) for `n` elements.
    pub fn new(n: usize, k_pa_per_m: f64) -> Self {
        Self {
            k_pa_per_m,
            bristles: vec![Bristle::default(); n],
            limits: Vec::new(),
            group_loaded: Vec::new(),
            loaded: Vec::with_capacity(n),
            unloaded_since: vec![0; n],
            updates: (0, Pose::default()),
        }
    }

    /// Presses the bristles for the updates that follow with `pressure_pa`, one per
    /// element group of `patch` ([`Groups`](super::geometry::Groups): the elements of a
    /// group carry the same pressure, as
    /// [`Foundation::fill`](super::foundation::Foundation::fill) gives it), and sets the
    /// slip limits `μ·p/k_t` from it, once per group. Element by element only where a
    /// group is loaded or unloaded.
    pub fn load(&mut self, patch: &Patch, pressure_pa: &[f64]) {
        let k = self.k_pa_per_m;
        let groups = &patch.groups;
        self.limits.clear();
        self.limits
            .extend(pressure_pa.iter().zip(&groups.first).map(|(&p, &i)| {
                let i = i as usize;
                [p, patch.mu_static[i] * p / k, patch.mu_kinetic[i] * p / k]
            }));
        let same = self.group_loaded.len() == self.limits.len()
            && (self.limits.iter().zip(&self.group_loaded)).all(|(l, &was)| was == loaded(l[0]));
        if !same {
            self.reload(patch);
        }
    }

    /// [`Bristles::load`] where groups were loaded or unloaded: the loaded elements
    /// anew, the anchors owed to the newly loaded ones set, the newly unloaded ones
    /// marked.
    fn reload(&mut self, patch: &Patch) {
        let ka = self.k_pa_per_m * patch.area_m2;
        let (count, q) = self.updates;
        let was = std::mem::take(&mut self.group_loaded);
        self.group_loaded = self.limits.iter().map(|l| loaded(l[0])).collect();
        self.loaded.clear();
        for (i, &g) in patch.groups.of.iter().enumerate().take(self.bristles.len()) {
            let (g, (x, y)) = (g as usize, (patch.x_m[i], patch.y_m[i]));
            let before = was.get(g).copied().unwrap_or(false);
            if !self.group_loaded[g] {
                if before {
                    self.unloaded_since[i] = count;
                }
                continue;
            }
            if !before && count > self.unloaded_since[i] {
                self.bristles[i] = Bristle {
                    anchor_m: [q.ux_m - q.theta_rad * y, q.uy_m + q.theta_rad * x],
                    sliding: false,
                };
            }
            self.loaded.push(Loaded {
                i,
                group: g,
                x,
                y,
                ka_r2: ka * (x * x + y * y),
                ka_x: ka * x,
                ka_y: ka * y,
            });
        }
    }

    /// Resets every bristle to zero stretch at pose `q`.
    pub fn relax(&mut self, patch: &Patch, q: Pose) {
        for (i, b) in self.bristles.iter_mut().enumerate().take(patch.len()) {
            *b = Bristle {
                anchor_m: [
                    q.ux_m - q.theta_rad * patch.y_m[i],
                    q.uy_m + q.theta_rad * patch.x_m[i],
                ],
                sliding: false,
            };
        }
        self.unloaded_since.fill(self.updates.0);
    }

    /// The loaded elements, ascending, with their pressure \[Pa\].
    fn loaded_pressures(&self) -> impl Iterator<Item = (&Loaded, f64)> + '_ {
        self.loaded.iter().map(|l| (l, self.limits[l.group][0]))
    }

    /// How far the finger's grip on the object has slipped: the rigid motion `(u, θ)`
    /// that best fits (least squares weighted by the pressure, about the origin of the
    /// patch) the anchors of the loaded elements (`p > 0`), each anchor being the
    /// object's point at which its bristle would be unstretched. A stuck bristle's anchor
    /// never moves, so the elastic stretch of the layer, which springs back when the load
    /// goes, is not slip; a slid anchor has moved with the object. The weights make the
    /// elements that carry the grip count most, the lightly pressed edge of the patch
    /// least. The zero pose when nothing is loaded, no rotation when the loaded elements
    /// are all at one point. The pressure of the last [`Bristles::load`]. Cost: two passes
    /// over the loaded elements.
    pub fn slip_pose(&self) -> Pose {
        let (mut w, mut sx, mut sy, mut sax, mut say) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for (l, p) in self.loaded_pressures() {
            if p > 0.0 {
                let [ax, ay] = self.bristles[l.i].anchor_m;
                w += p;
                sx += p * l.x;
                sy += p * l.y;
                sax += p * ax;
                say += p * ay;
            }
        }
        if !(w > 0.0 && w.is_finite()) {
            return Pose::default();
        }
        let (xm, ym, axm, aym) = (sx / w, sy / w, sax / w, say / w);
        let (mut num, mut den) = (0.0, 0.0);
        for (l, p) in self.loaded_pressures() {
            if p > 0.0 {
                let [ax, ay] = self.bristles[l.i].anchor_m;
                let (x, y) = (l.x - xm, l.y - ym);
                let (ax, ay) = (ax - axm, ay - aym);
                num += p * (x * ay - y * ax);
                den += p * (x * x + y * y);
            }
        }
        let theta = if den > 0.0 { num / den } else { 0.0 };
        Pose {
            ux_m: axm + theta * ym,
            uy_m: aym - theta * xm,
            theta_rad: theta,
        }
    }

    /// `(loaded, sliding)`: the elements with `p > 0` and those of them that slid in the
    /// last update.
    pub fn counts(&self) -> (usize, usize) {
        let mut out = (0, 0);
        for (l, p) in self.loaded_pressures() {
            if p > 0.0 {
                out.0 += 1;
                out.1 += usize::from(self.bristles[l.i].sliding);
            }
        }
        out
    }

    /// Moves the object to `q` under the pressures of the last [`Bristles::load`],
    /// applies the stick–slip rules and returns the wrench on the object.
    /// With `tangent`, also sums the consistent tangent stiffness
    /// ([`BristleWrench::tangent`]).
    pub fn update(&mut self, patch: &Patch, q: Pose, tangent: bool) -> BristleWrench {
        let ka = self.k_pa_per_m * patch.area_m2;
        let w = if tangent {
            self.pass::<true>(ka, q)
        } else {
            self.pass::<false>(ka, q)
        };
        self.updates = (self.updates.0 + 1, q);
        w
    }

    /// [`Bristles::update`]'s pass over the loaded elements, `ka = k_t·A`.
    fn pass<const TANGENT: bool>(&mut self, ka: f64, q: Pose) -> BristleWrench {
        let mut w = BristleWrench::default();
        for l in &self.loaded {
            let b = &mut self.bristles[l.i];
            let [_, limit_static, limit_kinetic] = self.limits[l.group];
            let (x, y) = (l.x, l.y);
            let dx = q.ux_m - q.theta_rad * y;
            let dy = q.uy_m + q.theta_rad * x;
            let (mut sx, mut sy) = (dx - b.anchor_m[0], dy - b.anchor_m[1]);
            let limit = if b.sliding {
                limit_kinetic
            } else {
                limit_static
            };
            let beyond = stretch_beyond(sx, sy, limit);
            let slides = beyond.is_some();
            if let Some(stretch) = beyond {
                let keep = limit_kinetic / stretch;
                if TANGENT {
                    let (ex, ey) = (sx / stretch, sy / stretch);
                    let m = [
                        keep * (1.0 - ex * ex),
                        -keep * ex * ey,
                        keep * (1.0 - ey * ey),
                    ];
                    add_tangent(&mut w.tangent, ka, m, x, y);
                }
                sx *= keep;
                sy *= keep;
                b.anchor_m = [dx - sx, dy - sy];
            } else if TANGENT {
                add_tangent(&mut w.tangent, ka, [1.0, 0.0, 1.0], x, y);
            }
            b.sliding = slides;
            let (fx, fy) = (-ka * sx, -ka * sy);
            w.f_t_n[0] += fx;
            w.f_t_n[1] += fy;
            w.m_n_nm += x * fy - y * fx;
            w.loaded += 1;
            w.stiffness_n_per_m += ka;
            w.torsion_nm_per_rad += l.ka_r2;
            if !slides {
                w.stuck += 1;
                w.stuck_stiffness_n_per_m += ka;
                w.stuck_torsion_nm_per_rad += l.ka_r2;
                w.stuck_moment_n[0] += l.ka_x;
                w.stuck_moment_n[1] += l.ka_y;
            }
            w.energy_j += 0.5 * ka * (sx * sx + sy * sy);
        }
        w
    }
}

/// Whether an element pressed with `p` \[Pa\] is loaded: the stick–slip rules apply to
/// it unless `p ≤ 0` (a NaN pressure is loaded, as it always was).
fn loaded(p: f64) -> bool {
    let unloaded = p <= 0.0;
    !unloaded
}

/// The stretch `|(sx, sy)|` \[m\] when it exceeds `limit` \[m\] (the bristle slides), else
/// `None`: the same answer as `sx.hypot(sy) > limit`, bit for bit, with the `hypot` (the
/// costliest libm call of a brush step under `perf`) skipped when the squares settle it. They do when
/// `sx² + sy²` lies below `limit²` by more than `1e-9` of it, far beyond their few ulps of
/// rounding (and `limit > 1e-100` keeps `limit²` a normal number); a NaN or an overflow
/// goes to the `hypot`, as before.
#[inline]
fn stretch_beyond(sx: f64, sy: f64, limit: f64) -> Option<f64> {
    if limit > 1e-100 && sx * sx + sy * sy < limit * limit * (1.0 - 1e-9) {
        return None;
    }
    let stretch = sx.hypot(sy);
    (stretch > limit).then_some(stretch)
}

/// Adds `ka·BᵀPB` to the tangent's upper triangle, `P = [[a, b], [b, d]]` given as
/// `[a, b, d]`, `B = [[1, 0, −y], [0, 1, x]]`.
fn add_tangent(t: &mut [f64; 6], ka: f64, [a, b, d]: [f64; 3], x: f64, y: f64) {
    t[0] += ka * a;
    t[1] += ka * b;
    t[2] += ka * (x * b - y * a);
    t[3] += ka * d;
    t[4] += ka * (x * d - y * b);
    t[5] += ka * (y * y * a - 2.0 * x * y * b + x * x * d);
}

#[cfg(test)]
mod tests {
    use super::stretch_beyond;
    use rand::{Rng, SeedableRng};

    /// What `update` decided before the squares were tried: the `hypot` alone.
    fn by_hypot(sx: f64, sy: f64, limit: f64) -> Option<f64> {
        let stretch = sx.hypot(sy);
        (stretch > limit).then_some(stretch)
    }

    #[test]
    fn the_squares_never_change_the_answer_of_the_hypot() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let same = |sx: f64, sy: f64, limit: f64| {
            let (a, b) = (stretch_beyond(sx, sy, limit), by_hypot(sx, sy, limit));
            assert!(
                a.map(f64::to_bits) == b.map(f64::to_bits),
                "{sx:e} {sy:e} {limit:e}: {a:?} against {b:?}"
            );
        };
        for _ in 0..200_000 {
            let limit = 10f64.powf(rng.random_range(-12.0..2.0));
            let angle = rng.random_range(0.0..std::f64::consts::TAU);
            // Stretches around the limit, most within a few ulps of it.
            let ulps = rng.random_range(-64i64..64);
            let r = f64::from_bits((limit.to_bits() as i64 + ulps) as u64)
                * if rng.random_bool(0.5) {
                    1.0
                } else {
                    rng.random_range(0.0..2.0)
                };
            same(r * angle.cos(), r * angle.sin(), limit);
            same(r, 0.0, limit);
            same(0.0, -r, limit);
        }
        for limit in [
            0.0,
            -1.0,
            1e-101,
            1e-200,
            f64::MIN_POSITIVE,
            f64::NAN,
            f64::INFINITY,
        ] {
            for s in [
                0.0,
                1e-160,
                1e-101,
                1.0,
                1e160,
                f64::NAN,
                f64::INFINITY,
                -f64::INFINITY,
            ] {
                same(s, s, limit);
                same(s, 0.0, limit);
            }
        }
    }
}
