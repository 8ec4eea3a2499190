//! The benchmark's scene families: generators of random grasp trials with documented
//! ranges. Every trial is drawn from the bench seed, the family and the trial's index
//! (a ChaCha stream of its own), so the same seed gives the same trials.
//!
//! All families share one fingertip ([`BenchFinger`]): by default that of the shipped
//! scenes (a hemicylinder, `k = 2`, `μ = 0.8`, `a = 2.5e-3·N^0.5` m, half-length 10 mm),
//! or a finger file's (`bench --finger`, e.g. `calibrate --out`'s). They share softgrip's
//! default limits (`N_min = 0.2` N, `N_max = 20` N), at 1 kHz, and last 1.2 to 1.5 s. The
//! finger's `μ` is the one every controller believes; the `mu-mismatch` family scales
//! the true one.
//!
//! | family | load | ranges (uniform) | effects |
//! | --- | --- | --- | --- |
//! | `lift-hold` | lift (0.1–0.6 s) then hold | mass 0.05–0.5 kg, COM offset 0–20 mm, peak lift acceleration 1–5 m/s² | gravity, sensor noise |
//! | `shake` | lift at 2 m/s², then shake (0.5–1.5 s) | mass 0.05–0.3 kg, COM offset 0–10 mm, 2–8 Hz, 2–10 m/s², actuator time constant 5–30 ms, slew 100–500 N/s (softgrip is told both) | gravity, sensor noise, actuator |
//! | `twist` | twist about the grasp axis (0.2–1.2 s) | peak moment 5–100 % of the grasp's torsion capacity at `N_max` (two contacts), mass 0.02–0.15 kg, COM offset 0–5 mm | gravity, sensor noise |
//! | `mu-mismatch` | as `lift-hold` | true μ = believed μ (0.8) × U(0.7, 1.3), mass 0.05–0.4 kg, COM 0–15 mm, lift 1–4 m/s²; every other trial lists the slip sensor | gravity, sensor noise, (slip sensor) |
//! | `faults` | as `lift-hold` | mass 0.05–0.4 kg, COM 0–15 mm, lift 1–4 m/s²; noise 0.01–0.05 N; dropouts 0–2 %, NaN 0–1 %; link delay 0–3 ticks, bit flips 0–2 %, truncation 0–1 %, drops 0–2 % | gravity, sensor noise and faults, link latency and faults |

use crate::sim::scene::Scene;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use softgrip::controller::FingerShape;

/// The families `--family all` runs, in order.
pub const NAMES: [&str; 5] = ["lift-hold", "shake", "twist", "mu-mismatch", "faults"];

/// The friction coefficient softgrip and the baselines believe by default [-].
pub const BELIEVED_MU: f64 = 0.8;

/// The fingertip of every trial: the truth's (`mu-mismatch` aside, whose true μ is this
/// μ scaled) and what every controller believes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BenchFinger {
    /// Hemicylinder (`rect`) or hemisphere (`disc`).
    pub shape: FingerShape,
    /// Pressure exponent `k ≥ 1`.
    pub k: f64,
    /// Friction coefficient [-].
    pub mu: f64,
    /// `c` in `a = c·N^γ` [m/N^γ].
    pub c: f64,
    /// `γ` in `a = c·N^γ`.
    pub gamma: f64,
    /// Half-length `l` of the rectangular patch [m].
    pub half_length_m: f64,
}

impl Default for BenchFinger {
    /// The shipped scenes' finger.
    fn default() -> Self {
        Self {
            shape: FingerShape::Rect,
            k: 2.0,
            mu: BELIEVED_MU,
            c: 2.5e-3,
            gamma: 0.5,
            half_length_m: 0.01,
        }
    }
}
/// The greatest command of every trial [N] (softgrip's default).
pub const N_MAX_N: f64 = 20.0;

/// One generated trial.
#[derive(Debug, Clone)]
pub struct Trial {
    /// Family name.
    pub family: &'static str,
    /// Index within the family.
    pub index: usize,
    /// The scene (its `seed` seeds the effects).
    pub scene: Scene,
    /// The scene as TOML, for traces and error messages.
    pub text: String,
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

/// The torsion capacity of the two-contact grasp on `finger` at `n_n` [N·m]:
/// `2·μ·N·a(N)·pitch`, with the pitch of the symmetric patch at that aspect.
pub fn grasp_torsion_capacity_nm(finger: &BenchFinger, n_n: f64) -> f64 {
    let a = finger.c * n_n.powf(finger.gamma);
    let pitch = softgrip::FlsModel::<f64>::new(softgrip::FlsConfig {
        shape: match finger.shape {
            FingerShape::Rect => softgrip::Shape::Rect {
                aspect: finger.half_length_m / a,
            },
            FingerShape::Disc => softgrip::Shape::Disc,
        },
        k: finger.k,
        skew: None,
        order: softgrip::QuadratureOrder::DEFAULT,
    })
    .map(|m| m.pitch())
    .unwrap_or(0.0);
    2.0 * finger.mu * n_n * a * pitch
}

#[allow(clippy::too_many_arguments)]
fn header(
    f: &BenchFinger,
    duration_s: f64,
    seed: u64,
    effects: &[&str],
    true_mu: f64,
    mass: f64,
    com: f64,
) -> String {
    let list: Vec<String> = effects.iter().map(|e| format!("\"{e}\"")).collect();
    format!(
        "duration_s = {duration_s}\ntick_hz = 1000.0\nseed = {seed}\neffects = [{}]\n\n\
         [finger]\nshape = \"{}\"\nk = {:?}\nmu = {true_mu:?}\nc = {:?}\ngamma = {:?}\n\
         half_length_m = {:?}\n\n\
         [object]\nmass_kg = {mass:?}\ncom_offset_m = {com:?}\ninertia_kg_m2 = {:?}\n\n",
        list.join(", "),
        f.shape.name(),
        f.k,
        f.c,
        f.gamma,
        f.half_length_m,
        // A body about 30 mm in radius of gyration.
        mass * 0.03 * 0.03,
    )
}

fn lift(start: f64, end: f64, accel: f64) -> String {
    format!(
        "[[task]]\nkind = \"lift\"\nstart_s = {start:?}\nend_s = {end:?}\naccel_m_s2 = {accel:?}\n\n"
    )
}

/// Why no scene accepts `finger`: the scene parser's error on a trial's text (a value out
/// of range names its `finger.` key).
pub fn probe(finger: &BenchFinger) -> Result<(), String> {
    let text = header(finger, 1.0, 0, &[], finger.mu, 0.1, 0.0);
    Scene::parse(&text).map(|_| ()).map_err(|e| e.to_string())
}

/// Trial `index` of `family` under `seed` on the default finger, or `None` for an
/// unknown family.
pub fn trial(family: &str, seed: u64, index: usize) -> Option<Trial> {
    trial_on(&BenchFinger::default(), family, seed, index)
}

/// Trial `index` of `family` under `seed` on `finger`, or `None` for an unknown family
/// (or a finger no scene accepts).
pub fn trial_on(finger: &BenchFinger, family: &str, seed: u64, index: usize) -> Option<Trial> {
    let family: &'static str = NAMES.iter().find(|n| **n == family)?;
    let mut r = rng(seed, family, index);
    let scene_seed: u64 = r.random();
    let text = match family {
        "lift-hold" => lift_hold(finger, &mut r, scene_seed),
        "shake" => shake(finger, &mut r, scene_seed),
        "twist" => twist(finger, &mut r, scene_seed),
        "mu-mismatch" => mu_mismatch(finger, &mut r, scene_seed, index),
        "faults" => faults(finger, &mut r, scene_seed),
        _ => return None,
    };
    let mut scene = Scene::parse(&text).ok()?;
    scene.name = format!("{family}-{index}");
    Some(Trial {
        family,
        index,
        scene,
        text,
    })
}

/// A `lift-hold` trial's scene text, drawn from `r`.
fn lift_hold(f: &BenchFinger, r: &mut ChaCha8Rng, scene_seed: u64) -> String {
    let believed = f.mu;
    let mass = r.random_range(0.05..=0.5);
    let com = r.random_range(0.0..=0.02);
    let accel = r.random_range(1.0..=5.0);
    header(
        f,
        1.2,
        scene_seed,
        &["gravity", "sensor_noise"],
        believed,
        mass,
        com,
    ) + &lift(0.1, 0.6, accel)
        + &format!("[controller]\nmu = {believed:?}\n")
}

/// A `shake` trial's scene text, drawn from `r`.
fn shake(f: &BenchFinger, r: &mut ChaCha8Rng, scene_seed: u64) -> String {
    let believed = f.mu;
    let mass = r.random_range(0.05..=0.3);
    let com = r.random_range(0.0..=0.01);
    let freq = r.random_range(2.0..=8.0);
    let amp = r.random_range(2.0..=10.0);
    let tau = r.random_range(0.005..=0.03);
    let slew = r.random_range(100.0..=500.0);
    header(
        f,
        1.5,
        scene_seed,
        &["gravity", "sensor_noise", "actuator"],
        believed,
        mass,
        com,
    ) + &lift(0.05, 0.45, 2.0)
        + &format!(
            "[[task]]\nkind = \"shake\"\nstart_s = 0.5\nend_s = 1.5\n\
             amplitude_m_s2 = {amp:?}\nfrequency_hz = {freq:?}\n\n\
             [effect.actuator]\ntime_constant_s = {tau:?}\nslew_n_per_s = {slew:?}\n\
             max_force_n = {N_MAX_N:?}\n\n\
             [controller]\nmu = {believed:?}\nactuator_lag_s = {tau:?}\n\
             actuator_slew_n_per_s = {slew:?}\n"
        )
}

/// A `twist` trial's scene text, drawn from `r`.
fn twist(f: &BenchFinger, r: &mut ChaCha8Rng, scene_seed: u64) -> String {
    let believed = f.mu;
    let mass = r.random_range(0.02..=0.15);
    let com = r.random_range(0.0..=0.005);
    let share = r.random_range(0.05..=1.0);
    let inertia = 2e-4;
    let moment = share * grasp_torsion_capacity_nm(f, N_MAX_N);
    let mut t = header(
        f,
        1.3,
        scene_seed,
        &["gravity", "sensor_noise"],
        believed,
        mass,
        com,
    );
    // A fixed inertia about the grasp axis: the peak moment is I·α.
    t = t.replace(
        &format!("inertia_kg_m2 = {:?}", mass * 0.03 * 0.03),
        &format!("inertia_kg_m2 = {inertia:?}"),
    );
    t + &format!(
        "[[task]]\nkind = \"twist\"\nstart_s = 0.2\nend_s = 1.2\n\
         angular_accel_rad_s2 = {:?}\n\n[controller]\nmu = {believed:?}\n",
        moment / inertia
    )
}

/// A `mu-mismatch` trial's scene text, drawn from `r`; trial `index` lists the slip
/// sensor when odd.
fn mu_mismatch(f: &BenchFinger, r: &mut ChaCha8Rng, scene_seed: u64, index: usize) -> String {
    let believed = f.mu;
    let mass = r.random_range(0.05..=0.4);
    let com = r.random_range(0.0..=0.015);
    let accel = r.random_range(1.0..=4.0);
    let ratio = r.random_range(0.7..=1.3);
    let sensor = index % 2 == 1;
    let mut effects = vec!["gravity", "sensor_noise"];
    if sensor {
        effects.push("slip_sensor");
    }
    header(f, 1.2, scene_seed, &effects, believed * ratio, mass, com)
        + &lift(0.1, 0.6, accel)
        + &format!("[controller]\nmu = {believed:?}\n")
}

/// A `faults` trial's scene text, drawn from `r`.
fn faults(f: &BenchFinger, r: &mut ChaCha8Rng, scene_seed: u64) -> String {
    let believed = f.mu;
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
    header(
        f,
        1.2,
        scene_seed,
        &[
            "gravity",
            "sensor_noise",
            "sensor_faults",
            "link_latency",
            "link_faults",
        ],
        believed,
        mass,
        com,
    ) + &lift(0.1, 0.6, accel)
        + &format!(
            "[effect.sensor_noise]\nforce_sd_n = {noise:?}\nnormal_sd_n = {noise:?}\n\n\
             [effect.sensor_faults]\ndropout_prob = {dropout:?}\nnan_prob = {nan:?}\n\n\
             [effect.link_latency]\ndelay_ticks = {delay}\n\n\
             [effect.link_faults]\nbit_flip_prob = {flip:?}\ntruncate_prob = {trunc:?}\n\
             drop_prob = {drop:?}\n\n[controller]\nmu = {believed:?}\n"
        )
}
