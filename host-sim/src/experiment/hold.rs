//! The hold protocol (`host-sim experiment hold`, docs/experiments.md): at one normal
//! force, on each axis (a tangential force across the cylinder axis, then a moment about
//! the normal), the static onset first ([`timed::onsets`]), then from fresh contacts at
//! each fraction of it a smooth ramp to the load (`(1 − cos πt/T)/2` over the ramp) and a
//! hold at it, recording how far the plate slid and turned over the hold and the rate of
//! each over the hold's last quarter. A test stops when the plate slides off the rig
//! ([`timed::slid_off`]); its row then gives the time it lasted, ramp included.
//!
//! What the rows say is fitted by `softgrip_calibrate::margins`: the largest fraction
//! that stops creeping within the hold. The defaults and why:
//! docs/decisions/margin-protocols.md. Cost: `2 × fractions × (ramp + hold)` of the rig's
//! simulated time, one plant step per [`TICK_S`], and two onset ramps per repeat.

use super::protocol::Noise;
use super::timed::{self, on_axis, Frame, Slip, TimedRig, TICK_S};
use softgrip_calibrate::margin_csv::{Axis, HoldRow};

/// The default ramp to the load \[s\] (docs/decisions/margin-protocols.md).
pub const DEFAULT_RAMP_S: f64 = 0.5;
/// The default hold \[s\] (docs/decisions/margin-protocols.md).
pub const DEFAULT_HOLD_S: f64 = 1.5;

/// What the protocol runs.
#[derive(Debug, Clone, PartialEq)]
pub struct HoldPlan {
    /// The normal force, the held loads (as fractions of the measured onset) and the
    /// onset ramps per axis.
    pub frame: Frame,
    /// The ramp to the load \[s\].
    pub ramp_s: f64,
    /// The hold \[s\].
    pub hold_s: f64,
}

/// The rows of the hold protocol on `rig`, recorded with `noise`: per axis, its onset rows
/// (`time_s = 0`), then one row per fraction. An axis whose ramp never slips records
/// nothing.
pub fn hold(rig: &dyn TimedRig, plan: &HoldPlan, noise: &mut Noise) -> Vec<HoldRow> {
    let onset_row = |axis, normal, (ft, mn)| HoldRow {
        axis,
        normal_force_n: normal,
        fraction: 1.0,
        tangential_force_n: ft,
        torsional_moment_nm: mn,
        time_s: 0.0,
        slide_m: 0.0,
        turn_rad: 0.0,
        slide_rate_m_s: 0.0,
        turn_rate_rad_s: 0.0,
    };
    timed::per_axis(
        rig,
        &plan.frame,
        noise,
        onset_row,
        |axis, fraction, load, noise, rows| {
            rows.push(held(rig, plan, axis, fraction, load, noise));
        },
    )
}

/// What one sustained load did: the slip at the hold's start (at zero load if the plate
/// slid off during the ramp), a quarter of the hold before the end, at the end, and how
/// long the test lasted, ramp included \[s\].
struct Creep {
    start: Slip,
    late: Slip,
    end: Slip,
    time_s: f64,
    window_s: f64,
}

/// Ramps fresh contacts to `load` on `axis` and holds it.
fn creep(rig: &dyn TimedRig, plan: &HoldPlan, axis: Axis, load: f64) -> Creep {
    let mut test = rig.fresh(plan.frame.normal_n);
    let ramp = (plan.ramp_s / TICK_S).round() as usize;
    let hold = ((plan.hold_s / TICK_S).round() as usize).max(4);
    let window = hold / 4;
    let mut trail = std::collections::VecDeque::with_capacity(window + 1);
    let (mut now, mut start) = (Slip::default(), Slip::default());
    let mut ticks = 0;
    while ticks < ramp + hold && !timed::slid_off(&now) {
        if ticks == ramp {
            start = now;
        }
        let s = if ticks < ramp {
            0.5 * (1.0 - (std::f64::consts::PI * (ticks + 1) as f64 / ramp as f64).cos())
        } else {
            1.0
        };
        trail.push_back(now);
        if trail.len() > window {
            trail.pop_front();
        }
        let (ft, mn) = on_axis(axis, load * s);
        now = test.step(ft, mn, TICK_S);
        ticks += 1;
    }
    Creep {
        start,
        late: trail.front().copied().unwrap_or_default(),
        end: now,
        time_s: ticks as f64 * TICK_S,
        window_s: trail.len().max(1) as f64 * TICK_S,
    }
}

/// One fraction's row.
fn held(
    rig: &dyn TimedRig,
    plan: &HoldPlan,
    axis: Axis,
    fraction: f64,
    load: f64,
    noise: &mut Noise,
) -> HoldRow {
    let c = creep(rig, plan, axis, load);
    let (normal, ft, mn) = timed::recorded(noise, plan.frame.normal_n, axis, load);
    HoldRow {
        axis,
        normal_force_n: normal,
        fraction,
        tangential_force_n: ft,
        torsional_moment_nm: mn,
        time_s: c.time_s,
        slide_m: noise.apply(c.end.slide_since(&c.start), 0.0).abs(),
        turn_rad: noise.apply(c.end.turn_since(&c.start), 0.0).abs(),
        slide_rate_m_s: noise
            .apply(c.end.slide_since(&c.late) / c.window_s, 0.0)
            .abs(),
        turn_rate_rad_s: noise
            .apply(c.end.turn_since(&c.late) / c.window_s, 0.0)
            .abs(),
    }
}
