//! The cyclic protocol (`host-sim experiment cyclic`, docs/experiments.md): at one normal
//! force, on each axis (a tangential force across the cylinder axis, then a moment about
//! the normal), the static onset first ([`timed::onsets`]), then from fresh contacts at
//! each fraction of it a train of load cycles from 0 to the peak and back
//! (`peak·(1 − cos 2πft)/2`), recording how far the plate slid and turned over each
//! cycle (from one return to zero load to the next, where the pressure is the same every
//! cycle). A test stops when the plate slides off the rig ([`timed::slid_off`]).
//!
//! What the rows say is fitted by `softgrip_calibrate::margins`: the largest fraction
//! whose cycles do not ratchet. The defaults and why:
//! docs/decisions/margin-protocols.md. Cost: `2 × fractions × cycles / frequency` of the
//! rig's simulated time, one plant step per [`TICK_S`], and two onset ramps per repeat.

use super::protocol::Noise;
use super::timed::{self, on_axis, Frame, Slip, TimedRig, TICK_S};
use softgrip_calibrate::margin_csv::{Axis, CyclicRow};

/// The default fractions of the onset (docs/decisions/margin-protocols.md).
pub const DEFAULT_FRACTIONS: [f64; 11] =
    [0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95, 1.0];
/// The default number of cycles per fraction (docs/decisions/margin-protocols.md).
pub const DEFAULT_CYCLES: usize = 10;
/// The default cycle frequency \[Hz\] (docs/decisions/margin-protocols.md).
pub const DEFAULT_FREQUENCY_HZ: f64 = 4.0;

/// What the protocol runs.
#[derive(Debug, Clone, PartialEq)]
pub struct CyclicPlan {
    /// The normal force, the peaks (as fractions of the measured onset) and the onset
    /// ramps per axis.
    pub frame: Frame,
    /// Cycles per fraction.
    pub cycles: usize,
    /// Cycle frequency \[Hz\].
    pub frequency_hz: f64,
}

/// The rows of the cyclic protocol on `rig`, recorded with `noise`: per axis, its onset
/// rows (`cycle = 0`), then each fraction's cycles. An axis whose ramp never slips
/// records nothing.
pub fn cyclic(rig: &dyn TimedRig, plan: &CyclicPlan, noise: &mut Noise) -> Vec<CyclicRow> {
    let onset_row = |axis, normal, (ft, mn)| CyclicRow {
        axis,
        normal_force_n: normal,
        fraction: 1.0,
        cycle: 0,
        tangential_force_n: ft,
        torsional_moment_nm: mn,
        slide_m: 0.0,
        turn_rad: 0.0,
    };
    timed::per_axis(
        rig,
        &plan.frame,
        noise,
        onset_row,
        |axis, fraction, peak, noise, rows| cycles(rig, plan, axis, fraction, peak, noise, rows),
    )
}

/// One fraction's cycles from fresh contacts, appended to `rows`.
fn cycles(
    rig: &dyn TimedRig,
    plan: &CyclicPlan,
    axis: Axis,
    fraction: f64,
    peak: f64,
    noise: &mut Noise,
    rows: &mut Vec<CyclicRow>,
) {
    let mut test = rig.fresh(plan.frame.normal_n);
    let ticks = ((1.0 / (plan.frequency_hz * TICK_S)).round() as usize).max(2);
    let mut last = Slip::default();
    for cycle in 1..=plan.cycles {
        let mut now = last;
        for k in 1..=ticks {
            let phase = std::f64::consts::TAU * k as f64 / ticks as f64;
            let (ft, mn) = on_axis(axis, peak * 0.5 * (1.0 - phase.cos()));
            now = test.step(ft, mn, TICK_S);
        }
        let (normal, ft, mn) = timed::recorded(noise, plan.frame.normal_n, axis, peak);
        let row = CyclicRow {
            axis,
            normal_force_n: normal,
            fraction,
            cycle,
            tangential_force_n: ft,
            torsional_moment_nm: mn,
            slide_m: noise.apply(now.slide_since(&last), 0.0).abs(),
            turn_rad: noise.apply(now.turn_since(&last), 0.0).abs(),
        };
        rows.push(row);
        last = now;
        if timed::slid_off(&now) {
            break;
        }
    }
}
