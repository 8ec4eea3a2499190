//! The benchmark's scene families: generators of random grasp trials with documented
//! ranges. Every trial is drawn from the bench seed, the family and the trial's index
//! (a ChaCha stream of its own), so the same seed gives the same trials.
//!
//! Each trial draws its own fingertip ([`super::trial_finger`]: by default a brush
//! finger, a physical plant softgrip does not model), measures it in the lab and
//! calibrates every controller from those same rows ([`super::lab`]); no controller
//! reads the plant. All trials share softgrip's default limits ([`N_MIN_N`], [`N_MAX_N`]),
//! at 1 kHz.
//!
//! The families, their load phases, effects and ranges (uniform draws, [`Ranges`]), the
//! `mu-mismatch` family's slip sensor and the `--hard` ranges ([`Ranges::hard`]) are
//! tabled in docs/bench.md, "What a trial is".

use super::lab::{self, Beliefs};
use super::onset_table::OnsetTable;
use super::oracle::TrueLimit;
use super::trial_finger::{FingerSource, TrialFinger};
use crate::sim::run as sim_run;
use crate::sim::scene::Scene;
use crate::sim::truth::Truth;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;

/// The families `--family all` runs, in order.
pub const NAMES: [&str; 5] = ["lift-hold", "shake", "twist", "mu-mismatch", "faults"];

/// The least command of every trial \[N\] (softgrip's default).
pub const N_MIN_N: f64 = 0.2;
/// The greatest command of every trial \[N\] (softgrip's default).
pub const N_MAX_N: f64 = 20.0;

/// The ranges the families draw from, and what the controllers are told.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Ranges {
    /// The harder ranges (`--hard`).
    pub hard: bool,
    /// Tell the controllers the shake family's actuator (`actuator_lag_s`,
    /// `actuator_slew_n_per_s`); by default they are not told.
    pub tell_actuator: bool,
}

/// One generated trial.
#[derive(Clone)]
pub struct Trial {
    /// Family name.
    pub family: &'static str,
    /// Index within the family.
    pub index: usize,
    /// The scene (its `seed` seeds the effects).
    pub scene: Scene,
    /// The scene as TOML, for traces and error messages.
    pub text: String,
    /// What every controller believes, from the lab.
    pub beliefs: Beliefs,
    /// The finger's true static μ over the one the lab measured [-].
    pub mu_ratio: f64,
    /// Whether the scene lists the slip sensor.
    pub sensor: bool,
    /// The true limit the oracle asks.
    pub limit: Arc<dyn TrueLimit + Send + Sync>,
    /// The limit-surface ground truth the run loop is given (the plant itself on the
    /// `fls` plant; on the brush plant only the run's bookkeeping reads it).
    pub truth: Arc<Truth>,
}

impl std::fmt::Debug for Trial {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Trial")
            .field("family", &self.family)
            .field("index", &self.index)
            .field("text", &self.text)
            .finish()
    }
}

/// The random stream of trial `index` of `family` under `seed`.
fn rng(seed: u64, family: &str, index: usize) -> ChaCha8Rng {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in family.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    let mut r = ChaCha8Rng::seed_from_u64(seed ^ h);
    r.set_stream(index as u64);
    r
}

/// What a family's generator draws besides the finger: the scene's text after the
/// `[finger]` table, whether it lists the slip sensor, the true μ ratio.
struct Load {
    text: String,
    sensor: bool,
    mu_ratio: f64,
}

fn header(duration_s: f64, seed: u64, effects: &[&str]) -> String {
    let list: Vec<String> = effects.iter().map(|e| format!("\"{e}\"")).collect();
    format!(
        "duration_s = {duration_s}\ntick_hz = 1000.0\nseed = {seed}\neffects = [{}]\n\n",
        list.join(", ")
    )
}

fn object(mass: f64, com: f64, inertia: Option<f64>) -> String {
    // By default a body about 30 mm in radius of gyration.
    let inertia = inertia.unwrap_or(mass * 0.03 * 0.03);
    format!("[object]\nmass_kg = {mass:?}\ncom_offset_m = {com:?}\ninertia_kg_m2 = {inertia:?}\n\n")
}

fn lift(start: f64, end: f64, accel: f64) -> String {
    format!(
        "[[task]]\nkind = \"lift\"\nstart_s = {start:?}\nend_s = {end:?}\naccel_m_s2 = {accel:?}\n\n"
    )
}

/// The `[controller]` table: what softgrip and the baselines believe, from the lab, and
/// `extra` lines.
fn controller(b: &Beliefs, extra: &str) -> String {
    format!(
        "[controller]\nmu = {:?}\nk = {:?}\nc_m_per_n_gamma = {:?}\ngamma = {:?}\n\
         half_length_m = {:?}\nn_min_n = {N_MIN_N:?}\nn_max_n = {N_MAX_N:?}\n\
         baseline_mu = {:?}\nbaseline_torsion_arm_m = {:?}\n{extra}",
        b.mu, b.k, b.c, b.gamma, b.half_length_m, b.cone_mu, b.torsion_arm_m
    )
}

/// Trial `index` of `family` under `seed`, its finger from `source`, or why it could not
/// be built (an unknown family, a finger the lab cannot calibrate).
pub fn trial_on(
    source: &FingerSource,
    ranges: &Ranges,
    family: &str,
    seed: u64,
    index: usize,
) -> Result<Trial, String> {
    let family: &'static str = NAMES
        .iter()
        .find(|n| **n == family)
        .ok_or_else(|| format!("no family \"{family}\""))?;
    let why = |e: String| format!("{family} trial {index} (seed {seed}): {e}");
    let mut r = rng(seed, family, index);
    let scene_seed: u64 = r.random();
    let finger = TrialFinger::draw(source, &mut r, N_MAX_N)
        .ok_or_else(|| why("no finger drawn carries N_max".into()))?;
    let lab_rig = finger.rig(N_MIN_N, N_MAX_N).map_err(why)?;
    let beliefs = lab::calibrate(
        &lab::measure(lab_rig.as_ref(), r.random()),
        finger.shape(),
        finger.half_length_m(),
    )
    .map_err(why)?;
    let capacity = 2.0
        * lab_rig
            .slip_onset(N_MAX_N, 0.0, 1e-3)
            .map_or(0.0, |(_, m)| m);
    let load = match family {
        "lift-hold" => lift_hold(&mut r, &beliefs),
        "shake" => shake(&mut r, &beliefs, ranges),
        "twist" => twist(&mut r, &beliefs, ranges, capacity),
        "mu-mismatch" => mu_mismatch(&mut r, &beliefs, ranges, index),
        _ => faults(&mut r, &beliefs),
    };
    let truth = finger.with_mu_scaled(load.mu_ratio);
    let text = header_for(family, scene_seed, &load.text)
        + &truth.toml((beliefs.k, beliefs.c, beliefs.gamma))
        + &load.text;
    let mut scene = Scene::parse(&text).map_err(|e| why(e.to_string()))?;
    scene.name = format!("{family}-{index}");
    let run_truth = Arc::new(sim_run::build_truth(&scene).map_err(why)?);
    let limit: Arc<dyn TrueLimit + Send + Sync> = match truth {
        TrialFinger::Brush { .. } => {
            let rig = truth.rig(N_MIN_N, N_MAX_N).map_err(why)?;
            Arc::new(OnsetTable::build(rig.as_ref(), N_MIN_N, N_MAX_N).map_err(why)?)
        }
        TrialFinger::Fls(_) => run_truth.clone(),
    };
    Ok(Trial {
        family,
        index,
        scene,
        text,
        beliefs,
        mu_ratio: load.mu_ratio,
        sensor: load.sensor,
        limit,
        truth: run_truth,
    })
}

/// The scene's top lines: duration and effects, by family (the load text says which
/// effects it configures).
fn header_for(family: &str, seed: u64, load: &str) -> String {
    let mut effects = vec!["gravity", "sensor_noise"];
    let duration = match family {
        "shake" => {
            effects.push("actuator");
            1.5
        }
        "twist" => 1.3,
        "faults" => {
            effects.extend(["sensor_faults", "link_latency", "link_faults"]);
            1.2
        }
        _ => 1.2,
    };
    if load.contains("[effect.slip_sensor]") {
        effects.push("slip_sensor");
    }
    header(duration, seed, &effects)
}

/// A `lift-hold` trial, drawn from `r`.
fn lift_hold(r: &mut ChaCha8Rng, b: &Beliefs) -> Load {
    let mass = r.random_range(0.05..=0.5);
    let com = r.random_range(0.0..=0.02);
    let accel = r.random_range(1.0..=5.0);
    Load {
        text: object(mass, com, None) + &lift(0.1, 0.6, accel) + &controller(b, ""),
        sensor: false,
        mu_ratio: 1.0,
    }
}

/// A `shake` trial, drawn from `r`.
fn shake(r: &mut ChaCha8Rng, b: &Beliefs, ranges: &Ranges) -> Load {
    let mass = r.random_range(0.05..=0.3);
    let com = r.random_range(0.0..=0.01);
    let (freq, tau) = if ranges.hard {
        (r.random_range(6.0..=15.0), r.random_range(0.02..=0.06))
    } else {
        (r.random_range(2.0..=8.0), r.random_range(0.005..=0.03))
    };
    let amp = r.random_range(2.0..=10.0);
    let slew = r.random_range(100.0..=500.0);
    let told = if ranges.tell_actuator {
        format!("actuator_lag_s = {tau:?}\nactuator_slew_n_per_s = {slew:?}\n")
    } else {
        String::new()
    };
    Load {
        text: object(mass, com, None)
            + &lift(0.05, 0.45, 2.0)
            + &format!(
                "[[task]]\nkind = \"shake\"\nstart_s = 0.5\nend_s = 1.5\n\
                 amplitude_m_s2 = {amp:?}\nfrequency_hz = {freq:?}\n\n\
                 [effect.actuator]\ntime_constant_s = {tau:?}\nslew_n_per_s = {slew:?}\n\
                 max_force_n = {N_MAX_N:?}\n\n"
            )
            + &controller(b, &told),
        sensor: false,
        mu_ratio: 1.0,
    }
}

/// A `twist` trial, drawn from `r`; `capacity_nm` is the grasp's torsion capacity at
/// `N_max` (two contacts).
fn twist(r: &mut ChaCha8Rng, b: &Beliefs, ranges: &Ranges, capacity_nm: f64) -> Load {
    let mass = r.random_range(0.02..=0.15);
    let com = r.random_range(0.0..=0.005);
    let share = if ranges.hard {
        r.random_range(0.8..=1.0)
    } else {
        r.random_range(0.05..=1.0)
    };
    // A fixed inertia about the grasp axis: the peak moment is I·α.
    let inertia = 2e-4;
    let moment = share * capacity_nm;
    Load {
        text: object(mass, com, Some(inertia))
            + &format!(
                "[[task]]\nkind = \"twist\"\nstart_s = 0.2\nend_s = 1.2\n\
                 angular_accel_rad_s2 = {:?}\n\n",
                moment / inertia
            )
            + &controller(b, ""),
        sensor: false,
        mu_ratio: 1.0,
    }
}

/// A `mu-mismatch` trial, drawn from `r`; trial `index` lists the slip sensor when odd.
fn mu_mismatch(r: &mut ChaCha8Rng, b: &Beliefs, ranges: &Ranges, index: usize) -> Load {
    let mass = r.random_range(0.05..=0.4);
    let com = r.random_range(0.0..=0.015);
    let accel = r.random_range(1.0..=4.0);
    let ratio = if ranges.hard {
        r.random_range(0.5..=1.0)
    } else {
        r.random_range(0.7..=1.3)
    };
    let sensor = index % 2 == 1;
    let threshold = r.random_range(0.2..=0.9);
    let latency = r.random_range(0.002..=0.02);
    let miss = r.random_range(0.0..=0.1);
    let false_rate = r.random_range(0.0..=1.0);
    let sensor_text = if sensor {
        format!(
            "[effect.slip_sensor]\nincipient_utilisation = {threshold:?}\nlatency_s = {latency:?}\n\
             miss_probability = {miss:?}\nfalse_alarm_rate_hz = {false_rate:?}\n\n"
        )
    } else {
        String::new()
    };
    Load {
        text: object(mass, com, None) + &lift(0.1, 0.6, accel) + &sensor_text + &controller(b, ""),
        sensor,
        mu_ratio: ratio,
    }
}

/// A `faults` trial, drawn from `r`.
fn faults(r: &mut ChaCha8Rng, b: &Beliefs) -> Load {
    let mass = r.random_range(0.05..=0.4);
    let com = r.random_range(0.0..=0.015);
    let accel = r.random_range(1.0..=4.0);
    let noise = r.random_range(0.01..=0.05);
    let dropout = r.random_range(0.0..=0.02);
    let nan = r.random_range(0.0..=0.01);
    let delay = r.random_range(0..=3u32);
    let flip = r.random_range(0.0..=0.02);
    let trunc = r.random_range(0.0..=0.01);
    let drop = r.random_range(0.0..=0.02);
    Load {
        text: object(mass, com, None)
            + &lift(0.1, 0.6, accel)
            + &format!(
                "[effect.sensor_noise]\nforce_sd_n = {noise:?}\nnormal_sd_n = {noise:?}\n\n\
                 [effect.sensor_faults]\ndropout_prob = {dropout:?}\nnan_prob = {nan:?}\n\n\
                 [effect.link_latency]\ndelay_ticks = {delay}\n\n\
                 [effect.link_faults]\nbit_flip_prob = {flip:?}\ntruncate_prob = {trunc:?}\n\
                 drop_prob = {drop:?}\n\n"
            )
            + &controller(b, ""),
        sensor: false,
        mu_ratio: 1.0,
    }
}
