//! Lab experiments on a fingertip (`host-sim experiment`, docs/experiments.md): the
//! protocols a lab runs, on any plant that implements [`Rig`], and the recorded rows
//! with sensor noise.
//!
//! - [`Rig`]: the two measurements a plant answers: the contact half-width under a normal
//!   force, and the onset of gross slip along a ramp of load;
//! - [`fls_rig`]: the plant whose contact is softgrip's exact limit surface;
//! - [`brush_rig`]: the physical brush finger ([`crate::brush`]), which softgrip does not
//!   model;
//! - [`protocol`]: indentation, slip, torsion and combined ramps, and the noise;
//! - [`timed`]: the rig's timed loading ([`timed::TimedRig`]), for the margin protocols
//!   [`cyclic`] (cyclic loads below the onset) and [`hold`] (sustained loads).

pub mod brush_rig;
pub mod cyclic;
pub mod fls_rig;
pub mod hold;
pub mod protocol;
pub mod timed;

pub use fls_rig::{FingerSpec, FlsRig};
pub use protocol::{Noise, Protocol};

/// A plant the experiments can be run on.
pub trait Rig {
    /// The contact half-width `a` \[m\] at normal force `normal_n` \[N\], at equilibrium.
    fn indentation_half_width_m(&self, normal_n: f64) -> f64;

    /// Ramps the load `s·(ft_unit_n, mn_unit_nm)` from `s = 0` at normal force `normal_n`
    /// until gross slip and returns the load `(f_t [N], m_n [N·m])` at the onset, or `None`
    /// if it never slips.
    fn slip_onset(&self, normal_n: f64, ft_unit_n: f64, mn_unit_nm: f64) -> Option<(f64, f64)>;
}
