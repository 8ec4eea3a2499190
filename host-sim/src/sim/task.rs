//! The task: what the hand does with the object, as loads over time. Phases add up where
//! they overlap. These are the scene's own loads, not effects: every scene has them.

use crate::sim::effects::World;
use crate::sim::scene::{Phase, Scene};

fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// The part of the object's weight the grasp carries at `t`: 0 before the first lift
/// (the object rests on its support), rising smoothly over the first 20 % of that lift,
/// then 1. Without a lift phase the grasp carries it all along.
pub fn support_fraction(scene: &Scene, t_s: f64) -> f64 {
    match scene.task.iter().find(|p| matches!(p, Phase::Lift { .. })) {
        Some(p) => {
            let (start_s, end_s) = p.span_s();
            smoothstep((t_s - start_s) / (0.2 * (end_s - start_s)))
        }
        None => 1.0,
    }
}

/// Adds the task's loads at `w.t_s` to `w`: the inertial force of lifting and shaking
/// (`m·a`, vertical), the inertial moment of twisting (`I·α`), and external pulls.
pub fn apply(scene: &Scene, w: &mut World) {
    let t = w.t_s;
    for p in &scene.task {
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
