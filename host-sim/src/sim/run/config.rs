//! softgrip's configuration for a scene (its finger, `[controller]` table and tick rate),
//! checked once, and configuration errors named by the scene key they come from.

use crate::config::names::scene_key;
use crate::input::{config_reason, short_num};
use crate::sim::scene::{ControllerSettings, Finger, Scene, SceneError};
use softgrip::controller::{Checked, ControllerConfig};
use softgrip::{BuildError, ConfigError, RangeOverflow};

/// softgrip's configuration for a scene, checked: the finger as the scene gives it
/// (without the true contact's skew, which the controller does not know), the scene's
/// `[controller]` fields over it, and the scene's tick rate.
pub fn controller_config(scene: &Scene) -> Result<Checked, SceneError> {
    controller_config_for(&scene.finger, &scene.controller, scene.tick_hz)
}

/// The configuration a finger and tick rate give before the `[controller]` table: the
/// finger's shape, `k`, `mu` (the true one), contact law and half-length, the tick period,
/// and the defaults for the rest (the default mode among them).
pub fn finger_base(f: &Finger, tick_hz: f64) -> ControllerConfig {
    ControllerConfig {
        mu: f.mu,
        shape: f.shape,
        k: f.k,
        skew: None,
        c_m_per_n_gamma: f.c,
        gamma: f.gamma,
        half_length_m: f.half_length_m,
        tick_period_s: 1.0 / tick_hz,
        ..ControllerConfig::default()
    }
}

/// softgrip's configuration for a finger, `[controller]` table and tick rate, checked
/// ([`scene_config`]).
pub fn controller_config_for(
    f: &Finger,
    s: &ControllerSettings,
    tick_hz: f64,
) -> Result<Checked, SceneError> {
    let cfg = scene_config(f, s, tick_hz)?;
    cfg.check().map_err(|e| config_error(&e, s, &cfg))
}

/// The configuration a finger, `[controller]` table and tick rate give, not yet checked:
/// [`finger_base`] with the table's fields over it; the stale timeout is at least one
/// tick.
pub fn scene_config(
    f: &Finger,
    s: &ControllerSettings,
    tick_hz: f64,
) -> Result<ControllerConfig, SceneError> {
    if f.model == crate::sim::finger::FingerModel::Brush && (f.c.is_nan() || f.gamma.is_nan()) {
        return Err(SceneError(
            "finger.c, finger.gamma: a brush finger runs a controller only with its contact \
             law as calibrated from the finger's lab data (host-sim experiment, then host-sim \
             calibrate); nothing is read from the plant"
                .into(),
        ));
    }
    let cfg = crate::config::overlay(&finger_base(f, tick_hz), &s.config)
        .map_err(|e| SceneError(format!("controller.{e}")))?;
    Ok(ControllerConfig {
        stale_timeout_s: cfg.stale_timeout_s.max(1.0 / tick_hz),
        ..cfg
    })
}

/// The scene key of a configuration error: the field's key in `[controller]` when the
/// table sets it, else where the finger or tick rate does (the rename table,
/// [`crate::config::names`]).
fn key_of(field: &str, s: &ControllerSettings) -> String {
    scene_key(field, s.config.contains_key(field))
}

/// A configuration error naming the scene key, its value shortened. The core's derived
/// `aspect` (`l/a`) is put on `finger.half_length_m` with the contact law.
pub fn config_error(e: &ConfigError, s: &ControllerSettings, cfg: &ControllerConfig) -> SceneError {
    if e.param() == "aspect" {
        return SceneError(format!(
            "{} = {} m with {} = {}, {} = {} (a = c·N^gamma) gives a contact of l/a = {} \
             at some force, whose limit surface cannot be computed",
            key_of("half_length_m", s),
            short_num(cfg.half_length_m),
            key_of("c_m_per_n_gamma", s),
            short_num(cfg.c_m_per_n_gamma),
            key_of("gamma", s),
            short_num(cfg.gamma),
            match e {
                ConfigError::OutOfRange { value, .. } => short_num(*value),
                _ => "∞".into(),
            }
        ));
    }
    SceneError(format!("{}: {}", key_of(e.field(), s), config_reason(e)))
}

/// A controller build's error naming the scene keys: a sensor-range overflow names the
/// factor that causes it ([`RangeOverflow`]), `μ` first with the safety factor.
pub fn build_error(e: &BuildError, s: &ControllerSettings, cfg: &ControllerConfig) -> SceneError {
    let overflow = "the worst load the sensor range admits, times safety/mu, overflows the \
                    tick's precision";
    match e {
        BuildError::Config(e) => config_error(e, s, cfg),
        BuildError::RangeOverflow(RangeOverflow::SafetyOverMu) => SceneError(format!(
            "{} = {} with {} = {} (safety/mu = {}): {overflow}",
            key_of("mu", s),
            short_num(cfg.mu),
            key_of("safety", s),
            short_num(cfg.safety),
            short_num(cfg.safety / cfg.mu),
        )),
        BuildError::RangeOverflow(RangeOverflow::SensorRange) => SceneError(format!(
            "{} = {} with {} = {}: {overflow}",
            key_of("force_range_n", s),
            short_num(cfg.force_range_n),
            key_of("moment_range_nm", s),
            short_num(cfg.moment_range_nm),
        )),
        BuildError::RangeOverflow(RangeOverflow::Contact) => SceneError(format!(
            "{} = {} m with {} = {}: {overflow}",
            key_of("half_length_m", s),
            short_num(cfg.half_length_m),
            key_of("c_m_per_n_gamma", s),
            short_num(cfg.c_m_per_n_gamma),
        )),
    }
}
