//! Timed loading for the margin protocols ([`super::cyclic`], [`super::hold`]), and the
//! frame they share ([`per_axis`]: each axis's onsets, then a test at each fraction of
//! them, its loads recorded by [`recorded`]): the rig presses the finger at a fixed normal force on a light plate and loads the plate with a
//! force-controlled actuator, tangentially (across the cylinder axis, `y`) or about the
//! contact normal, and reads how far the plate has slipped.
//!
//! The rig is the simulator's grasp: a plate of [`PLATE_MASS_KG`] and
//! [`PLATE_INERTIA_KG_M2`] pinched between two like fingertips, each carrying half of the
//! actuator's load. A [`Loading`] is one test from fresh contacts (a lab re-seats the
//! finger before each), stepped at [`TICK_S`]; its [`Slip`] is the plate's slip relative
//! to the fingertips, less the soft layer's elastic stretch (which springs back).
//!
//! - the brush finger ([`BrushFinger`]): its own plant (`BrushPlant`), the plate's
//!   dynamics, stick–slip bristles and all; the slip is the plant's slip pose;
//! - the `fls` plant ([`FlsRig`]): rigid–plastic, per axis: the plate stays put while the
//!   load on that axis is within the limit surface's onset on it, and slides against that
//!   onset (Coulomb, one coefficient) with the plate's inertia beyond it. The protocols
//!   load one axis at a time, where this is the limit surface's own law.
//!
//! Why this plate and tick: docs/decisions/margin-protocols.md.
//! Cost: the brush plant's step per tick (a few sub-steps of one bristle pass); the `fls`
//! plant's, a few flops.

use super::{FlsRig, Noise, Rig};
use crate::brush::{BrushFinger, BrushPlant};
use crate::sim::run::{DROP_DISTANCE_M, DROP_ROTATION_RAD};
use softgrip_calibrate::margin_csv::Axis;

/// The plate's mass \[kg\] (docs/decisions/margin-protocols.md).
pub const PLATE_MASS_KG: f64 = 0.02;
/// The plate's moment of inertia about the contact normal [kg·m²]
/// (docs/decisions/margin-protocols.md).
pub const PLATE_INERTIA_KG_M2: f64 = 2e-6;
/// The step of the timed tests \[s\]: the simulator's tick.
pub const TICK_S: f64 = 1e-3;

/// How far the plate has slipped relative to the fingertips.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Slip {
    /// Along the cylinder axis \[m\].
    pub x_m: f64,
    /// Across the axis \[m\].
    pub y_m: f64,
    /// About the contact normal \[rad\].
    pub turn_rad: f64,
}

impl Slip {
    /// The slide from `earlier` to `self` \[m\].
    pub fn slide_since(&self, earlier: &Slip) -> f64 {
        (self.x_m - earlier.x_m).hypot(self.y_m - earlier.y_m)
    }

    /// The turn from `earlier` to `self` \[rad\], unsigned.
    pub fn turn_since(&self, earlier: &Slip) -> f64 {
        (self.turn_rad - earlier.turn_rad).abs()
    }
}

/// One timed test on fresh contacts at a fixed normal force.
pub trait Loading {
    /// Advances by `dt_s` \[s\] with each fingertip carrying `ft_n` \[N\] across the axis and
    /// `mn_nm` [N·m] about the normal; returns the slip so far.
    fn step(&mut self, ft_n: f64, mn_nm: f64, dt_s: f64) -> Slip;
}

/// A plant the timed protocols can run on: fresh contacts pressed at `normal_n` \[N\].
pub trait TimedRig: Rig {
    /// A fresh test.
    fn fresh(&self, normal_n: f64) -> Box<dyn Loading + '_>;
}

struct BrushLoading {
    plant: BrushPlant,
    normal_n: f64,
}

impl Loading for BrushLoading {
    fn step(&mut self, ft_n: f64, mn_nm: f64, dt_s: f64) -> Slip {
        // The grasp applies the actuator's load: twice one fingertip's.
        self.plant
            .step(self.normal_n, [0.0, 2.0 * ft_n], 2.0 * mn_nm, dt_s);
        let q = self.plant.contact().slip_pose();
        Slip {
            x_m: q.ux_m,
            y_m: q.uy_m,
            turn_rad: q.theta_rad,
        }
    }
}

impl TimedRig for BrushFinger {
    fn fresh(&self, normal_n: f64) -> Box<dyn Loading + '_> {
        Box::new(BrushLoading {
            plant: self.plant(PLATE_MASS_KG, PLATE_INERTIA_KG_M2),
            normal_n,
        })
    }
}

/// Rigid–plastic per axis: `[across the axis, about the normal]`.
struct RigidLoading {
    onset: [f64; 2],
    inertia: [f64; 2],
    velocity: [f64; 2],
    position: [f64; 2],
}

impl Loading for RigidLoading {
    fn step(&mut self, ft_n: f64, mn_nm: f64, dt_s: f64) -> Slip {
        for (i, load) in [ft_n, mn_nm].into_iter().enumerate() {
            let v = self.velocity[i];
            if v == 0.0 && load.abs() <= self.onset[i] {
                continue;
            }
            let sense = if v != 0.0 { v.signum() } else { load.signum() };
            // Two fingertips, each at its onset against the motion.
            let accel = 2.0 * (load - self.onset[i] * sense) / self.inertia[i];
            let next = v + accel * dt_s;
            // Friction stops the plate; it does not drive it back.
            self.velocity[i] = if v != 0.0 && next * v <= 0.0 {
                0.0
            } else {
                next
            };
            self.position[i] += self.velocity[i] * dt_s;
        }
        Slip {
            x_m: 0.0,
            y_m: self.position[0],
            turn_rad: self.position[1],
        }
    }
}

impl TimedRig for FlsRig {
    fn fresh(&self, normal_n: f64) -> Box<dyn Loading + '_> {
        let force = self.slip_onset(normal_n, 1.0, 0.0).map(|(f, _)| f);
        let moment = self.slip_onset(normal_n, 0.0, 1e-3).map(|(_, m)| m);
        Box::new(RigidLoading {
            onset: [
                force.unwrap_or(f64::INFINITY),
                moment.unwrap_or(f64::INFINITY),
            ],
            inertia: [PLATE_MASS_KG, PLATE_INERTIA_KG_M2],
            velocity: [0.0; 2],
            position: [0.0; 2],
        })
    }
}

/// The load `(f_t [N], m_n [N·m])` of `s` on `axis`.
pub fn on_axis(axis: Axis, s: f64) -> (f64, f64) {
    match axis {
        Axis::Force => (s, 0.0),
        Axis::Torsion => (0.0, s),
    }
}

/// The static onset the margin protocols' fractions refer to: `repeats` ramps to gross
/// slip on `axis` at `normal_n` from fresh contacts (as `experiment slip` and `torsion`
/// ramp), each recorded with `noise` as `(N [N], load [N or N·m])`; a ramp that never
/// slips records nothing.
pub fn onsets(
    rig: &dyn TimedRig,
    normal_n: f64,
    axis: Axis,
    repeats: usize,
    noise: &mut Noise,
) -> Vec<(f64, f64)> {
    let (ft_unit, mn_unit) = match axis {
        Axis::Force => (1.0, 0.0),
        Axis::Torsion => (0.0, 1e-3),
    };
    let mut out = Vec::new();
    for _ in 0..repeats {
        let Some((ft, mn)) = rig.slip_onset(normal_n, ft_unit, mn_unit) else {
            continue;
        };
        let (fa, ma) = (noise.force_n, noise.moment_nm);
        let normal = noise.apply(normal_n, fa);
        let load = match axis {
            Axis::Force => noise.apply(ft, fa),
            Axis::Torsion => noise.apply(mn, ma),
        };
        out.push((normal, load.abs()));
    }
    out
}

/// What the margin protocols share of their plan.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The normal force \[N\].
    pub normal_n: f64,
    /// The tests' loads, as fractions of the measured onset.
    pub fractions: Vec<f64>,
    /// Onset ramps per axis.
    pub onsets: usize,
}

/// The margin protocols' frame, shared by [`super::cyclic`] and [`super::hold`]: on each
/// axis (force, then torsion) the static onset first ([`onsets`]: `frame.onsets` ramps at
/// `frame.normal_n`), each recorded as `onset_row(axis, N [N], (f_t [N], m_n [N·m]))`,
/// then `test(axis, fraction, fraction·reference, noise, rows)` for each of the frame's
/// fractions, the reference being the onsets' mean ([`reference()`]). An axis whose ramp
/// never slips records nothing.
pub fn per_axis<R>(
    rig: &dyn TimedRig,
    frame: &Frame,
    noise: &mut Noise,
    onset_row: impl Fn(Axis, f64, (f64, f64)) -> R,
    mut test: impl FnMut(Axis, f64, f64, &mut Noise, &mut Vec<R>),
) -> Vec<R> {
    let mut rows = Vec::new();
    for axis in [Axis::Force, Axis::Torsion] {
        let onsets = onsets(rig, frame.normal_n, axis, frame.onsets, noise);
        let Some(reference) = reference(&onsets) else {
            continue;
        };
        for &(normal, load) in &onsets {
            rows.push(onset_row(axis, normal, on_axis(axis, load)));
        }
        for &fraction in &frame.fractions {
            test(axis, fraction, fraction * reference, noise, &mut rows);
        }
    }
    rows
}

/// A test row's loads as recorded with `noise`: `(N [N], |f_t| [N], |m_n| [N·m])` of
/// `load` on `axis` at `normal_n`.
pub fn recorded(noise: &mut Noise, normal_n: f64, axis: Axis, load: f64) -> (f64, f64, f64) {
    let (fa, ma) = (noise.force_n, noise.moment_nm);
    let normal = noise.apply(normal_n, fa);
    let (ft, mn) = on_axis(axis, load);
    (normal, noise.apply(ft, fa).abs(), noise.apply(mn, ma).abs())
}

/// The mean of the recorded onsets' loads, `None` without any.
pub fn reference(onsets: &[(f64, f64)]) -> Option<f64> {
    (!onsets.is_empty()).then(|| onsets.iter().map(|o| o.1).sum::<f64>() / onsets.len() as f64)
}

/// Whether the plate has slid off the rig: past the simulator's drop
/// ([`crate::sim::run::DROP_DISTANCE_M`], [`crate::sim::run::DROP_ROTATION_RAD`]); a
/// test stops there.
pub fn slid_off(slip: &Slip) -> bool {
    let start = Slip::default();
    slip.slide_since(&start) > DROP_DISTANCE_M || slip.turn_since(&start) > DROP_ROTATION_RAD
}
