//! The brush finger: a physical fingertip plant that softgrip does not model, built from
//! its own plain f64 mechanics (it calls none of the core's pressure or limit-surface
//! code), as an independent ground truth for the simulator (`[finger] model = "brush"`)
//! and for lab experiments. `docs/brush-finger.md` gives the equations.
//!
//! - [`params`]: the parameters, with units, defaults and ranges;
//! - [`geometry`]: the hemicylinder or hemisphere over a grid of patch elements, each
//!   with its undeformed gap;
//! - [`foundation`]: the normal pressure of an elastic (Winkler) foundation,
//!   `p = K·max(0, δ + β·y − gap)^n`, solved for the normal force and the tilt `β` that
//!   balances the tangential force acting at the finger's height (the skew);
//! - [`bristles`]: a tangential bristle per element with Coulomb stick–slip (static and
//!   kinetic friction);
//! - [`contact`]: one fingertip's contact (the three above together);
//! - [`object`]: the held object's motion relative to the fingertips under the load and
//!   two contacts (a symmetric pinch);
//! - [`onset`]: quasi-static equilibria and the gross-slip onset of a load ramp.
//!
//! [`BrushFinger`] is the finger (parameters and patch, shared); [`BrushPlant`] one
//! grasp's state, stepped once a tick by the run loop.
//!
//! **Accuracy.** The sums over the patch converge with the element count at about second
//! order (hemicylinder, `R = 20 mm`, 1 N: the half-width against the exact circle within
//! 1.2e-3 at 24 elements per side and 3e-5 at 96, `N(δ)` within 9.5e-4 and 7.5e-5); the
//! gross-slip onset of a combined load changes by 2.2e-5 from 24 to 48 elements; the
//! motion is first order in the sub-step (`host-sim/tests/brush_plant.rs` prints the figures).
//!
//! **Cost** per tick (one pressure solve, warm, and one sub-step at its forces): the run's
//! metric `brush_step_per_tick_s`, which
//! `cargo run --release -p host-sim -- simulate host-sim/scenes/brush_lift_hold.toml`
//! reports. Each bristle pass is one sweep over the loaded elements; the pressure solve
//! 1–4 sweeps over the elements, its pressure law (a `powf` for `n ≠ 1`) evaluated once
//! per element group ([`geometry::Groups`]). `docs/brush-finger.md` ("Cost") gives the
//! figures per finger.

pub mod bristles;
pub mod contact;
pub mod foundation;
pub mod geometry;
pub mod object;
pub mod onset;
pub mod params;

use bristles::{BristleWrench, Pose};
use contact::Contact;
use geometry::Patch;
use object::Object;
pub use params::{BrushParams, BrushSettings, BrushShape, ParamError};
use std::sync::Arc;

/// The finger: checked parameters and the patch grid.
#[derive(Debug, Clone)]
pub struct BrushFinger {
    params: BrushParams,
    patch: Arc<Patch>,
}

impl BrushFinger {
    /// The finger for `params`, checked (the error names the key).
    pub fn new(params: BrushParams) -> Result<Self, ParamError> {
        params.check()?;
        let patch = Arc::new(Patch::new(&params));
        Ok(Self { params, patch })
    }

    /// The parameters.
    pub fn params(&self) -> &BrushParams {
        &self.params
    }

    /// The patch grid.
    pub fn patch(&self) -> &Patch {
        &self.patch
    }

    /// A fresh, unloaded contact (one fingertip).
    pub fn contact(&self) -> Contact {
        Contact::new(&self.params, Arc::clone(&self.patch))
    }

    /// A fresh grasp of an object of `mass_kg` \[kg\] and `inertia_kg_m2` [kg·m²].
    pub fn plant(&self, mass_kg: f64, inertia_kg_m2: f64) -> BrushPlant {
        BrushPlant {
            contact: self.contact(),
            object: Object {
                mass_kg,
                inertia_kg_m2,
                damping_ratio: self.params.damping_ratio,
                ..Object::default()
            },
            last: BristleWrench::default(),
            report: PlantReport::default(),
            mu_static: self.params.mu_static,
        }
    }

    /// Quasi-static indentation: the contact half-width across the cylinder axis (y) at
    /// normal force `normal_n` \[m\] (no tangential load, so no tilt). It saturates at the
    /// mesh's half-extent ([`BrushParams::mesh_half_width_m`]); 0 for a force that is not
    /// positive and finite.
    pub fn indentation_half_width_m(&self, normal_n: f64) -> f64 {
        let mut c = self.contact();
        c.press(normal_n, 0.0);
        c.half_width_m()
    }

    /// The indentation `δ` at normal force `normal_n` without tangential load \[m\].
    pub fn indentation_m(&self, normal_n: f64) -> f64 {
        let mut c = self.contact();
        c.press(normal_n, 0.0);
        c.indentation().delta_m
    }

    /// At normal force `normal_n`, ramps the load λ·(ft_unit_n along y, mn_unit_nm about
    /// z) quasi-statically from λ = 0 (fresh bristles) until gross slip; returns λ at the
    /// onset times the units, (f_t \[N\], m_n [N·m]), or None if it never slips within the
    /// bound `λ = 3·λ*` ([`onset`] defines the onset and `λ*`; also `None` for a force or
    /// unit that is not finite, or zero units).
    pub fn slip_onset(&self, normal_n: f64, ft_unit_n: f64, mn_unit_nm: f64) -> Option<(f64, f64)> {
        let lam = onset::ramp(&self.contact(), normal_n, [ft_unit_n, mn_unit_nm])?;
        Some((lam * ft_unit_n, lam * mn_unit_nm))
    }

    /// The full-slip limits at normal force `normal_n` without tangential load, as
    /// brute-force sums over the elements: `(Σ μ_s p A [N], Σ μ_s p A r [N·m])`.
    pub fn full_slip_limits(&self, normal_n: f64) -> (f64, f64) {
        let mut c = self.contact();
        c.press(normal_n, 0.0);
        c.full_slip_limits()
    }
}

/// What the plant reports after a step (one contact's wrench; the pinch has two).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PlantReport {
    /// Tangential force one contact applies to the object \[N\]: `(x, y)`.
    pub f_t_n: [f64; 2],
    /// Moment one contact applies to the object about the contact normal [N·m].
    pub m_n_nm: f64,
    /// Normal force of each fingertip \[N\].
    pub normal_n: f64,
    /// Contact half-width across the axis \[m\].
    pub half_width_m: f64,
    /// Pressure centre across the axis \[m\].
    pub pressure_centre_y_m: f64,
    /// Fraction of the loaded elements that stuck (1 with nothing loaded).
    pub stuck_fraction: f64,
    /// Whether the contact slid grossly: no loaded element stuck while the object moved.
    pub gross_slip: bool,
    /// How far the grip has slipped, `|(u_x, u_y)|` \[m\]: the object's translation
    /// relative to the fingertips less the soft layer's elastic stretch
    /// ([`bristles::Bristles::slip_pose`]).
    pub slip_distance_m: f64,
    /// How far the grip has turned by slipping \[rad\] (the object's rotation less the
    /// layer's elastic twist).
    pub slip_rotation_rad: f64,
    /// Sub-steps taken.
    pub substeps: usize,
}

/// One grasp: a contact (both fingertips alike) and the object's motion.
#[derive(Debug, Clone)]
pub struct BrushPlant {
    contact: Contact,
    object: Object,
    last: BristleWrench,
    report: PlantReport,
    mu_static: f64,
}

fn finite_or_zero(v: f64) -> f64 {
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

impl BrushPlant {
    /// Advances by `dt_s` \[s\] with each fingertip pressing `normal_n` \[N\] while the grasp
    /// must apply `grasp_force_n` \[N\] and `grasp_moment_nm` [N·m] to the object (the
    /// run loop's `World::force_n`/`moment_nm`: the load on the object is minus that).
    /// Non-finite inputs count as zero (a non-finite or non-positive `dt_s` steps nothing).
    pub fn step(
        &mut self,
        normal_n: f64,
        grasp_force_n: [f64; 2],
        grasp_moment_nm: f64,
        dt_s: f64,
    ) -> PlantReport {
        if !(dt_s > 0.0 && dt_s.is_finite()) {
            return self.report;
        }
        self.contact
            .press(finite_or_zero(normal_n), self.report.f_t_n[1]);
        let load = [
            -finite_or_zero(grasp_force_n[0]),
            -finite_or_zero(grasp_force_n[1]),
            -finite_or_zero(grasp_moment_nm),
        ];
        let out = self.object.step(&mut self.contact, load, dt_s, &self.last);
        self.last = out.bristles;
        let b = &out.bristles;
        let v = self.object.velocity;
        let moving = v.ux_m != 0.0 || v.uy_m != 0.0 || v.theta_rad != 0.0;
        let q = self.contact.slip_pose();
        self.report = PlantReport {
            f_t_n: out.f_t_n,
            m_n_nm: out.m_n_nm,
            normal_n: self.contact.normal_n(),
            half_width_m: self.contact.half_width_m(),
            pressure_centre_y_m: self.contact.pressure_centre_y_m(),
            stuck_fraction: if b.loaded > 0 {
                b.stuck as f64 / b.loaded as f64
            } else {
                1.0
            },
            gross_slip: b.stuck == 0 && moving,
            slip_distance_m: q.ux_m.hypot(q.uy_m),
            slip_rotation_rad: q.theta_rad,
            substeps: out.substeps,
        };
        self.report
    }

    /// The static friction coefficient (without the gradient) [-].
    pub fn mu_static(&self) -> f64 {
        self.mu_static
    }

    /// The last report.
    pub fn report(&self) -> PlantReport {
        self.report
    }

    /// The object's pose relative to the fingertips.
    pub fn pose(&self) -> Pose {
        self.object.pose
    }

    /// The contact (one fingertip).
    pub fn contact(&self) -> &Contact {
        &self.contact
    }
}
