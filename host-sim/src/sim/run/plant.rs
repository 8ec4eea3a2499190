//! The plant's step of one tick: the true load, whether the contact slides, and how far
//! the object has slid; on the limit surface (quasi-static slip, see the module docs of
//! [`crate::sim::run`]) or on the brush finger, which replaces both.

use super::costs::Costs;
use crate::brush::BrushPlant;
use crate::sim::effects::{Pipeline, World};
use crate::sim::truth::{TrueLoad, Truth};

/// The plant under the fingertips.
pub(super) enum Plant<'t> {
    /// softgrip's limit surface, with the quasi-static slide of the object.
    Surface {
        /// The true contact and limit surface.
        truth: &'t Truth,
        /// The object's slide relative to the fingertips.
        slide: Slide,
    },
    /// The brush finger, which slides the object itself.
    Brush(Box<BrushPlant>),
}

/// The object's quasi-static slide on the limit surface: velocity [m/s], angular velocity
/// [rad/s], distance [m] and rotation [rad] relative to the fingertips.
#[derive(Debug, Default)]
pub(super) struct Slide {
    v_m_s: f64,
    omega_rad_s: f64,
    distance_m: f64,
    rotation_rad: f64,
}

/// What the run records of one plant step.
pub(super) struct PlantStep {
    /// The true load against the true limit surface.
    pub tl: TrueLoad,
    /// Whether the contact slides.
    pub slipping: bool,
    /// The contact's `|f_t|` [N].
    pub ft_n: f64,
    /// The contact's `|m_n|` [N·m].
    pub mn_nm: f64,
}

impl<'t> Plant<'t> {
    /// The brush finger when `brush` is one, else the limit surface of `truth`.
    pub(super) fn new(truth: &'t Truth, brush: Option<BrushPlant>) -> Self {
        match brush {
            Some(b) => Plant::Brush(Box::new(b)),
            None => Plant::Surface {
                truth,
                slide: Slide::default(),
            },
        }
    }

    /// Whether this is the brush finger.
    pub(super) fn is_brush(&self) -> bool {
        matches!(self, Plant::Brush(_))
    }

    /// The tangential force [N] and moment [N·m] the contact carries, as the sensor sees
    /// them: the grasp's share of the load, or what the brush plant transmitted last.
    pub(super) fn contact_load(&self, w: &World) -> ([f64; 2], f64) {
        match self {
            Plant::Surface { .. } => (w.contact_force_n(), w.contact_moment_nm()),
            Plant::Brush(p) => (p.report().f_t_n, p.report().m_n_nm),
        }
    }

    /// The object's slip distance [m] and rotation [rad] so far.
    pub(super) fn slide(&self) -> (f64, f64) {
        match self {
            Plant::Surface { slide, .. } => (slide.distance_m, slide.rotation_rad),
            Plant::Brush(p) => (p.report().slip_distance_m, p.report().slip_rotation_rad),
        }
    }

    /// One tick's step, with the contact effects of `pipeline` in their place (after the
    /// contact size is set, before the load is judged): `f_t` [N] is the contact's
    /// tangential force as sensed; nothing slides any more once `dropped`.
    pub(super) fn step(
        &mut self,
        w: &mut World,
        pipeline: &mut Pipeline,
        f_t: [f64; 2],
        dropped: bool,
        costs: &mut Costs,
    ) -> PlantStep {
        let t = costs.start();
        match self {
            Plant::Brush(p) => {
                let step = brush_step(p, w, dropped);
                costs.brush += Costs::since(t);
                costs.brush_substeps += p.report().substeps as u64;
                costs.core += Costs::since(t);
                pipeline.contact(w);
                step
            }
            Plant::Surface { truth, slide } => {
                w.half_width_eq_m = truth.half_width_m(w.normal_n);
                w.half_width_m = w.half_width_eq_m;
                costs.core += Costs::since(t);
                pipeline.contact(w);
                surface_step(truth, slide, w, f_t, dropped)
            }
        }
    }
}

/// The limit surface's judgement of the load after the contact effects, and the object's
/// slide: while the load is outside the surface (utilisation `u > 1`) the fraction
/// `1 − 1/u` of it accelerates the object. Sets the world's utilisation and sliding for
/// the next tick's sensors.
fn surface_step(
    truth: &Truth,
    slide: &mut Slide,
    w: &mut World,
    [fx, fy]: [f64; 2],
    dropped: bool,
) -> PlantStep {
    let dt = w.dt_s;
    let (ft, mn) = (fx.hypot(fy), w.contact_moment_nm().abs());
    let tl = truth.evaluate(ft, mn, w.normal_n, w.half_width_m);
    let slipping = tl.utilisation > 1.0;
    if slipping && !dropped {
        let excess = if tl.utilisation.is_finite() {
            1.0 - 1.0 / tl.utilisation
        } else {
            1.0
        };
        slide.v_m_s += excess * w.force_n[0].hypot(w.force_n[1]) / w.mass_kg * dt;
        slide.omega_rad_s += excess * w.moment_nm.abs() / w.inertia_kg_m2 * dt;
        slide.distance_m += slide.v_m_s * dt;
        slide.rotation_rad += slide.omega_rad_s * dt;
    } else if !dropped {
        slide.v_m_s = 0.0;
        slide.omega_rad_s = 0.0;
    }
    // What the next tick's sensors can know of this one (the slip sensor).
    w.true_utilisation = tl.utilisation;
    w.sliding = slipping && !dropped;
    PlantStep {
        tl,
        slipping,
        ft_n: ft,
        mn_nm: mn,
    }
}

/// The brush plant's step for one tick (unless the object is already `dropped`), and
/// what the run records of it: the load state, whether the contact slides grossly, and
/// the contact's `|f_t|` and `|m_n|`. For the brush finger `utilisation` is the fraction
/// of the loaded elements that slide (1 in gross slip), `f_norm = |f_t|/(μ_s N)`,
/// `m_norm = |m_n|/(μ_s N a)` and `pitch` is 0 (there is no limit surface). Sets the
/// world's half-width, utilisation and sliding for the effects.
fn brush_step(plant: &mut BrushPlant, w: &mut World, dropped: bool) -> PlantStep {
    let r = if dropped {
        plant.report()
    } else {
        plant.step(w.normal_n, w.force_n, w.moment_nm, w.dt_s)
    };
    let ft = r.f_t_n[0].hypot(r.f_t_n[1]);
    let mn = r.m_n_nm.abs();
    let cap = plant.mu_static() * r.normal_n;
    let ratio = |x: f64, d: f64| if d > 0.0 { x / d } else { 0.0 };
    let tl = TrueLoad {
        f_norm: ratio(ft, cap),
        m_norm: ratio(mn, cap * r.half_width_m),
        pitch: 0.0,
        utilisation: 1.0 - r.stuck_fraction,
    };
    w.half_width_eq_m = r.half_width_m;
    w.half_width_m = r.half_width_m;
    w.true_utilisation = tl.utilisation;
    let slipping = r.gross_slip;
    w.sliding = slipping && !dropped;
    PlantStep {
        tl,
        slipping,
        ft_n: ft,
        mn_nm: mn,
    }
}
