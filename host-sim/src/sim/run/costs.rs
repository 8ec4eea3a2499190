//! What a run's steps cost in wall-clock time, unless the run is untimed (the clock is
//! read about ten times a tick).

use std::time::{Duration, Instant};

/// A run's step costs so far.
#[derive(Debug, Default)]
pub(super) struct Costs {
    /// Skip the clock: every duration stays zero.
    untimed: bool,
    /// The plant's own step, the effects left out.
    pub(super) core: Duration,
    /// The controller and the link.
    pub(super) control: Duration,
    /// The brush plant's step (pressure solve, sub-steps).
    pub(super) brush: Duration,
    /// The brush plant's sub-steps.
    pub(super) brush_substeps: u64,
}

impl Costs {
    /// Nothing spent yet; nothing ever if `untimed`.
    pub(super) fn new(untimed: bool) -> Self {
        Costs {
            untimed,
            ..Costs::default()
        }
    }

    /// Reads the clock unless untimed.
    pub(super) fn start(&self) -> Option<Instant> {
        (!self.untimed).then(Instant::now)
    }

    /// The time since `start`, zero when untimed.
    pub(super) fn since(start: Option<Instant>) -> Duration {
        start.map_or(Duration::ZERO, |s| s.elapsed())
    }
}
