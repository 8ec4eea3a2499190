//! The in-process baselines softgrip is compared with (see [`super`] for
//! the table of their rules), with the same clamps and rate limits as softgrip, and what
//! they are told besides softgrip's configuration ([`BaselineSettings`]).

use super::{Answer, ControllerKind, GripController};
use crate::link::LinkError;
use crate::sim::effects::LinkFate;
use crate::sim::record::LinkSummary;
use softgrip::controller::ControllerConfig;
use softgrip::protocol::SensorFrame;
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};

/// The limits every baseline shares with softgrip: `[N_min, N_max]` and the rise and
/// fall rates.
#[derive(Debug, Clone, Copy)]
struct Limits {
    n_min: f64,
    n_max: f64,
    rise: f64,
    fall: f64,
}

impl Limits {
    fn step(&self, current: f64, target: f64) -> f64 {
        target
            .min(current + self.rise)
            .max(current - self.fall)
            .clamp(self.n_min, self.n_max)
    }
}

/// The force the cone of `fixed-torsion` asks for a load `(f, m)` at safety 1 \[N\]:
/// `hypot(f/μ, m/(μ·arm))`, `arm` the fixed patch's torsion arm \[m\].
pub fn cone_force_n(f: f64, m: f64, mu: f64, arm_m: f64) -> f64 {
    (f / mu).hypot(m / (mu * arm_m))
}

/// The force the `box` asks for a load `(f, m)` at safety 1 \[N\]: `max(f/μ, m/(μ·arm))`.
pub fn box_force_n(f: f64, m: f64, mu: f64, arm_m: f64) -> f64 {
    (f / mu).max(m / (mu * arm_m))
}

/// What the baselines are told besides softgrip's configuration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaselineSettings {
    /// The constant baseline's force \[N\] (and the force at which the default fixed patch
    /// is taken).
    pub constant_n: f64,
    /// The μ of the cone, box and fixed-torsion; `None`: softgrip's.
    pub mu: Option<f64>,
    /// The fixed patch's torsion arm \[m\]; `None`: `a·pitch` at `constant_n`.
    pub torsion_arm_m: Option<f64>,
}

/// The in-process baselines.
#[derive(Debug)]
pub struct Baseline {
    name: String,
    kind: Kind,
    limits: Limits,
    mu: f64,
    safety: f64,
    torsion_arm_m: f64,
    constant_n: f64,
    command: f64,
    sent: u64,
    lost: u64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Constant,
    Coulomb,
    Box,
    FixedTorsion,
    SlipServo,
}

impl Baseline {
    /// The baseline `name` for a controller configuration and the baselines' settings
    /// (the constant force, at which the default fixed patch size is taken; μ and the
    /// torsion arm if given). `Ok(None)` for a name that is not a baseline; an error
    /// (naming the scene key) when the constant force is not finite and positive, when
    /// the fixed patch at that force has no limit surface (a contact size that gives an
    /// aspect `l/a` of 0 or ∞), or when a given μ or arm is not finite and positive.
    pub fn new(
        name: &str,
        cfg: &ControllerConfig,
        settings: &BaselineSettings,
    ) -> Result<Option<Self>, String> {
        let constant_n = settings.constant_n;
        let kind = match ControllerKind::from_name(name) {
            Some(ControllerKind::Constant) => Kind::Constant,
            Some(ControllerKind::Coulomb) => Kind::Coulomb,
            Some(ControllerKind::Box) => Kind::Box,
            Some(ControllerKind::FixedTorsion) => Kind::FixedTorsion,
            Some(ControllerKind::SlipServo) => Kind::SlipServo,
            _ => return Ok(None),
        };
        let bad = |why: String| {
            format!(
                "controller.constant_force_n: {} N {why}",
                crate::input::short_num(constant_n)
            )
        };
        if !(constant_n > 0.0 && constant_n.is_finite()) {
            return Err(bad("must be a finite number > 0".into()));
        }
        for (key, v) in [
            ("baseline_mu", settings.mu),
            ("baseline_torsion_arm_m", settings.torsion_arm_m),
        ] {
            if let Some(v) = v.filter(|v| !(*v > 0.0 && v.is_finite())) {
                return Err(format!(
                    "controller.{key}: {} must be a finite number > 0",
                    crate::input::short_num(v)
                ));
            }
        }
        // The fixed patch: the contact's size and pitch at the constant force.
        let a_ref = cfg.c_m_per_n_gamma * constant_n.powf(cfg.gamma);
        let shape = match cfg.shape {
            softgrip::controller::FingerShape::Rect => Shape::Rect {
                aspect: cfg.half_length_m / a_ref,
            },
            softgrip::controller::FingerShape::Disc => Shape::Disc,
        };
        let pitch = FlsModel::<f64>::new(FlsConfig {
            shape,
            k: cfg.k,
            skew: None,
            order: QuadratureOrder::DEFAULT,
        })
        .map(|m| m.pitch())
        .map_err(|e| {
            bad(format!(
                "gives the fixed patch of the baselines a = {} m, l/a = {}: {e}",
                crate::input::short_num(a_ref),
                crate::input::short_num(cfg.half_length_m / a_ref)
            ))
        })?;
        let dt = cfg.tick_period_s;
        Ok(Some(Self {
            name: name.to_string(),
            kind,
            limits: Limits {
                n_min: cfg.n_min_n,
                n_max: cfg.n_max_n,
                rise: cfg.rise_rate_n_per_s * dt,
                fall: cfg.fall_rate_n_per_s * dt,
            },
            mu: settings.mu.unwrap_or(cfg.mu),
            safety: cfg.safety,
            torsion_arm_m: settings.torsion_arm_m.unwrap_or(a_ref * pitch),
            constant_n,
            command: if kind == Kind::Constant {
                constant_n
            } else {
                cfg.n_min_n
            },
            sent: 0,
            lost: 0,
        }))
    }
}

impl GripController for Baseline {
    fn name(&self) -> &str {
        &self.name
    }

    fn tick(
        &mut self,
        frames: &[(SensorFrame, LinkFate)],
        slip_seen: bool,
    ) -> Result<Option<Answer>, LinkError> {
        // A damaged frame is lost, as the CRC would lose it.
        let mut last = None;
        for (frame, fate) in frames {
            self.sent += 1;
            if *fate == LinkFate::Deliver {
                last = Some(*frame);
            } else {
                self.lost += 1;
            }
        }
        let Some(frame) = last else {
            return Ok(None);
        };
        let [fx, fy] = frame.tangential_force_n;
        let f = f64::from(fx).hypot(f64::from(fy));
        let m = f64::from(frame.torsional_moment_nm).abs();
        if !(f.is_finite() && m.is_finite()) {
            // Bad reading: hold.
            return Ok(Some(Answer {
                command_n: self.command,
                status: "sensor_fault",
            }));
        }
        let (s, mu, arm) = (self.safety, self.mu, self.torsion_arm_m);
        let target = match self.kind {
            Kind::Constant => self.constant_n,
            Kind::Coulomb => s * f / mu,
            Kind::Box => s * box_force_n(f, m, mu, arm),
            Kind::FixedTorsion => s * cone_force_n(f, m, mu, arm),
            Kind::SlipServo => {
                if slip_seen {
                    (self.command * 1.5 + 0.5).min(self.limits.n_max)
                } else {
                    self.limits.n_min
                }
            }
        };
        self.command = match self.kind {
            Kind::Constant => target.clamp(self.limits.n_min, self.limits.n_max),
            // A slip servo jumps up at once and relaxes at the fall rate.
            Kind::SlipServo if slip_seen => target,
            _ => self.limits.step(self.command, target),
        };
        Ok(Some(Answer {
            command_n: self.command,
            status: "none",
        }))
    }

    fn link_summary(&mut self) -> Result<LinkSummary, LinkError> {
        Ok(LinkSummary {
            frames_sent: self.sent,
            frames_received: self.sent - self.lost,
            frames_corrupt: 0,
            frames_lost: self.lost,
            commands_missing: 0,
        })
    }
}
