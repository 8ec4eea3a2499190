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
    /// What softgrip's command is made of: the CSV's last columns, written inline
    /// ([`CommandParts::NONE`], all NaN, for baselines and ticks without a reply).
    pub parts: CommandParts,
}

/// What softgrip's command is made of on one tick ([`Sample::parts`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CommandParts {
    /// softgrip's `N_slip` at `μ̂`, as its reply says \[N\].
    pub n_slip_n: f32,
    /// softgrip's `N_req` at the safety factor times `margin`, at `μ̂` \[N\]: derived on the
    /// host from the answered frame's load (the reply does not carry it).
    pub required_n: f32,
    /// softgrip's friction estimate `μ̂` \[-\].
    pub mu_hat: f32,
    /// softgrip's margin on the safety factor, `slip_margin · load_factor` \[-\].
    pub margin: f32,
    /// The slip response's part of `margin` \[-\]: `margin / load_factor`.
    pub slip_margin: f32,
    /// The load's part of `margin` \[-\]: the cyclic factor while the load cycles, the
    /// steady factor (≤ 1) on a steady hold, else 1.
    pub load_factor: f32,
    /// How far softgrip's target leads `min(required_n, N_max)` for the actuator's lag \[N\].
    pub lead_n: f32,
    /// `N_slip` at the configured `μ` \[N\]: the force plot's first band (derived).
    pub n_slip_mu_n: f32,
    /// `N_req` at the safety factor alone, at the configured `μ` \[N\] (derived).
    pub n_safety_n: f32,
    /// `N_req` at the safety factor times `load_factor`, at the configured `μ` \[N\]
    /// (derived).
    pub n_load_n: f32,
}

impl CommandParts {
    /// No parts: a baseline's tick, or one without a reply.
    pub const NONE: Self = Self {
        n_slip_n: f32::NAN,
        required_n: f32::NAN,
        mu_hat: f32::NAN,
        margin: f32::NAN,
        slip_margin: f32::NAN,
        load_factor: f32::NAN,
        lead_n: f32::NAN,
        n_slip_mu_n: f32::NAN,
        n_safety_n: f32::NAN,
        n_load_n: f32::NAN,
    };
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
