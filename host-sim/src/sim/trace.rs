//! What `simulate` keeps of a run for its plots, in memory bounded by a constant whatever
//! the run's length: the CSV gets every tick as it is produced, the plots get a
//! [`PlotTrace`].
//!
//! - **Samples** (docs/decisions/simulate-bounded-memory.md): at most [`MAX_TRACE_SAMPLES`]
//!   (16 384 of 176 bytes: 2.9 MB), every `stride`-th tick
//!   plus the last. The stride starts at 1 and doubles whenever the buffer fills (every
//!   other kept sample is dropped), so a run of up to 16 384 ticks is kept whole and a
//!   longer one at a uniform stride of at most twice `ticks/16 384`. The plots draw at most
//!   4 000 line points and 2 000 slip markers per run anyway (`report.rs`), so runs of up to
//!   16 384 ticks plot exactly as before; longer runs miss the peaks and slip ticks that
//!   fall between kept samples.
//! - **Slip intervals** (the slip bars of the force plot) are taken from every tick, so no
//!   episode is missed; at most [`MAX_SLIP_INTERVALS`] are kept, merging the closest ones
//!   when there would be more (the plot merges those closer than 1/1000 of its time axis
//!   anyway).
//!
//! Why these bounds: docs/decisions/simulate-bounded-memory.md; `host-sim/tests/bounded_cli.rs`
//! checks them.

use super::record::Sample;

/// Most samples a [`PlotTrace`] keeps.
pub const MAX_TRACE_SAMPLES: usize = 16_384;
/// Most slip intervals a [`PlotTrace`] keeps.
pub const MAX_SLIP_INTERVALS: usize = 4_096;

/// A bounded record of one run for plotting (see the module docs).
#[derive(Debug, Clone)]
pub struct PlotTrace {
    samples: Vec<Sample>,
    stride: u64,
    seen: u64,
    last: Option<Sample>,
    slips: Vec<(f64, f64)>,
    slip_start: Option<f64>,
    merge_gap_s: f64,
}

impl Default for PlotTrace {
    fn default() -> Self {
        Self::new()
    }
}

impl PlotTrace {
    /// An empty trace.
    pub fn new() -> Self {
        Self {
            samples: Vec::new(),
            stride: 1,
            seen: 0,
            last: None,
            slips: Vec::new(),
            slip_start: None,
            merge_gap_s: 0.0,
        }
    }

    /// Records the next tick's sample.
    pub fn push(&mut self, s: &Sample) {
        if self.seen.is_multiple_of(self.stride) {
            if self.samples.len() == MAX_TRACE_SAMPLES {
                // Keep the ticks that are multiples of twice the stride.
                let mut i = 0;
                self.samples.retain(|_| {
                    i += 1;
                    (i - 1) % 2 == 0
                });
                self.stride *= 2;
            }
            if self.seen.is_multiple_of(self.stride) {
                self.samples.push(*s);
            }
        }
        self.seen += 1;
        self.last = Some(*s);
        if s.t_s.is_finite() {
            match (s.slipping, self.slip_start) {
                (true, None) => self.slip_start = Some(s.t_s),
                (false, Some(t0)) => {
                    self.add_slip(t0, s.t_s);
                    self.slip_start = None;
                }
                _ => {}
            }
        }
    }

    fn add_slip(&mut self, t0: f64, t1: f64) {
        match self.slips.last_mut() {
            Some(prev) if t0 - prev.1 <= self.merge_gap_s => prev.1 = prev.1.max(t1),
            _ => self.slips.push((t0, t1)),
        }
        while self.slips.len() > MAX_SLIP_INTERVALS {
            let least = self
                .slips
                .windows(2)
                .map(|w| w[1].0 - w[0].1)
                .fold(f64::INFINITY, f64::min);
            self.merge_gap_s = (2.0 * self.merge_gap_s).max(least);
            let gap = self.merge_gap_s;
            let mut merged: Vec<(f64, f64)> = Vec::with_capacity(self.slips.len());
            for &(a, b) in &self.slips {
                match merged.last_mut() {
                    Some(prev) if a - prev.1 <= gap => prev.1 = prev.1.max(b),
                    _ => merged.push((a, b)),
                }
            }
            self.slips = merged;
        }
    }

    /// The kept samples, in time order, the run's last sample included.
    pub fn samples(&self) -> Vec<Sample> {
        let mut out = self.samples.clone();
        if let Some(last) = self.last {
            if !(self.seen - 1).is_multiple_of(self.stride) {
                out.push(last);
            }
        }
        out
    }

    /// The slip intervals: from the first slipping tick of an episode to the tick after
    /// its last (or the run's last tick), merged as the module docs say.
    pub fn slip_intervals(&self) -> Vec<(f64, f64)> {
        let mut out = self.slips.clone();
        if let (Some(t0), Some(last)) = (self.slip_start, self.last) {
            match out.last_mut() {
                Some(prev) if t0 - prev.1 <= self.merge_gap_s => prev.1 = prev.1.max(last.t_s),
                _ => out.push((t0, last.t_s)),
            }
        }
        out
    }

    /// The ticks recorded.
    pub fn ticks(&self) -> u64 {
        self.seen
    }

    /// The present stride between kept samples \[ticks\].
    pub fn stride(&self) -> u64 {
        self.stride
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::record::CommandParts;

    fn sample(k: u64, slipping: bool) -> Sample {
        Sample {
            t_s: k as f64 * 1e-3,
            ft_n: 0.0,
            mn_nm: 0.0,
            ft_meas_n: 0.0,
            mn_meas_nm: 0.0,
            n_cmd_n: 0.0,
            n_true_n: k as f64,
            a_true_m: 0.0,
            f_norm: 0.0,
            m_norm: 0.0,
            pitch: 1.0,
            utilisation: 0.0,
            slipping,
            slip_distance_m: 0.0,
            slip_rotation_rad: 0.0,
            status: "ok",
            parts: CommandParts::NONE,
        }
    }

    #[test]
    fn short_runs_are_kept_whole() {
        let mut t = PlotTrace::new();
        for k in 0..1000 {
            t.push(&sample(k, k % 100 < 3));
        }
        let s = t.samples();
        assert_eq!(s.len(), 1000);
        assert_eq!(t.slip_intervals().len(), 10);
        assert_eq!(t.slip_intervals()[1], (100.0 * 1e-3, 103.0 * 1e-3));
    }

    #[test]
    fn long_runs_stay_bounded_at_a_uniform_stride_with_every_slip() {
        let mut t = PlotTrace::new();
        let n = 1_000_003u64;
        for k in 0..n {
            // A one-tick slip every 10 000 ticks: the decimated samples miss most of them.
            t.push(&sample(k, k % 10_000 == 5));
        }
        let s = t.samples();
        assert!(s.len() <= MAX_TRACE_SAMPLES + 1, "{}", s.len());
        assert!(s.len() > MAX_TRACE_SAMPLES / 2);
        let stride = t.stride();
        assert!(stride.is_power_of_two() && stride >= n / MAX_TRACE_SAMPLES as u64);
        for w in s[..s.len() - 1].windows(2) {
            assert_eq!(w[1].n_true_n - w[0].n_true_n, stride as f64);
        }
        assert_eq!(s.last().unwrap().n_true_n, (n - 1) as f64);
        assert_eq!(t.slip_intervals().len(), 100);
    }

    #[test]
    fn slip_intervals_are_bounded_by_merging() {
        let mut t = PlotTrace::new();
        for k in 0..40_000 {
            t.push(&sample(k, k % 2 == 0));
        }
        let v = t.slip_intervals();
        assert!(v.len() <= MAX_SLIP_INTERVALS && !v.is_empty());
        assert_eq!(v[0].0, 0.0);
        assert!((v.last().unwrap().1 - 39.999).abs() < 1e-9);
    }
}
