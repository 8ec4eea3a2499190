//! When a device loop ticks its controller without a frame: one idle tick per tick period
//! that passes with no sensor frame, measured on the loop's own free-running timer.
//!
//! The loop owns the timer (TIM2 on the firmware, `Instant` on the host) and calls
//! [`Device::idle_ticks_due`] between reads, waiting at most
//! [`SilenceWatch::remaining`] counts for the next byte. The watch only does wrapping
//! arithmetic on the counts it is given, so it is the same code on the Cortex-M4F and the
//! host.

use super::{ControllerSource, Device, ForceActuator};
use crate::controller::TickMath;
use crate::protocol::Pacing;

/// The next idle deadline, in counts of the loop's timer (wrapping `u32`).
///
/// Unarmed until the device has a configuration (there is no controller to tick). A
/// sensor frame re-arms the deadline one tick period after it; each deadline that passes
/// without one is an idle tick, and the next deadline follows one period later, so a loop
/// that was busy for several periods runs the missed idle ticks one after the other (up
/// to [`SilenceWatch::MAX_BEHIND_PERIODS`]; beyond that the watch re-arms from now, which
/// only makes the fault come later, never sooner).
#[derive(Debug, Clone, Copy)]
pub struct SilenceWatch {
    timer_hz: f64,
    period_s: f64,
    period: u32,
    deadline: u32,
    ticks_seen: u32,
    armed: bool,
}

impl SilenceWatch {
    /// How many missed periods a late loop catches up on.
    pub const MAX_BEHIND_PERIODS: u32 = 64;

    /// An unarmed watch on a timer counting `timer_hz` per second.
    pub const fn new(timer_hz: f64) -> Self {
        Self {
            timer_hz,
            period_s: 0.0,
            period: 1,
            deadline: 0,
            ticks_seen: 0,
            armed: false,
        }
    }

    /// The tick period in timer counts for `tick_period_s` on a timer of `timer_hz`,
    /// rounded to the nearest count and kept within `[1, 2³⁰]` (so a deadline is never
    /// ambiguous on the wrapping 32-bit count).
    pub fn period_counts(tick_period_s: f64, timer_hz: f64) -> u32 {
        let counts = tick_period_s * timer_hz + 0.5;
        if counts >= f64::from(1u32 << 30) {
            1 << 30
        } else if counts >= 1.0 {
            counts as u32
        } else {
            // Also NaN.
            1
        }
    }

    /// Arms the watch for `tick_period_s` (first deadline one period after `now`), unless
    /// it is already armed for that period.
    pub fn arm(&mut self, tick_period_s: f64, now: u32, ticks: u32) {
        if self.armed && self.period_s == tick_period_s {
            return;
        }
        self.period_s = tick_period_s;
        self.period = Self::period_counts(tick_period_s, self.timer_hz);
        self.deadline = now.wrapping_add(self.period);
        self.ticks_seen = ticks;
        self.armed = true;
    }

    /// Back to unarmed: nothing is due until the next [`SilenceWatch::arm`].
    pub fn disarm(&mut self) {
        self.armed = false;
    }

    /// The tick period in timer counts (1 while unarmed).
    pub fn period(&self) -> u32 {
        self.period
    }

    /// Counts from `now` until the next deadline (0 when it has passed), `None` while
    /// unarmed: how long a loop may wait for the next byte.
    pub fn remaining(&self, now: u32) -> Option<u32> {
        if !self.armed {
            return None;
        }
        let ahead = self.deadline.wrapping_sub(now);
        Some(if ahead > u32::MAX / 2 { 0 } else { ahead })
    }

    /// Whether an idle tick is due at `now`, given the device's sensor tick count
    /// `ticks`: a sensor tick since the last call re-arms the deadline one period from
    /// `now` and nothing is due; otherwise a passed deadline is due, and the next one
    /// follows a period later.
    pub fn due(&mut self, now: u32, ticks: u32) -> bool {
        if !self.armed {
            return false;
        }
        if ticks != self.ticks_seen {
            self.ticks_seen = ticks;
            self.deadline = now.wrapping_add(self.period);
            return false;
        }
        let late = now.wrapping_sub(self.deadline);
        if late > u32::MAX / 2 {
            return false;
        }
        self.deadline =
            if late.checked_div(self.period).unwrap_or(u32::MAX) >= Self::MAX_BEHIND_PERIODS {
                now.wrapping_add(self.period)
            } else {
                self.deadline.wrapping_add(self.period)
            };
        true
    }
}

impl<M: TickMath<f32>, S: ControllerSource<M>> Device<M, S> {
    /// Runs every idle tick due at `now` (a count of the timer `watch` was made for),
    /// keeping `watch` armed for the running configuration's tick period, and returns how
    /// many ran (each drove `actuator`, see [`Device::idle_tick`]). Call it between reads,
    /// at least once per tick period; wait for bytes at most
    /// [`SilenceWatch::remaining`] counts. Before a configuration, and in
    /// [`Pacing::Lockstep`], it does nothing (and the watch is unarmed).
    pub fn idle_ticks_due<A: ForceActuator>(
        &mut self,
        watch: &mut SilenceWatch,
        now: u32,
        actuator: &mut A,
    ) -> u32 {
        let period_s = match (self.pacing, self.tick_period_s()) {
            (Pacing::RealTime, Some(p)) => p,
            _ => {
                watch.disarm();
                return 0;
            }
        };
        watch.arm(period_s, now, self.ticks);
        let mut ran = 0u32;
        while watch.due(now, self.ticks) {
            self.idle_tick(actuator);
            ran = ran.saturating_add(1);
        }
        ran
    }
}

#[cfg(test)]
mod tests {
    use super::SilenceWatch;

    #[test]
    fn one_idle_tick_per_silent_period_and_a_frame_rearms() {
        let start = u32::MAX - 150;
        let mut w = SilenceWatch::new(1e5);
        assert!(!w.due(start, 0), "unarmed");
        assert_eq!(w.remaining(start), None);
        w.arm(1e-3, start, 0);
        assert_eq!(w.period(), 100);
        let mut now = start;
        let mut idle = 0;
        // 1000 counts of silence across the wrap of the count: ten periods.
        for _ in 0..1000 {
            now = now.wrapping_add(1);
            idle += u32::from(w.due(now, 0));
        }
        assert_eq!(idle, 10);
        // Arming again for the same period changes nothing.
        w.arm(1e-3, now.wrapping_add(50), 0);
        assert_eq!(w.remaining(now), Some(100));
        // A sensor tick re-arms: nothing for one period after it.
        assert!(!w.due(now, 1));
        assert_eq!(w.remaining(now), Some(100));
        assert!(!w.due(now.wrapping_add(99), 1));
        assert!(w.due(now.wrapping_add(100), 1));
        // A loop that was away for three periods catches up, one tick per call.
        let back = now.wrapping_add(400);
        assert_eq!(w.remaining(back), Some(0));
        assert!(w.due(back, 1));
        assert!(w.due(back, 1));
        assert!(w.due(back, 1));
        assert!(!w.due(back, 1));
        assert_eq!(w.remaining(back), Some(100));
        // Away for far longer: re-armed from now rather than a burst of idle ticks.
        let much_later = back.wrapping_add(100 * 1000);
        assert!(w.due(much_later, 1));
        assert!(!w.due(much_later, 1));
        w.disarm();
        assert!(!w.due(much_later.wrapping_add(1000), 1));
    }

    #[test]
    fn period_counts_are_bounded() {
        assert_eq!(SilenceWatch::period_counts(1e-3, 1e9), 1_000_000);
        assert_eq!(SilenceWatch::period_counts(1e-3, 16e6), 16_000);
        assert_eq!(SilenceWatch::period_counts(f64::NAN, 1e9), 1);
        assert_eq!(SilenceWatch::period_counts(1e9, 1e9), 1 << 30);
    }
}
