//! One run: a scene against one controller, in lockstep, one plant step per tick.
//!
//! Each tick:
//! 1. the task's loads and the load effects give the wrench the grasp must apply to the
//!    object; each of the two fingertips carries half;
//! 2. the sensor reports the contact load and the applied normal force (sensor effects);
//! 3. the frame crosses the link (link effects) and the controller answers with a
//!    command (softgrip over the pseudo-terminal; the baselines in-process);
//! 4. the ground truth: the true contact size (creep), the true limit surface (skew), the
//!    utilisation of the true load, and, outside the surface, slip;
//! 5. the actuator (lag, limits) turns the command into the next tick's normal force.
//!
//! Slip is accounted quasi-statically: while the true load lies outside the true limit
//! surface (utilisation `u > 1`) the contact can transmit only the fraction `1/u` of it,
//! and the rest accelerates the object relative to the fingertips
//! (`a = (1 − 1/u)·|F|/m`, `α = (1 − 1/u)·|M|/I`); once the load is back inside, the
//! contact sticks again. A slip event is an episode of sliding after at least 10 ms of
//! sticking.
//!
//! **The drop** (the one definition, used by `simulate`, `bench` and the tests): once the
//! object has slid more than [`DROP_DISTANCE_M`] (10 mm) or turned more than
//! [`DROP_ROTATION_RAD`] (0.2 rad) relative to the fingertips it is lost from the grasp
//! ([`is_drop`]); the run reports `dropped = true` and the time (metric `dropped_at_s`),
//! and slip is no longer accumulated.
//!
//! softgrip's configuration for a scene, and its errors named by scene key, are in
//! `run/config.rs` (re-exported here).

mod config;

pub use config::*;

use crate::brush::BrushPlant;
use crate::sim::controllers::{self, LinkKind};
use crate::sim::effects::{LinkFate, World};
use crate::sim::record::{RunSummary, Sample};
use crate::sim::scene::Scene;
use crate::sim::task;
use crate::sim::truth::{TrueLoad, Truth};
use indicatif::ProgressBar;
use softgrip::controller::Checked;
use softgrip::protocol::SensorFrame;
use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

/// Slip distance beyond which the object is lost from the grasp [m] (10 mm).
pub const DROP_DISTANCE_M: f64 = 0.01;
/// Slip rotation beyond which the object is lost from the grasp [rad].
pub const DROP_ROTATION_RAD: f64 = 0.2;

/// Whether an object that has slid `slip_distance_m` [m] and turned `slip_rotation_rad`
/// [rad] relative to the fingertips is dropped: more than [`DROP_DISTANCE_M`] or more
/// than [`DROP_ROTATION_RAD`]. The only definition of a drop.
pub fn is_drop(slip_distance_m: f64, slip_rotation_rad: f64) -> bool {
    slip_distance_m > DROP_DISTANCE_M || slip_rotation_rad.abs() > DROP_ROTATION_RAD
}

/// How a run is carried out beyond its scene and controller.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunOptions<'a> {
    /// Skip the per-tick samples (`RunOutput::samples` stays empty and `surface` is not
    /// computed): a run's memory then does not grow with its duration.
    pub skip_samples: bool,
    /// A ground truth already built for this scene (the same finger, skew and force
    /// range), shared between runs instead of rebuilt.
    pub truth: Option<&'a Truth>,
    /// Skip the wall-clock accounting (`step_cost_share`, `plant_step_s`,
    /// `controller_and_link_s` come out zero): it reads the clock about ten times a tick.
    pub untimed: bool,
}

/// Reads the clock unless `untimed`.
fn now(untimed: bool) -> Option<Instant> {
    (!untimed).then(Instant::now)
}

/// The time since `start`, zero when untimed.
fn since(start: Option<Instant>) -> Duration {
    start.map_or(Duration::ZERO, |s| s.elapsed())
}

/// A finished run.
#[derive(Debug)]
pub struct RunOutput {
    /// The summary.
    pub summary: RunSummary,
    /// One sample per tick.
    pub samples: Vec<Sample>,
    /// The true limit surface at the run's mean normal force, in `(f̃, m̃/pitch)`.
    pub surface: Vec<(f64, f64)>,
}

/// Runs `scene` against the controller `controller`.
pub fn run(
    scene: &Scene,
    controller: &str,
    progress: Option<&ProgressBar>,
) -> Result<RunOutput, String> {
    run_on(scene, controller, &LinkKind::InProcess, progress)
}

/// Runs `scene` against `controller`, with softgrip on the link `link`.
pub fn run_on(
    scene: &Scene,
    controller: &str,
    link_kind: &LinkKind,
    progress: Option<&ProgressBar>,
) -> Result<RunOutput, String> {
    run_with(
        scene,
        controller,
        link_kind,
        progress,
        RunOptions::default(),
    )
}

/// Builds the ground truth a run of `scene` uses (its force range follows from the
/// scene's controller settings), for sharing between runs through [`RunOptions::truth`].
pub fn build_truth(scene: &Scene) -> Result<Truth, String> {
    let cfg = controller_config(scene).map_err(|e| e.to_string())?;
    let pipeline = scene.pipeline().map_err(|e| e.to_string())?;
    Truth::build(
        scene,
        pipeline.true_skew(),
        cfg.n_min_n * 0.05,
        cfg.n_max_n * 1.5,
    )
    .map_err(|e| e.to_string())
}

/// Where a run's per-tick samples go, as they are produced.
pub trait SampleSink {
    /// Takes the next tick's sample; an error ends the run with it.
    fn sample(&mut self, s: &Sample) -> Result<(), String>;
}

impl SampleSink for Vec<Sample> {
    fn sample(&mut self, s: &Sample) -> Result<(), String> {
        self.push(*s);
        Ok(())
    }
}

/// Runs `scene` against `controller` on `link_kind`, with `options`. Unless
/// `options.skip_samples`, every tick's sample is collected into `RunOutput::samples`
/// (memory grows with the run: about 136 bytes a tick); [`run_streaming`] hands them to a
/// sink instead.
pub fn run_with(
    scene: &Scene,
    controller: &str,
    link_kind: &LinkKind,
    progress: Option<&ProgressBar>,
    options: RunOptions<'_>,
) -> Result<RunOutput, String> {
    let cfg = controller_config(scene).map_err(|e| e.to_string())?;
    if options.skip_samples {
        return run_into(scene, &cfg, controller, link_kind, progress, options, None);
    }
    let mut samples = Vec::new();
    let mut out = run_into(
        scene,
        &cfg,
        controller,
        link_kind,
        progress,
        options,
        Some(&mut samples),
    )?;
    out.samples = samples;
    Ok(out)
}

/// Runs `scene` against `controller` on `link_kind`, handing each tick's sample to `sink`
/// as it is produced: the run itself keeps nothing per tick (`RunOutput::samples` is
/// empty; `surface` is computed), so its memory does not grow with its duration.
/// `options.skip_samples` is ignored. `config` is the scene's configuration as
/// [`controller_config`] checked it (the caller checked it once, before any run).
pub fn run_streaming(
    scene: &Scene,
    config: &Checked,
    controller: &str,
    link_kind: &LinkKind,
    progress: Option<&ProgressBar>,
    options: RunOptions<'_>,
    sink: &mut dyn SampleSink,
) -> Result<RunOutput, String> {
    let options = RunOptions {
        skip_samples: false,
        ..options
    };
    run_into(
        scene,
        config,
        controller,
        link_kind,
        progress,
        options,
        Some(sink),
    )
}

/// The run: samples go to `sink` if there is one; the surface is computed unless
/// `options.skip_samples`.
fn run_into(
    scene: &Scene,
    cfg: &Checked,
    controller: &str,
    link_kind: &LinkKind,
    progress: Option<&ProgressBar>,
    options: RunOptions<'_>,
    mut sink: Option<&mut dyn SampleSink>,
) -> Result<RunOutput, String> {
    let wall = Instant::now();
    let constant_n = scene
        .controller
        .constant_force_n
        .unwrap_or(cfg.fault_force_n);
    let mut pipeline = scene.pipeline().map_err(|e| e.to_string())?;
    pipeline.set_timed(!options.untimed);
    let untimed = options.untimed;
    let has_actuator = pipeline.names().iter().any(|n| n == "actuator");
    let built;
    let truth = match options.truth {
        Some(t) => t,
        None => {
            built = Truth::build(
                scene,
                pipeline.true_skew(),
                cfg.n_min_n * 0.05,
                cfg.n_max_n * 1.5,
            )
            .map_err(|e| e.to_string())?;
            &built
        }
    };
    let mut ctl = controllers::build(controller, cfg, constant_n, link_kind)?;
    // The brush finger, when the scene's finger is one: its plant replaces the limit
    // surface and the quasi-static slip accounting below.
    let mut plant = scene
        .finger
        .brush_finger()?
        .map(|b| b.plant(scene.object.mass_kg, scene.object.inertia_kg_m2));

    let dt = 1.0 / scene.tick_hz;
    let ticks = (scene.duration_s * scene.tick_hz).round() as u64;
    let detect_ticks = ((0.01 * scene.tick_hz).ceil() as usize).max(1);
    let mut w = World {
        dt_s: dt,
        mass_kg: scene.object.mass_kg,
        inertia_kg_m2: scene.object.inertia_kg_m2,
        com_offset_m: scene.object.com_offset_m,
        command_n: cfg.n_min_n,
        normal_n: cfg.n_min_n,
        ..World::default()
    };
    let mut frames: Vec<(SensorFrame, LinkFate)> = Vec::with_capacity(4);
    let mut slip_seen: VecDeque<bool> = std::iter::repeat_n(false, detect_ticks).collect();
    let (mut v, mut omega, mut dist, mut rot) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut tally = Tally::new(detect_ticks as u64);
    let mut status = "none";
    let mut missing = 0u64;
    let mut core = Duration::ZERO;
    let (mut brush_s, mut substeps) = (Duration::ZERO, 0u64);
    let mut control = Duration::ZERO;
    let period_us = (1e6 / scene.tick_hz).round().max(1.0) as u64;

    for k in 0..ticks {
        let t0 = now(untimed);
        w.t_s = k as f64 * dt;
        w.force_n = [0.0, 0.0];
        w.moment_nm = 0.0;
        w.support_fraction = task::support_fraction(scene, w.t_s);
        task::apply(scene, &mut w);
        core += since(t0);
        pipeline.load(&mut w);

        let ([fx, fy], moment) = match &plant {
            None => (w.contact_force_n(), w.contact_moment_nm()),
            Some(p) => (p.report().f_t_n, p.report().m_n_nm),
        };
        let mut frame = SensorFrame {
            seq: k as u32,
            timestamp_us: (k + 1) * period_us,
            tangential_force_n: [fx as f32, fy as f32],
            torsional_moment_nm: moment as f32,
            normal_force_n: w.normal_n as f32,
            slip: Default::default(),
        };
        pipeline.sense(&w, &mut frame);
        let sensed = frame;
        frames.clear();
        frames.push((frame, LinkFate::Deliver));
        pipeline.link(&mut frames);

        let t1 = now(untimed);
        let seen = slip_seen.pop_front().unwrap_or(false);
        match ctl.tick(&frames, seen).map_err(|e| e.to_string())? {
            Some(a) => {
                w.command_n = a.command_n;
                status = a.status;
            }
            None => missing += 1,
        }
        control += since(t1);

        let t2 = now(untimed);
        let dropped = tally.dropped_at.is_some();
        // The plant step: the true load, whether it slips, and the object's slide.
        let (tl, slipping, ft, mn) = match plant.as_mut() {
            Some(p) => {
                let step = brush_tick(p, &mut w, dropped);
                brush_s += since(t2);
                substeps += p.report().substeps as u64;
                (dist, rot) = (p.report().slip_distance_m, p.report().slip_rotation_rad);
                core += since(t2);
                pipeline.contact(&mut w);
                step
            }
            None => {
                w.half_width_eq_m = truth.half_width_m(w.normal_n);
                w.half_width_m = w.half_width_eq_m;
                core += since(t2);
                pipeline.contact(&mut w);
                let (ft, mn) = (fx.hypot(fy), w.contact_moment_nm().abs());
                let tl = truth.evaluate(ft, mn, w.normal_n, w.half_width_m);
                let slipping = tl.utilisation > 1.0;
                if slipping && !dropped {
                    let excess = if tl.utilisation.is_finite() {
                        1.0 - 1.0 / tl.utilisation
                    } else {
                        1.0
                    };
                    v += excess * w.force_n[0].hypot(w.force_n[1]) / w.mass_kg * dt;
                    omega += excess * w.moment_nm.abs() / w.inertia_kg_m2 * dt;
                    dist += v * dt;
                    rot += omega * dt;
                } else if !dropped {
                    v = 0.0;
                    omega = 0.0;
                }
                // What the next tick's sensors can know of this one (the slip sensor).
                w.true_utilisation = tl.utilisation;
                w.sliding = slipping && !dropped;
                (tl, slipping, ft, mn)
            }
        };
        let t3 = now(untimed);
        tally.record(&w, &tl, slipping, (dist, rot));
        slip_seen.push_back(slipping);
        if let Some(sink) = sink.as_deref_mut() {
            sink.sample(&sample(
                &w,
                &sensed,
                (ft, mn),
                &tl,
                slipping,
                (dist, rot),
                status,
            ))?;
        }
        core += since(t3);
        actuate(&mut pipeline, &mut w, has_actuator);
        report_progress(progress, k);
    }
    if let Some(p) = progress {
        p.inc(ticks % 1000);
    }
    let mut link = ctl.link_summary().map_err(|e| e.to_string())?;
    link.commands_missing = missing;

    let effect_costs = pipeline.costs();
    let total = core + effect_costs.iter().map(|(_, c)| *c).sum::<Duration>();
    let share = |d: Duration| {
        if total.is_zero() {
            0.0
        } else {
            d.as_secs_f64() / total.as_secs_f64()
        }
    };
    let mut step_cost_share = BTreeMap::new();
    step_cost_share.insert("core".to_string(), share(core));
    for (name, c) in &effect_costs {
        step_cost_share.insert(name.clone(), share(*c));
    }
    let mean_n = if ticks > 0 {
        tally.sum_n / ticks as f64
    } else {
        0.0
    };
    let wall_s = wall.elapsed().as_secs_f64();
    let duration_s = ticks as f64 * dt;
    let mut metrics = ctl.device_metrics().map_err(|e| e.to_string())?;
    metrics.insert("plant_step_s".to_string(), total.as_secs_f64());
    metrics.insert("controller_and_link_s".to_string(), control.as_secs_f64());
    if let Some(t) = tally.dropped_at {
        metrics.insert("dropped_at_s".to_string(), t);
    }
    if plant.is_some() && ticks > 0 {
        // The brush plant's own step (pressure solve, sub-steps): wall time per tick.
        metrics.insert(
            "brush_step_per_tick_s".to_string(),
            brush_s.as_secs_f64() / ticks as f64,
        );
        metrics.insert(
            "brush_substeps_per_tick".to_string(),
            substeps as f64 / ticks as f64,
        );
    }
    if pipeline.names().iter().any(|n| n == "partial_slip") {
        metrics.insert("max_micro_slip_m".to_string(), tally.max_micro_m);
    }
    let surface = if options.skip_samples || plant.is_some() {
        Vec::new()
    } else {
        truth.normalised_surface(truth.half_width_m(mean_n.max(cfg.n_min_n)))
    };
    Ok(RunOutput {
        summary: RunSummary {
            scene: scene.name.clone(),
            controller: controller.to_string(),
            dropped: tally.dropped_at.is_some(),
            slip_events: tally.events,
            slip_distance_m: dist,
            slip_rotation_rad: rot,
            mean_normal_force_n: mean_n,
            peak_normal_force_n: tally.peak_n,
            expected_slip: scene.expected_slip,
            max_utilisation: tally.max_u,
            ticks,
            duration_s,
            wall_s,
            real_time_factor: if wall_s > 0.0 {
                duration_s / wall_s
            } else {
                0.0
            },
            link,
            step_cost_share,
            effects: pipeline.names(),
            metrics,
        },
        samples: Vec::new(),
        surface,
    })
}

/// Stage 4 of the step: the actuator effect, or the command applied as it is.
fn actuate(pipeline: &mut crate::sim::effects::Pipeline, w: &mut World, has_actuator: bool) {
    if has_actuator {
        pipeline.actuate(w);
    } else {
        w.normal_n = w.command_n;
    }
}

/// Advances the progress bar every 1000 ticks.
fn report_progress(progress: Option<&ProgressBar>, k: u64) {
    if k % 1000 == 999 {
        if let Some(p) = progress {
            p.inc(1000);
        }
    }
}

/// One tick's sample.
fn sample(
    w: &World,
    sensed: &SensorFrame,
    (ft, mn): (f64, f64),
    tl: &TrueLoad,
    slipping: bool,
    (dist, rot): (f64, f64),
    status: &'static str,
) -> Sample {
    let [mx, my] = sensed.tangential_force_n;
    Sample {
        t_s: w.t_s,
        ft_n: ft,
        mn_nm: mn,
        ft_meas_n: f64::from(mx).hypot(f64::from(my)),
        mn_meas_nm: f64::from(sensed.torsional_moment_nm).abs(),
        n_cmd_n: w.command_n,
        n_true_n: w.normal_n,
        a_true_m: w.half_width_m,
        f_norm: tl.f_norm,
        m_norm: tl.m_norm,
        pitch: tl.pitch,
        utilisation: tl.utilisation,
        slipping,
        slip_distance_m: dist,
        slip_rotation_rad: rot,
        status,
    }
}

/// The brush plant's step for one tick (unless the object is already `dropped`), and
/// what the run records of it: the load state, whether the contact slides grossly, and
/// the contact's `|f_t|` and `|m_n|`. For the brush finger `utilisation` is the fraction
/// of the loaded elements that slide (1 in gross slip), `f_norm = |f_t|/(μ_s N)`,
/// `m_norm = |m_n|/(μ_s N a)` and `pitch` is 0 (there is no limit surface). Sets the
/// world's half-width, utilisation and sliding for the effects.
/// A run's statistics, tick by tick, whatever the plant: slip events, the drop, the
/// normal force's sum and peak, the greatest utilisation and micro-slip.
#[derive(Debug)]
struct Tally {
    /// Ticks of sticking before a slip counts as a new event.
    stick_ticks: u64,
    stuck_for: u64,
    events: u64,
    dropped_at: Option<f64>,
    sum_n: f64,
    peak_n: f64,
    max_u: f64,
    max_micro_m: f64,
}

impl Tally {
    fn new(stick_ticks: u64) -> Self {
        Self {
            stick_ticks,
            stuck_for: u64::MAX,
            events: 0,
            dropped_at: None,
            sum_n: 0.0,
            peak_n: 0.0,
            max_u: 0.0,
            max_micro_m: 0.0,
        }
    }

    /// Counts one tick: `slipping` whether the contact slid, `slide` the object's slip
    /// distance [m] and rotation [rad] so far. Nothing is counted as slip once dropped.
    fn record(&mut self, w: &World, tl: &TrueLoad, slipping: bool, slide: (f64, f64)) {
        if self.dropped_at.is_none() {
            if slipping {
                if self.stuck_for >= self.stick_ticks {
                    self.events += 1;
                }
                self.stuck_for = 0;
            } else {
                self.stuck_for = self.stuck_for.saturating_add(1);
            }
            if is_drop(slide.0, slide.1) {
                self.dropped_at = Some(w.t_s);
            }
        }
        self.sum_n += w.normal_n;
        self.peak_n = self.peak_n.max(w.normal_n);
        if tl.utilisation.is_finite() {
            self.max_u = self.max_u.max(tl.utilisation);
        }
        self.max_micro_m = self.max_micro_m.max(w.micro_slip_m);
    }
}

fn brush_tick(plant: &mut BrushPlant, w: &mut World, dropped: bool) -> (TrueLoad, bool, f64, f64) {
    let r = if dropped {
        plant.report()
    } else {
        plant.step(w.normal_n, w.force_n, w.moment_nm, w.dt_s)
    };
    let ft = r.f_t_n[0].hypot(r.f_t_n[1]);
    let mn = r.m_n_nm.abs();
    let cap = plant.mu_static() * r.normal_n;
    let ratio = |x: f64, d: f64| if d > 0.0 { x / d } else { 0.0 };
    let tl = TrueLoad {
        f_norm: ratio(ft, cap),
        m_norm: ratio(mn, cap * r.half_width_m),
        pitch: 0.0,
        utilisation: 1.0 - r.stuck_fraction,
    };
    w.half_width_eq_m = r.half_width_m;
    w.half_width_m = r.half_width_m;
    w.true_utilisation = tl.utilisation;
    let slipping = r.gross_slip;
    w.sliding = slipping && !dropped;
    (tl, slipping, ft, mn)
}
