//! The controllers a scene can run against: softgrip over the serial link, and the
//! baselines it is compared with (in-process, with the same clamps and rate limits).
//!
//! | name | rule |
//! | --- | --- |
//! | `softgrip`, `softgrip-ellipse`, `softgrip-table` | docs/model.md's rule on the device, over the link |
//! | `constant` | a fixed grip force |
//! | `coulomb` | `N = s·f_t/μ`: translation only, torsion ignored |
//! | `box` | `N = s·max(f_t/μ, m_n/m̂)`, `m̂ = μ·a_ref·pitch` (a box-shaped limit, as some tactile-gripper code uses) |
//! | `fixed-torsion` | `N = s·sqrt((f_t/μ)² + (m_n/(μ_t))²)`, `μ_t = μ·a_ref·pitch`: the elliptic soft-contact cone of physics engines, with a patch of constant size |
//! | `slip-servo` | starts light; after a detected slip raises the force by half plus a fixed step (`baseline.rs`), then relaxes slowly |
//!
//! `a_ref·pitch` is the fixed patch's torsion arm: by default that of the contact at the
//! constant baseline's force, the size a fixed-patch model would be tuned at; a scene can
//! give it (`controller.baseline_torsion_arm_m`, as the bench does from each finger's
//! torsion test), and the baselines' μ (`controller.baseline_mu`, from a slip test).

use crate::link::direct::DirectLink;
use crate::link::pty::PtyLink;
use crate::link::qemu::QemuLink;
use crate::link::serial::SerialLink;
use crate::link::{Link, LinkError};
use crate::sim::effects::LinkFate;
use crate::sim::record::{CommandParts, LinkSummary};
use clap::builder::PossibleValue;
use clap::ValueEnum;
use softgrip::controller::{Checked, Controller, ControllerConfig, Libm, Mode, Status};
use softgrip::protocol::{CommandFrame, Reply, Request, SensorFrame};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Mutex;

pub mod baseline;

pub use baseline::{Baseline, BaselineSettings};

/// A controller a scene can run against: softgrip in one of its modes, or a baseline.
/// Its [`name`](ControllerKind::name) is what `--controller` takes and what output file
/// names, CSV columns and bench.json keys carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, ValueEnum)]
pub enum ControllerKind {
    /// softgrip in the default configuration's mode (`ControllerConfig::DEFAULT.mode`).
    Softgrip,
    /// softgrip, mode `ellipse`.
    SoftgripEllipse,
    /// softgrip, mode `table`.
    SoftgripTable,
    /// A fixed grip force.
    Constant,
    /// `N = s·f_t/μ`: translation only, torsion ignored.
    Coulomb,
    /// `N = s·max(f_t/μ, m_n/m̂)`: a box-shaped limit.
    Box,
    /// The elliptic soft-contact cone of physics engines, with a patch of constant size.
    FixedTorsion,
    /// Starts light; raises the force after a detected slip, then relaxes slowly.
    SlipServo,
}

impl ControllerKind {
    /// Every controller `--controller` accepts (besides `all`).
    pub const NAMES: [Self; 8] = [
        Self::Softgrip,
        Self::SoftgripEllipse,
        Self::SoftgripTable,
        Self::Constant,
        Self::Coulomb,
        Self::Box,
        Self::FixedTorsion,
        Self::SlipServo,
    ];

    /// The softgrip mode that is not the default's: `softgrip` runs the default mode.
    pub const OTHER_MODE: Self = match ControllerConfig::DEFAULT.mode {
        Mode::Ellipse => Self::SoftgripTable,
        Mode::Table => Self::SoftgripEllipse,
    };

    /// The controllers `--controller all` runs (softgrip's default mode is `softgrip`).
    pub const ALL: [Self; 7] = [
        Self::Softgrip,
        Self::OTHER_MODE,
        Self::Constant,
        Self::Coulomb,
        Self::Box,
        Self::FixedTorsion,
        Self::SlipServo,
    ];

    /// The name, as `--controller` takes it and the outputs carry it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Softgrip => "softgrip",
            Self::SoftgripEllipse => "softgrip-ellipse",
            Self::SoftgripTable => "softgrip-table",
            Self::Constant => "constant",
            Self::Coulomb => "coulomb",
            Self::Box => "box",
            Self::FixedTorsion => "fixed-torsion",
            Self::SlipServo => "slip-servo",
        }
    }

    /// The controller named `name`, if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::NAMES.into_iter().find(|k| k.name() == name)
    }

    /// Whether it is softgrip (it runs on the device, over the link), not a baseline (in
    /// this process).
    pub fn is_softgrip(self) -> bool {
        matches!(
            self,
            Self::Softgrip | Self::SoftgripEllipse | Self::SoftgripTable
        )
    }

    /// Whether the output's controller `name` is softgrip's (in any mode).
    pub fn name_is_softgrip(name: &str) -> bool {
        Self::from_name(name).is_some_and(Self::is_softgrip)
    }

    /// The controller that runs softgrip in `mode` alone (`softgrip-ellipse` or
    /// `softgrip-table`).
    pub fn of_mode(mode: Mode) -> Self {
        match mode {
            Mode::Ellipse => Self::SoftgripEllipse,
            Mode::Table => Self::SoftgripTable,
        }
    }

    /// The mode softgrip runs in on a configuration whose own mode is `configured`
    /// (`softgrip` keeps it, the other two name theirs); `None` for a baseline.
    pub fn softgrip_mode(self, configured: Mode) -> Option<Mode> {
        match self {
            Self::Softgrip => Some(configured),
            Self::SoftgripEllipse => Some(Mode::Ellipse),
            Self::SoftgripTable => Some(Mode::Table),
            _ => None,
        }
    }
}

/// What `--controller` takes: one controller, or `all` ([`ControllerKind::ALL`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ControllerChoice {
    /// Every controller of [`ControllerKind::ALL`].
    All,
    /// One controller.
    One(ControllerKind),
}

impl ControllerChoice {
    const VARIANTS: [Self; 9] = [
        Self::All,
        Self::One(ControllerKind::Softgrip),
        Self::One(ControllerKind::SoftgripEllipse),
        Self::One(ControllerKind::SoftgripTable),
        Self::One(ControllerKind::Constant),
        Self::One(ControllerKind::Coulomb),
        Self::One(ControllerKind::Box),
        Self::One(ControllerKind::FixedTorsion),
        Self::One(ControllerKind::SlipServo),
    ];

    /// The controllers the choices select, in the order given, each once.
    pub fn kinds(choices: &[Self]) -> Vec<ControllerKind> {
        let mut v: Vec<ControllerKind> = Vec::new();
        for c in choices {
            let add: &[ControllerKind] = match c {
                Self::All => &ControllerKind::ALL,
                Self::One(k) => std::slice::from_ref(k),
            };
            for k in add {
                if !v.contains(k) {
                    v.push(*k);
                }
            }
        }
        v
    }
}

impl ValueEnum for ControllerChoice {
    fn value_variants<'a>() -> &'a [Self] {
        &Self::VARIANTS
    }

    fn to_possible_value(&self) -> Option<PossibleValue> {
        match self {
            Self::All => Some(PossibleValue::new("all").help(
                "softgrip in both modes (the default mode as softgrip-ellipse or softgrip-table) \
                 and every baseline",
            )),
            Self::One(k) => k.to_possible_value(),
        }
    }
}

/// Where softgrip runs.
#[derive(Debug, Clone)]
pub enum LinkKind {
    /// The device loop on a thread of its own, over a pseudo-terminal.
    InProcess,
    /// The device loop on the calling thread, through an in-memory byte stream (the same
    /// bytes as over the pty).
    Direct,
    /// The firmware on a board (or any device) behind a serial port.
    Serial {
        /// The port's path.
        port: PathBuf,
        /// Its speed.
        baud: u32,
    },
    /// The firmware in QEMU, over its USART's pseudo-terminal.
    Qemu {
        /// Where QEMU is unpacked.
        qemu_dir: PathBuf,
        /// The firmware ELF.
        firmware: PathBuf,
    },
}

/// What a controller answers to one tick.
#[derive(Debug, Clone, Copy)]
pub struct Answer {
    /// Commanded normal force \[N\].
    pub command_n: f64,
    /// Status name.
    pub status: &'static str,
}

/// A grip controller as the plant drives it.
pub trait GripController {
    /// The name.
    fn name(&self) -> &str;
    /// One tick: the frames the link delivers this tick (possibly none, possibly damaged)
    /// and whether a slip sensor has seen the object slide. `None`: no new command.
    fn tick(
        &mut self,
        frames: &[(SensorFrame, LinkFate)],
        slip_seen: bool,
    ) -> Result<Option<Answer>, LinkError>;
    /// What the command of the last [`tick`](GripController::tick) is made of, for its
    /// sample ([`CommandParts::NONE`] for a baseline, or when that tick had no reply).
    /// Called only when the run keeps its samples; after every tick then.
    fn parts(&mut self) -> CommandParts {
        CommandParts::NONE
    }
    /// The link's accounting at the end of a run.
    fn link_summary(&mut self) -> Result<LinkSummary, LinkError>;
    /// What the device measured of itself (start-up and tick costs, stack), as run
    /// metrics; empty for in-process baselines.
    fn device_metrics(&mut self) -> Result<BTreeMap<String, f64>, LinkError> {
        Ok(BTreeMap::new())
    }
}

/// softgrip on the device loop, over the in-process pseudo-terminal link or in QEMU.
#[derive(Debug)]
pub struct SoftgripLink {
    name: String,
    link: Box<dyn Link>,
    sent: u64,
    lost: u64,
    base: (u32, u32, u32, u32),
    /// How many ticks cost each amount (a histogram, not a list: its size is bounded by
    /// the distinct costs, not the run's length).
    tick_costs: BTreeMap<u32, u64>,
    /// The configuration the device runs (for [`Levels`]).
    config: Checked,
    /// The last tick's reply and the frame it answers, if it had one.
    answered: Option<(CommandFrame, SensorFrame)>,
    /// The host's copy of the device's model, built at the first sample: the forces the
    /// reply does not carry.
    levels: Option<Levels>,
}

/// The forces of a command's parts that the reply does not carry, evaluated on the host
/// with the device's model (its configuration, `f32`, [`Libm`]: the same numbers to the
/// solver's tolerance) for the load of the frame the device answered.
#[derive(Debug)]
struct Levels {
    model: Option<Controller<f32, Libm>>,
    /// The last good tick's `[required_n, n_slip_mu_n, n_safety_n, n_load_n]`: a bad tick
    /// reports the last good one's, as the device does its `N_slip`.
    last: [f32; 4],
}

impl Levels {
    /// The host's model of `config` (the in-process devices' own when the process keeps
    /// it: [`crate::link::handed`]).
    fn new(config: &Checked) -> Self {
        Self {
            model: crate::link::handed::precompute::<Libm>(config).ok(),
            last: [f32::NAN; 4],
        }
    }

    /// `[required_n, n_slip_mu_n, n_safety_n, n_load_n]` \[N\] for the reply `c` to
    /// `frame`: on a good tick (`ok`, `saturated`) the model's requirement of the frame's
    /// load at the configured `μ`, with no safety factor, at the safety factor `s`, at
    /// `s·load_factor` and at `s·margin·μ/μ̂` (the last two floored at 1 before `μ/μ̂`, as
    /// the tick floors its safety factor); else the last good tick's.
    fn of(&mut self, c: &CommandFrame, frame: &SensorFrame) -> [f32; 4] {
        let (Some(model), Status::Ok | Status::Saturated) = (&self.model, c.status) else {
            return self.last;
        };
        let [fx, fy] = frame.tangential_force_n;
        let (ft, mn) = ((fx * fx + fy * fy).sqrt(), frame.torsional_moment_nm);
        let s = model.config().safety as f32;
        let mu = model.config().mu as f32;
        let at = |safety: f32| {
            model
                .tick_required_force(ft, mn, safety)
                .map_or(f32::NAN, |x| x.force_n)
        };
        let slip = model.slip_force(ft, mn).map_or(f32::NAN, |x| x.force_n);
        self.last = [
            at((s * c.margin).max(1.0) * (mu / c.mu_estimate)),
            slip,
            at(s),
            at((s * c.load_factor).max(1.0)),
        ];
        self.last
    }
}

impl SoftgripLink {
    /// Starts a device, configures it and records its counters' starting point.
    pub fn start(name: &str, cfg: Checked, kind: &LinkKind) -> Result<Self, LinkError> {
        let mut link: Box<dyn Link> = match kind {
            LinkKind::InProcess => Box::new(PtyLink::spawn::<Libm>()?),
            LinkKind::Direct => Box::new(DirectLink::<Libm>::new()?),
            LinkKind::Qemu { qemu_dir, firmware } => Box::new(QemuLink::boot(qemu_dir, firmware)?),
            LinkKind::Serial { port, baud } => Box::new(
                SerialLink::open(port, *baud, softgrip::protocol::Pacing::Lockstep)
                    .map_err(|e| LinkError::Io(std::io::Error::other(format!("--port: {e}"))))?,
            ),
        };
        match link.exchange(&Request::Configure(*cfg.config()))? {
            Reply::Configured(Ok(())) => {}
            other => return Err(LinkError::Unexpected(Box::new(other))),
        }
        let base = stats(&mut link)?;
        Ok(Self {
            name: name.to_string(),
            link,
            sent: 0,
            lost: 0,
            base,
            tick_costs: BTreeMap::new(),
            config: cfg,
            answered: None,
            levels: None,
        })
    }
}

fn stats(link: &mut Box<dyn Link>) -> Result<(u32, u32, u32, u32), LinkError> {
    match link.exchange(&Request::GetStats)? {
        Reply::Stats(s) => Ok((
            s.ticks,
            s.crc_errors + s.decode_errors,
            s.overruns,
            s.frames_received,
        )),
        other => Err(LinkError::Unexpected(Box::new(other))),
    }
}

impl GripController for SoftgripLink {
    fn name(&self) -> &str {
        &self.name
    }

    fn tick(
        &mut self,
        frames: &[(SensorFrame, LinkFate)],
        _slip_seen: bool,
    ) -> Result<Option<Answer>, LinkError> {
        let mut answer = None;
        self.answered = None;
        for (frame, fate) in frames {
            self.sent += 1;
            match fate {
                LinkFate::Drop => self.lost += 1,
                LinkFate::Corrupt(bytes) => self.link.inject(bytes)?,
                LinkFate::Deliver => {
                    // Lockstep: wait for this frame's command (a stale reply would carry
                    // another sequence number).
                    for _ in 0..4 {
                        match self.link.exchange(&Request::Sensor(*frame))? {
                            Reply::Command(c) if c.seq == frame.seq => {
                                *self.tick_costs.entry(c.tick_cost).or_insert(0) += 1;
                                self.answered = Some((c, *frame));
                                answer = Some(Answer {
                                    command_n: f64::from(c.normal_force_n),
                                    status: c.status.name(),
                                });
                                break;
                            }
                            _ => continue,
                        }
                    }
                }
            }
        }
        Ok(answer)
    }

    fn parts(&mut self) -> CommandParts {
        let config = &self.config;
        let levels = self.levels.get_or_insert_with(|| Levels::new(config));
        let Some((c, frame)) = &self.answered else {
            return CommandParts::NONE;
        };
        let [required_n, n_slip_mu_n, n_safety_n, n_load_n] = levels.of(c, frame);
        CommandParts {
            n_slip_n: c.n_slip_n,
            required_n,
            mu_hat: c.mu_estimate,
            margin: c.margin,
            slip_margin: c.margin / c.load_factor,
            load_factor: c.load_factor,
            lead_n: c.lead_n,
            n_slip_mu_n,
            n_safety_n,
            n_load_n,
        }
    }

    fn link_summary(&mut self) -> Result<LinkSummary, LinkError> {
        let (ticks, corrupt, overruns, _) = stats(&mut self.link)?;
        Ok(LinkSummary {
            frames_sent: self.sent,
            frames_received: u64::from(ticks - self.base.0),
            frames_corrupt: u64::from(corrupt - self.base.1) + u64::from(overruns - self.base.2),
            frames_lost: self.lost,
            commands_missing: 0,
        })
    }

    fn device_metrics(&mut self) -> Result<BTreeMap<String, f64>, LinkError> {
        let s = match self.link.exchange(&Request::GetStats)? {
            Reply::Stats(s) => s,
            other => return Err(LinkError::Unexpected(Box::new(other))),
        };
        let unit = match s.cost_unit {
            softgrip::protocol::CostUnit::Nanoseconds => "ns",
            softgrip::protocol::CostUnit::Instructions => "instructions",
            softgrip::protocol::CostUnit::Cycles => "cycles",
        };
        let mut m = BTreeMap::new();
        m.insert(format!("device_startup_{unit}"), f64::from(s.startup_cost));
        m.insert(
            "device_stack_peak_bytes".to_string(),
            f64::from(s.stack_peak_bytes),
        );
        let c = &self.tick_costs;
        if let (Some((first, _)), Some((last, _))) = (c.first_key_value(), c.last_key_value()) {
            // The element at index len/2 of the sorted costs, as before the histogram.
            let half = c.values().sum::<u64>() / 2;
            let mut seen = 0;
            let mut median = *last;
            for (cost, n) in c {
                seen += n;
                if seen > half {
                    median = *cost;
                    break;
                }
            }
            m.insert(format!("device_tick_min_{unit}"), f64::from(*first));
            m.insert(format!("device_tick_median_{unit}"), f64::from(median));
            m.insert(format!("device_tick_max_{unit}"), f64::from(*last));
        }
        Ok(m)
    }
}

/// How many controllers of each name [`build`] has built in this process: for the tests
/// that check a run builds each of its controllers once.
static BUILDS: Mutex<BTreeMap<String, usize>> = Mutex::new(BTreeMap::new());

/// The controllers [`build`] has built in this process, by name, with how many times.
pub fn builds() -> BTreeMap<String, usize> {
    BUILDS.lock().map(|m| m.clone()).unwrap_or_default()
}

/// Builds the controller `name` for a scene's checked configuration (softgrip's is sent
/// to the device as it is: it was validated once, by the caller).
pub fn build(
    name: &str,
    cfg: &Checked,
    baseline: &BaselineSettings,
    link: &LinkKind,
) -> Result<Box<dyn GripController>, String> {
    if let Ok(mut builds) = BUILDS.lock() {
        *builds.entry(name.to_string()).or_default() += 1;
    }
    match ControllerKind::from_name(name).and_then(|k| k.softgrip_mode(cfg.mode)) {
        Some(mode) => SoftgripLink::start(name, cfg.with_mode(mode), link)
            .map(|c| Box::new(c) as Box<dyn GripController>)
            .map_err(|e| e.to_string()),
        None => Baseline::new(name, cfg, baseline)?
            .map(|b| Box::new(b) as Box<dyn GripController>)
            .ok_or_else(|| {
                format!(
                    "--controller: unknown controller \"{}\", expected all or one of {}",
                    crate::input::short(name),
                    ControllerKind::NAMES.map(ControllerKind::name).join(", ")
                )
            }),
    }
}
