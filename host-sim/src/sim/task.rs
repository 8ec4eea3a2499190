//! The task: its load phases (a scene's `[[task]]` tables, [`Phase`]) and what the hand does
//! with the object, as loads over time. Phases add up where they overlap. These are the
//! scene's own loads, not effects: every scene has them.

use crate::sim::effects::World;
use serde::Deserialize;

/// One load phase, active on `[start_s, end_s)`: a `[[task]]` table whose `kind` picks the
/// variant, with that kind's keys only (an unknown kind, or another kind's key, is refused
/// by name and line). A kind's own loads default to 0.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
pub enum Phase {
    /// Lift: a smooth accelerate–decelerate bump upward, `a = A·sin(2πx)`.
    Lift {
        /// Start \[s\].
        start_s: f64,
        /// End \[s\].
        end_s: f64,
        /// Peak upward acceleration [m/s²].
        #[serde(default)]
        accel_m_s2: f64,
    },
    /// Hold: no load of its own.
    Hold {
        /// Start \[s\].
        start_s: f64,
        /// End \[s\].
        end_s: f64,
    },
    /// Twist: a smooth accelerate–decelerate turn about the grasp axis.
    Twist {
        /// Start \[s\].
        start_s: f64,
        /// End \[s\].
        end_s: f64,
        /// Peak angular acceleration [rad/s²].
        #[serde(default)]
        angular_accel_rad_s2: f64,
    },
    /// Shake: a vertical sinusoidal acceleration.
    Shake {
        /// Start \[s\].
        start_s: f64,
        /// End \[s\].
        end_s: f64,
        /// Acceleration amplitude [m/s²].
        #[serde(default)]
        amplitude_m_s2: f64,
        /// Frequency \[Hz\].
        #[serde(default)]
        frequency_hz: f64,
    },
    /// Pull: an external force along the cylinder axis and a twisting moment, ramped in
    /// smoothly at the start of the phase ([`apply`]).
    Pull {
        /// Start \[s\].
        start_s: f64,
        /// End \[s\].
        end_s: f64,
        /// The force \[N\].
        #[serde(default)]
        force_n: f64,
        /// The moment [N·m].
        #[serde(default)]
        moment_nm: f64,
    },
}

impl Phase {
    /// The kind's name, as the scene spells it.
    pub fn kind(&self) -> &'static str {
        match self {
            Phase::Lift { .. } => "lift",
            Phase::Hold { .. } => "hold",
            Phase::Twist { .. } => "twist",
            Phase::Shake { .. } => "shake",
            Phase::Pull { .. } => "pull",
        }
    }

    /// `[start_s, end_s)` \[s\].
    pub fn span_s(&self) -> (f64, f64) {
        match *self {
            Phase::Lift { start_s, end_s, .. }
            | Phase::Hold { start_s, end_s }
            | Phase::Twist { start_s, end_s, .. }
            | Phase::Shake { start_s, end_s, .. }
            | Phase::Pull { start_s, end_s, .. } => (start_s, end_s),
        }
    }

    /// Every number of the phase (for the scene's finiteness check).
    pub fn values(&self) -> Vec<f64> {
        let (start_s, end_s) = self.span_s();
        let own = match *self {
            Phase::Lift { accel_m_s2, .. } => vec![accel_m_s2],
            Phase::Hold { .. } => vec![],
            Phase::Twist {
                angular_accel_rad_s2,
                ..
            } => vec![angular_accel_rad_s2],
            Phase::Shake {
                amplitude_m_s2,
                frequency_hz,
                ..
            } => vec![amplitude_m_s2, frequency_hz],
            Phase::Pull {
                force_n, moment_nm, ..
            } => vec![force_n, moment_nm],
        };
        [start_s, end_s].into_iter().chain(own).collect()
    }
}

fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// The part of the object's weight the grasp carries at `t`: 0 before the first lift
/// (the object rests on its support), rising smoothly over the start of that lift, then
/// 1. Without a lift phase the grasp carries it all along.
pub fn support_fraction(task: &[Phase], t_s: f64) -> f64 {
    match task.iter().find(|p| matches!(p, Phase::Lift { .. })) {
        Some(p) => {
            let (start_s, end_s) = p.span_s();
            smoothstep((t_s - start_s) / (0.2 * (end_s - start_s)))
        }
        None => 1.0,
    }
}

/// Adds the task's loads at `w.t_s` to `w`: the inertial force of lifting and shaking
/// (`m·a`, vertical), the inertial moment of twisting (`I·α`), and external pulls.
pub fn apply(task: &[Phase], w: &mut World) {
    let t = w.t_s;
    for p in task {
        let (start_s, end_s) = p.span_s();
        if !(t >= start_s && t < end_s) {
            continue;
        }
        let x = (t - start_s) / (end_s - start_s);
        let two_pi = std::f64::consts::TAU;
        match *p {
            // Accelerate, then decelerate to rest: a = A·sin(2πx).
            Phase::Lift { accel_m_s2, .. } => {
                w.force_n[1] += w.mass_kg * accel_m_s2 * (two_pi * x).sin()
            }
            Phase::Twist {
                angular_accel_rad_s2,
                ..
            } => w.moment_nm += w.inertia_kg_m2 * angular_accel_rad_s2 * (two_pi * x).sin(),
            Phase::Shake {
                amplitude_m_s2,
                frequency_hz,
                ..
            } => {
                w.force_n[1] +=
                    w.mass_kg * amplitude_m_s2 * (two_pi * frequency_hz * (t - start_s)).sin()
            }
            Phase::Pull {
                force_n, moment_nm, ..
            } => {
                let ramp = smoothstep(x / 0.1);
                w.force_n[0] += force_n * ramp;
                w.moment_nm += moment_nm * ramp;
            }
            Phase::Hold { .. } => {}
        }
    }
}
