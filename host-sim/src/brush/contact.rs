//! One fingertip's contact: the patch, the foundation's pressure and the bristles,
//! together. [`Contact::press`] sets the normal force (and the tilt that balances the
//! tangential force acting at the finger's height `H`), [`Contact::displace`] moves the
//! object and returns the bristles' wrench.
//!
//! The skew: the tangential force `F_y` the contact transmits acts on the finger at its
//! height `H` above the patch; the foundation tilts (`β`) until the pressure's moment
//! balances it, `Σ p·A·y = F_y·H`, so the pressure centre moves by `F_y·H/N` towards the
//! side the contact force on the object points to (the finger's leading edge as it drags
//! the object that way), clamped as
//! [`foundation::MAX_CENTRE_SHIFT`](super::foundation::MAX_CENTRE_SHIFT) says.
//!
//! Accuracy and cost: those of [`foundation`](super::foundation) (one solve per
//! [`Contact::press`]) and [`bristles`](super::bristles) (one pass per
//! [`Contact::displace`]).

use super::bristles::{BristleWrench, Bristles, Pose};
use super::foundation::{Foundation, Indentation, Scratch};
use super::geometry::Patch;
use super::params::BrushParams;
use std::sync::Arc;

/// One contact's state.
#[derive(Debug, Clone)]
pub struct Contact {
    patch: Arc<Patch>,
    foundation: Foundation,
    height_m: f64,
    bristles: Bristles,
    pressure_pa: Vec<f64>,
    indentation: Indentation,
    flat: Indentation,
    normal_n: f64,
    extent_m: (f64, f64),
    /// The untilted and the tilted solves' working space (each begins where its last
    /// solve ended).
    passes: [Scratch; 2],
}

impl Contact {
    /// A fresh, unloaded contact on `patch` for checked parameters `p`.
    pub fn new(p: &BrushParams, patch: Arc<Patch>) -> Self {
        let n = patch.len();
        Self {
            foundation: Foundation {
                modulus: p.foundation_modulus(),
                exponent: p.stiffening_exponent,
            },
            height_m: p.height_m,
            bristles: Bristles::new(n, p.bristle_stiffness_pa_per_m()),
            pressure_pa: vec![0.0; n],
            indentation: Indentation::default(),
            flat: Indentation::default(),
            normal_n: 0.0,
            extent_m: (0.0, 0.0),
            passes: Default::default(),
            patch,
        }
    }

    /// The patch.
    pub fn patch(&self) -> &Patch {
        &self.patch
    }

    /// The foundation law.
    pub fn foundation(&self) -> Foundation {
        self.foundation
    }

    /// Presses with `normal_n` while the contact transmits `ft_y_n` across the axis:
    /// solves the indentation and tilt and refreshes every element's pressure. A NaN,
    /// infinite or non-positive force unloads the contact.
    pub fn press(&mut self, normal_n: f64, ft_y_n: f64) {
        let n = if normal_n.is_finite() && normal_n > 0.0 {
            normal_n
        } else {
            0.0
        };
        let f = &self.foundation;
        let [flat, tilted] = &mut self.passes;
        // The untilted contact (for the clamp of the skew), warm-started like the tilted.
        self.flat = f.solve_in(&self.patch, [n, 0.0, 0.0], self.flat, flat);
        let (lo, hi) = f.extent_m(&self.patch, self.flat);
        let load = [n, ft_y_n * self.height_m, 0.5 * (hi - lo)];
        self.indentation = f.solve_in(&self.patch, load, self.indentation, tilted);
        f.fill_in(&self.patch, self.indentation, &mut self.pressure_pa, tilted);
        self.bristles.load(&self.patch, tilted.group_pressures());
        self.extent_m = f.extent_m(&self.patch, self.indentation);
        self.normal_n = n;
    }

    /// Moves the object to `q` and returns the bristles' wrench on it.
    pub fn displace(&mut self, q: Pose) -> BristleWrench {
        self.bristles.update(&self.patch, q, false)
    }

    /// [`Contact::displace`] that also sums the bristles' consistent tangent stiffness
    /// ([`BristleWrench::tangent`]), for quasi-static solves.
    pub fn displace_with_tangent(&mut self, q: Pose) -> BristleWrench {
        self.bristles.update(&self.patch, q, true)
    }

    /// How far the grip has slipped ([`Bristles::slip_pose`]): the object's pose less the
    /// layer's elastic stretch.
    pub fn slip_pose(&self) -> Pose {
        self.bristles.slip_pose()
    }

    /// Resets the bristles to zero stretch at `q`.
    pub fn relax(&mut self, q: Pose) {
        self.bristles.relax(&self.patch, q);
    }

    /// Every element's pressure \[Pa\].
    pub fn pressure_pa(&self) -> &[f64] {
        &self.pressure_pa
    }

    /// The present indentation and tilt.
    pub fn indentation(&self) -> Indentation {
        self.indentation
    }

    /// The normal force carried \[N\].
    pub fn normal_n(&self) -> f64 {
        self.normal_n
    }

    /// Half the contact's extent across the axis \[m\].
    pub fn half_width_m(&self) -> f64 {
        0.5 * (self.extent_m.1 - self.extent_m.0)
    }

    /// The pressure centre across the axis, `Σ p A y / Σ p A` \[m\] (0 unloaded).
    pub fn pressure_centre_y_m(&self) -> f64 {
        let (mut f, mut m) = (0.0, 0.0);
        for (p, y) in self.pressure_pa.iter().zip(&self.patch.y_m) {
            f += p;
            m += p * y;
        }
        if f > 0.0 {
            m / f
        } else {
            0.0
        }
    }

    /// The fraction of the loaded elements whose bristle did not slide in the last
    /// [`Contact::displace`] (1 with nothing loaded).
    pub fn stuck_fraction(&self) -> f64 {
        let (loaded, sliding) = self.bristles.counts();
        if loaded == 0 {
            1.0
        } else {
            1.0 - sliding as f64 / loaded as f64
        }
    }

    /// The full-slip limits at the present pressure, brute-force sums over the elements:
    /// pure translation `Σ μ_s p A` \[N\] and pure torsion about the patch centre
    /// `Σ μ_s p A r` [N·m].
    pub fn full_slip_limits(&self) -> (f64, f64) {
        let a = self.patch.area_m2;
        let (mut f, mut m) = (0.0, 0.0);
        for i in 0..self.patch.len() {
            let t = self.patch.mu_static[i] * self.pressure_pa[i] * a;
            f += t;
            m += t * self.patch.x_m[i].hypot(self.patch.y_m[i]);
        }
        (f, m)
    }
}
