//! The held object's motion relative to the fingertips: two translations and the twist
//! about the grasp axis, driven by the external wrench (the load: minus the wrench the
//! grasp must apply) and the two contacts' forces (a symmetric pinch: twice one contact's
//! bristle wrench), plus a viscous term through the stuck bristles (damping ratio `ζ` of
//! the stuck stiffness, `c = 2ζ·sqrt(m·k_stuck)`; it always opposes the relative
//! velocity, so it only dissipates).
//!
//! Integration: semi-implicit (symplectic) Euler, with the tick split into `n` sub-steps
//! so that each is at most `0.2/ω` for the stiffest mode (`ω² = 2·k/m` and `2·k_θ/I` with
//! the loaded bristles' stiffness of the previous step), at most [`MAX_SUBSTEPS`]. It
//! neither creates energy (symplectic, with `ω·dt ≤ 0.2`) nor needs any iteration
//! (`host-sim/tests/brush_plant.rs::a_closed_stick_slip_cycle_dissipates_energy`,
//! `host-sim/tests/brush_plant.rs::object_motion_converges_as_the_tick_shrinks`).
//!
//! Accuracy: first order in the sub-step (`host-sim/tests/brush_plant.rs` measures the motion's
//! convergence as the tick shrinks). Cost: one bristle pass per sub-step.

use super::bristles::{BristleWrench, Pose};
use super::contact::Contact;

/// Most sub-steps per tick.
pub const MAX_SUBSTEPS: usize = 256;

/// The object's inertia and its state relative to the fingertips.
#[derive(Debug, Clone, Copy, Default)]
pub struct Object {
    /// Mass \[kg\].
    pub mass_kg: f64,
    /// Moment of inertia about the grasp axis [kg·m²].
    pub inertia_kg_m2: f64,
    /// Damping ratio of the stuck bristles [-].
    pub damping_ratio: f64,
    /// Pose relative to the fingertips.
    pub pose: Pose,
    /// Velocity relative to the fingertips (`[m/s, m/s, rad/s]`).
    pub velocity: Pose,
}

/// One contact's wrench on the object over a step (bristles and their damping).
#[derive(Debug, Clone, Copy, Default)]
pub struct StepOutcome {
    /// The bristles' state at the last sub-step.
    pub bristles: BristleWrench,
    /// One contact's tangential force on the object, damping included \[N\].
    pub f_t_n: [f64; 2],
    /// One contact's moment on the object, damping included [N·m].
    pub m_n_nm: f64,
    /// Sub-steps taken.
    pub substeps: usize,
}

impl Object {
    /// Sub-steps for a tick of `dt_s` with the loaded bristle stiffness of `last`.
    pub fn substeps(&self, dt_s: f64, last: &BristleWrench) -> usize {
        let w2 = (2.0 * last.stiffness_n_per_m / self.mass_kg)
            .max(2.0 * last.torsion_nm_per_rad / self.inertia_kg_m2);
        let n = (dt_s * w2.sqrt() / 0.2).ceil();
        if n.is_finite() {
            (n as usize).clamp(1, MAX_SUBSTEPS)
        } else {
            1
        }
    }

    /// Advances by `dt_s` under the external wrench `load` (`[F_x, F_y, M]` on the object,
    /// [N, N, N·m]) and two contacts like `contact`.
    pub fn step(
        &mut self,
        contact: &mut Contact,
        load: [f64; 3],
        dt_s: f64,
        last: &BristleWrench,
    ) -> StepOutcome {
        let n = self.substeps(dt_s, last);
        let h = dt_s / n as f64;
        let mut out = StepOutcome {
            substeps: n,
            ..StepOutcome::default()
        };
        for _ in 0..n {
            let w = contact.displace(self.pose);
            let c =
                2.0 * self.damping_ratio * (self.mass_kg * 2.0 * w.stuck_stiffness_n_per_m).sqrt();
            let ct = 2.0
                * self.damping_ratio
                * (self.inertia_kg_m2 * 2.0 * w.stuck_torsion_nm_per_rad).sqrt();
            let v = self.velocity;
            let f = [
                w.f_t_n[0] - 0.5 * c * v.ux_m,
                w.f_t_n[1] - 0.5 * c * v.uy_m,
                w.m_n_nm - 0.5 * ct * v.theta_rad,
            ];
            self.velocity.ux_m += (load[0] + 2.0 * f[0]) / self.mass_kg * h;
            self.velocity.uy_m += (load[1] + 2.0 * f[1]) / self.mass_kg * h;
            self.velocity.theta_rad += (load[2] + 2.0 * f[2]) / self.inertia_kg_m2 * h;
            self.pose.ux_m += self.velocity.ux_m * h;
            self.pose.uy_m += self.velocity.uy_m * h;
            self.pose.theta_rad += self.velocity.theta_rad * h;
            out.bristles = w;
            out.f_t_n = [f[0], f[1]];
            out.m_n_nm = f[2];
        }
        out
    }
}
