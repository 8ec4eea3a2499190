//! What a simulation run records: one [`Sample`] per tick and a [`RunSummary`] per run.

use serde::Serialize;
use std::collections::BTreeMap;

/// One tick of one run. Loads are per contact (each of the two fingertips of the pinch).
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Sample {
    /// Simulated time \[s\].
    pub t_s: f64,
    /// True tangential load magnitude on the contact \[N\].
    pub ft_n: f64,
    /// True torsional moment on the contact [N·m].
    pub mn_nm: f64,
    /// Measured tangential force magnitude as the controller saw it \[N\] (NaN if the frame
    /// carried no usable value).
    pub ft_meas_n: f64,
    /// Measured torsional moment [N·m] (NaN likewise).
    pub mn_meas_nm: f64,
    /// The controller's command \[N\].
    pub n_cmd_n: f64,
    /// The normal force the actuator actually applies \[N\].
    pub n_true_n: f64,
    /// True contact half-width \[m\].
    pub a_true_m: f64,
    /// True `f̃ = f_t/(μN)`.
    pub f_norm: f64,
    /// True `m̃ = m_n/(μNa)`.
    pub m_norm: f64,
    /// Pitch of the true contact's surface at its present aspect.
    pub pitch: f64,
    /// True utilisation (≥ 1: the load is outside the true limit surface).
    pub utilisation: f64,
    /// Whether the contact is sliding this tick.
    pub slipping: bool,
    /// Cumulative slip distance \[m\].
    pub slip_distance_m: f64,
    /// Cumulative slip rotation \[rad\].
    pub slip_rotation_rad: f64,
    /// The controller's status name (`ok`, `saturated`, ..., or `none` for baselines and
    /// lost replies).
    pub status: &'static str,
}

/// The serial link's accounting for a run (all zero for controllers run in-process).
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub struct LinkSummary {
    /// Sensor frames the plant sent (or meant to send).
    pub frames_sent: u64,
    /// Frames the device decoded.
    pub frames_received: u64,
    /// Frames the device counted as corrupt (CRC, decode) or oversized.
    pub frames_corrupt: u64,
    /// Frames that never reached the device (dropped on the line).
    pub frames_lost: u64,
    /// Ticks without a fresh command (the plant held the last one).
    pub commands_missing: u64,
}

/// One run: a scene against one controller.
#[derive(Debug, Clone, Serialize)]
pub struct RunSummary {
    /// Scene name.
    pub scene: String,
    /// Controller name.
    pub controller: String,
    /// Whether the object was dropped ([`crate::sim::run::is_drop`]: slid more than
    /// 10 mm or turned more than 0.2 rad;
    /// `host-sim/tests/bench.rs::a_drop_is_more_than_10_mm_or_0_2_rad`).
    pub dropped: bool,
    /// Number of separate slip episodes.
    pub slip_events: u64,
    /// Total slip distance \[m\].
    pub slip_distance_m: f64,
    /// Total slip rotation \[rad\].
    pub slip_rotation_rad: f64,
    /// Mean applied normal force \[N\].
    pub mean_normal_force_n: f64,
    /// Peak applied normal force \[N\].
    pub peak_normal_force_n: f64,
    /// Whether the scene is an overload that no allowed force can hold.
    pub expected_slip: bool,
    /// Largest true utilisation.
    pub max_utilisation: f64,
    /// Ticks simulated.
    pub ticks: u64,
    /// Simulated duration \[s\].
    pub duration_s: f64,
    /// Wall-clock time of the run \[s\].
    pub wall_s: f64,
    /// Simulated seconds per wall second.
    pub real_time_factor: f64,
    /// Link accounting.
    pub link: LinkSummary,
    /// Each enabled effect's share of the plant's step cost, and `"core"` for the rest
    /// (ground truth and bookkeeping), summing to 1.
    pub step_cost_share: BTreeMap<String, f64>,
    /// The effects the scene enabled, in pipeline order.
    pub effects: Vec<String>,
    /// Further figures: `plant_step_s` and `controller_and_link_s` (wall time in the plant
    /// step and in the controller with its link), and effect metrics such as
    /// `max_micro_slip_m` (partial slip).
    pub metrics: BTreeMap<String, f64>,
}
