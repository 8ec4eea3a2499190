//! A run in lockstep, one tick at a time: the task and the load effects, the sensor, the
//! link and the controller, the plant's step, the statistics, the actuator; and at the
//! end the run's summary.

use super::costs::Costs;
use super::plant::{Plant, PlantStep};
use super::tally::Tally;
use crate::sim::controllers::GripController;
use crate::sim::effects::{LinkFate, Pipeline, World};
use crate::sim::record::{CommandParts, RunSummary, Sample};
use crate::sim::scene::Scene;
use crate::sim::task;
use softgrip::protocol::SensorFrame;
use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

/// Everything a run carries from one tick to the next.
pub(super) struct Lockstep<'s, 't> {
    scene: &'s Scene,
    pipeline: Pipeline,
    controller: Box<dyn GripController>,
    plant: Plant<'t>,
    /// The world the effects act on.
    w: World,
    /// This tick's frames as the link delivers them.
    frames: Vec<(SensorFrame, LinkFate)>,
    /// Whether the object slid, for each of the last ticks a slip sensor lags behind.
    slip_seen: VecDeque<bool>,
    tally: Tally,
    /// The controller's last status.
    status: &'static str,
    /// Ticks the controller answered nothing.
    missing: u64,
    costs: Costs,
    has_actuator: bool,
    period_us: u64,
}

impl<'s, 't> Lockstep<'s, 't> {
    /// The run of `scene` before its first tick, the normal force at `n_min_n` [N].
    pub(super) fn new(
        scene: &'s Scene,
        pipeline: Pipeline,
        controller: Box<dyn GripController>,
        plant: Plant<'t>,
        n_min_n: f64,
        untimed: bool,
    ) -> Self {
        let detect_ticks = ((0.01 * scene.tick_hz).ceil() as usize).max(1);
        let has_actuator = pipeline.names().iter().any(|n| n == "actuator");
        Lockstep {
            scene,
            pipeline,
            controller,
            plant,
            w: World {
                dt_s: 1.0 / scene.tick_hz,
                mass_kg: scene.object.mass_kg,
                inertia_kg_m2: scene.object.inertia_kg_m2,
                com_offset_m: scene.object.com_offset_m,
                command_n: n_min_n,
                normal_n: n_min_n,
                ..World::default()
            },
            frames: Vec::with_capacity(4),
            slip_seen: std::iter::repeat_n(false, detect_ticks).collect(),
            tally: Tally::new(detect_ticks as u64),
            status: "none",
            missing: 0,
            costs: Costs::new(untimed),
            has_actuator,
            period_us: (1e6 / scene.tick_hz).round().max(1.0) as u64,
        }
    }

    /// Tick `k`: a plant step plus the statistics; its sample if `keep_sample`.
    pub(super) fn tick(&mut self, k: u64, keep_sample: bool) -> Result<Option<Sample>, String> {
        let (sensed, f_t) = self.sense(k);
        self.control(sensed)?;
        let dropped = self.tally.dropped_at.is_some();
        let step = self.plant.step(
            &mut self.w,
            &mut self.pipeline,
            f_t,
            dropped,
            &mut self.costs,
        );
        // The command's parts for the sample (the host's reporting, outside the costs).
        let parts = keep_sample.then(|| self.controller.parts());
        let t = self.costs.start();
        let slide = self.plant.slide();
        self.tally.record(&self.w, &step.tl, step.slipping, slide);
        self.slip_seen.push_back(step.slipping);
        let sample = parts.map(|p| sample(&self.w, &sensed, &step, slide, (self.status, p)));
        self.costs.core += Costs::since(t);
        if self.has_actuator {
            self.pipeline.actuate(&mut self.w);
        } else {
            self.w.normal_n = self.w.command_n;
        }
        Ok(sample)
    }

    /// Stages 1 and 2 of tick `k`: the task's and the load effects' wrench, and the sensor
    /// frame the sensor effects leave of it; with the tangential force the contact carries
    /// [N].
    fn sense(&mut self, k: u64) -> (SensorFrame, [f64; 2]) {
        let t = self.costs.start();
        let w = &mut self.w;
        w.t_s = k as f64 * w.dt_s;
        w.force_n = [0.0, 0.0];
        w.moment_nm = 0.0;
        w.support_fraction = task::support_fraction(&self.scene.task, w.t_s);
        task::apply(&self.scene.task, w);
        self.costs.core += Costs::since(t);
        self.pipeline.load(w);
        let ([fx, fy], moment) = self.plant.contact_load(w);
        let mut frame = SensorFrame {
            seq: k as u32,
            timestamp_us: (k + 1) * self.period_us,
            tangential_force_n: [fx as f32, fy as f32],
            torsional_moment_nm: moment as f32,
            normal_force_n: w.normal_n as f32,
            slip: Default::default(),
        };
        self.pipeline.sense(w, &mut frame);
        (frame, [fx, fy])
    }

    /// Stage 3: the frame crosses the link and the controller answers, or does not.
    fn control(&mut self, frame: SensorFrame) -> Result<(), String> {
        self.frames.clear();
        self.frames.push((frame, LinkFate::Deliver));
        self.pipeline.link(&mut self.frames);
        let t = self.costs.start();
        let seen = self.slip_seen.pop_front().unwrap_or(false);
        match self
            .controller
            .tick(&self.frames, seen)
            .map_err(|e| e.to_string())?
        {
            Some(a) => {
                self.w.command_n = a.command_n;
                self.status = a.status;
            }
            None => self.missing += 1,
        }
        self.costs.control += Costs::since(t);
        Ok(())
    }

    /// The summary of the run after `ticks` ticks, begun at `wall`, against the
    /// controller named `controller`.
    pub(super) fn summary(
        &mut self,
        controller: &str,
        ticks: u64,
        wall: Instant,
    ) -> Result<RunSummary, String> {
        let mut link = self.controller.link_summary().map_err(|e| e.to_string())?;
        link.commands_missing = self.missing;
        let (step_cost_share, total) = self.step_cost_share();
        let mean_n = if ticks > 0 {
            self.tally.sum_n / ticks as f64
        } else {
            0.0
        };
        let wall_s = wall.elapsed().as_secs_f64();
        let duration_s = ticks as f64 * self.w.dt_s;
        let (dist, rot) = self.plant.slide();
        Ok(RunSummary {
            scene: self.scene.name.clone(),
            controller: controller.to_string(),
            dropped: self.tally.dropped_at.is_some(),
            slip_events: self.tally.events,
            slip_distance_m: dist,
            slip_rotation_rad: rot,
            mean_normal_force_n: mean_n,
            peak_normal_force_n: self.tally.peak_n,
            expected_slip: self.scene.expected_slip,
            max_utilisation: self.tally.max_u,
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
            effects: self.pipeline.names(),
            metrics: self.metrics(ticks, total)?,
        })
    }

    /// Each part's share of the plant step's cost (the core and each effect), and the
    /// step's whole cost.
    fn step_cost_share(&self) -> (BTreeMap<String, f64>, Duration) {
        let effect_costs = self.pipeline.costs();
        let core = self.costs.core;
        let total = core + effect_costs.iter().map(|(_, c)| *c).sum::<Duration>();
        let share = |d: Duration| {
            if total.is_zero() {
                0.0
            } else {
                d.as_secs_f64() / total.as_secs_f64()
            }
        };
        let mut shares = BTreeMap::new();
        shares.insert("core".to_string(), share(core));
        for (name, c) in &effect_costs {
            shares.insert(name.clone(), share(*c));
        }
        (shares, total)
    }

    /// The run's metrics after `ticks` ticks whose plant steps cost `total`: the device's
    /// own, the costs, the drop's time, the brush plant's step and the micro-slip.
    fn metrics(&mut self, ticks: u64, total: Duration) -> Result<BTreeMap<String, f64>, String> {
        let mut metrics = self
            .controller
            .device_metrics()
            .map_err(|e| e.to_string())?;
        metrics.insert("plant_step_s".to_string(), total.as_secs_f64());
        let control_s = self.costs.control.as_secs_f64();
        metrics.insert("controller_and_link_s".to_string(), control_s);
        if let Some(t) = self.tally.dropped_at {
            metrics.insert("dropped_at_s".to_string(), t);
        }
        if self.plant.is_brush() && ticks > 0 {
            // The brush plant's own step (pressure solve, sub-steps): wall time per tick.
            metrics.insert(
                "brush_step_per_tick_s".to_string(),
                self.costs.brush.as_secs_f64() / ticks as f64,
            );
            metrics.insert(
                "brush_substeps_per_tick".to_string(),
                self.costs.brush_substeps as f64 / ticks as f64,
            );
        }
        if self.pipeline.names().iter().any(|n| n == "partial_slip") {
            metrics.insert("max_micro_slip_m".to_string(), self.tally.max_micro_m);
        }
        Ok(metrics)
    }
}

/// One tick's sample: the world after the step, the frame as sensed, the plant's step,
/// the object's slide so far (distance [m], rotation [rad]), and the controller's status
/// and its command's parts.
fn sample(
    w: &World,
    sensed: &SensorFrame,
    step: &PlantStep,
    (dist, rot): (f64, f64),
    (status, p): (&'static str, CommandParts),
) -> Sample {
    let [mx, my] = sensed.tangential_force_n;
    let tl = &step.tl;
    Sample {
        t_s: w.t_s,
        ft_n: step.ft_n,
        mn_nm: step.mn_nm,
        ft_meas_n: f64::from(mx).hypot(f64::from(my)),
        mn_meas_nm: f64::from(sensed.torsional_moment_nm).abs(),
        n_cmd_n: w.command_n,
        n_true_n: w.normal_n,
        a_true_m: w.half_width_m,
        f_norm: tl.f_norm,
        m_norm: tl.m_norm,
        pitch: tl.pitch,
        utilisation: tl.utilisation,
        slipping: step.slipping,
        slip_distance_m: dist,
        slip_rotation_rad: rot,
        status,
        parts: p,
    }
}
