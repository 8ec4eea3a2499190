//! A run's statistics, accumulated tick by tick whatever the plant, and the drop.

use crate::sim::effects::World;
use crate::sim::truth::TrueLoad;

/// Slip distance beyond which the object is lost from the grasp \[m\] (10 mm).
pub const DROP_DISTANCE_M: f64 = 0.01;
/// Slip rotation beyond which the object is lost from the grasp \[rad\].
pub const DROP_ROTATION_RAD: f64 = 0.2;

/// Whether an object that has slid `slip_distance_m` \[m\] and turned `slip_rotation_rad`
/// \[rad\] relative to the fingertips is dropped: more than [`DROP_DISTANCE_M`] or more
/// than [`DROP_ROTATION_RAD`]. The only definition of a drop.
pub fn is_drop(slip_distance_m: f64, slip_rotation_rad: f64) -> bool {
    slip_distance_m > DROP_DISTANCE_M || slip_rotation_rad.abs() > DROP_ROTATION_RAD
}

/// A run's statistics, tick by tick, whatever the plant: slip events, the drop, the
/// normal force's sum and peak, the greatest utilisation and micro-slip.
#[derive(Debug)]
pub(super) struct Tally {
    /// Ticks of sticking before a slip counts as a new event.
    stick_ticks: u64,
    /// Ticks of sticking since the last slip (`u64::MAX` before any).
    stuck_for: u64,
    /// Slip events so far.
    pub(super) events: u64,
    /// When the object was lost from the grasp [s], once it is.
    pub(super) dropped_at: Option<f64>,
    /// The sum of the true normal force over the ticks [N].
    pub(super) sum_n: f64,
    /// The greatest true normal force [N].
    pub(super) peak_n: f64,
    /// The greatest finite utilisation of the true load.
    pub(super) max_u: f64,
    /// The greatest micro-slip of the partial-slip effect [m].
    pub(super) max_micro_m: f64,
}

impl Tally {
    /// Nothing counted yet; a slip after `stick_ticks` of sticking is a new event.
    pub(super) fn new(stick_ticks: u64) -> Self {
        Self {
            stick_ticks,
            stuck_for: u64::MAX,
            events: 0,
            dropped_at: None,
            sum_n: 0.0,
            peak_n: 0.0,
            max_u: 0.0,
            max_micro_m: 0.0,
        }
    }

    /// Counts one tick: `slipping` whether the contact slid, `slide` the object's slip
    /// distance [m] and rotation [rad] so far. Nothing is counted as slip once dropped.
    pub(super) fn record(&mut self, w: &World, tl: &TrueLoad, slipping: bool, slide: (f64, f64)) {
        if self.dropped_at.is_none() {
            if slipping {
                if self.stuck_for >= self.stick_ticks {
                    self.events += 1;
                }
                self.stuck_for = 0;
            } else {
                self.stuck_for = self.stuck_for.saturating_add(1);
            }
            if is_drop(slide.0, slide.1) {
                self.dropped_at = Some(w.t_s);
            }
        }
        self.sum_n += w.normal_n;
        self.peak_n = self.peak_n.max(w.normal_n);
        if tl.utilisation.is_finite() {
            self.max_u = self.max_u.max(tl.utilisation);
        }
        self.max_micro_m = self.max_micro_m.max(w.micro_slip_m);
    }
}
