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
//! ([`is_drop`]; `host-sim/tests/bench.rs::a_drop_is_more_than_10_mm_or_0_2_rad`); the run
//! reports `dropped = true` and the time (metric `dropped_at_s`), and slip is no longer
//! accumulated.
//!
//! softgrip's configuration for a scene, and its errors named by scene key, are in
//! `run/config.rs` (re-exported here). The tick itself is `run/lockstep.rs`: stages 1–3
//! and 5, the plant's step (`run/plant.rs`: the limit surface or the brush finger) and
//! the statistics accumulator (`run/tally.rs`, with the drop); `run/costs.rs` keeps the
//! wall-clock accounting.

mod config;
mod costs;
mod lockstep;
mod plant;
mod tally;

pub use config::*;
pub use tally::{is_drop, DROP_DISTANCE_M, DROP_ROTATION_RAD};

use crate::sim::controllers::{self, LinkKind};
use crate::sim::record::{RunSummary, Sample};
use crate::sim::scene::Scene;
use crate::sim::truth::Truth;
use indicatif::ProgressBar;
use lockstep::Lockstep;
use plant::Plant;
use softgrip::controller::Checked;
use std::time::Instant;

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
/// (memory grows with the run: 176 bytes a tick); [`run_streaming`] hands them to a
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
    let baseline = scene.controller.baseline(cfg.fault_force_n);
    let mut pipeline = scene.pipeline().map_err(|e| e.to_string())?;
    pipeline.set_timed(!options.untimed);
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
    let ctl = controllers::build(controller, cfg, &baseline, link_kind)?;
    // The brush finger, when the scene's finger is one: its plant replaces the limit
    // surface and the quasi-static slip accounting.
    let brush = scene
        .finger
        .brush_finger()?
        .map(|b| b.plant(scene.object.mass_kg, scene.object.inertia_kg_m2));
    let plant = Plant::new(truth, brush);
    let on_surface = !plant.is_brush();
    let mut run = Lockstep::new(scene, pipeline, ctl, plant, cfg.n_min_n, options.untimed);

    let ticks = (scene.duration_s * scene.tick_hz).round() as u64;
    for k in 0..ticks {
        if let Some(sample) = run.tick(k, sink.is_some())? {
            if let Some(sink) = sink.as_deref_mut() {
                sink.sample(&sample)?;
            }
        }
        report_progress(progress, k);
    }
    if let Some(p) = progress {
        p.inc(ticks % 1000);
    }
    let summary = run.summary(controller, ticks, wall)?;
    let surface = if options.skip_samples || !on_surface {
        Vec::new()
    } else {
        let mean_n = summary.mean_normal_force_n;
        truth.normalised_surface(truth.half_width_m(mean_n.max(cfg.n_min_n)))
    };
    Ok(RunOutput {
        summary,
        samples: Vec::new(),
        surface,
    })
}

/// Advances the progress bar every 1000 ticks.
fn report_progress(progress: Option<&ProgressBar>, k: u64) {
    if k % 1000 == 999 {
        if let Some(p) = progress {
            p.inc(1000);
        }
    }
}
