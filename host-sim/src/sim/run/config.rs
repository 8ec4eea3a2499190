//! softgrip's configuration for a scene (its finger, controller settings and tick rate),
//! and configuration errors named by the scene key they come from.

use crate::sim::scene::{Scene, SceneError};
use softgrip::controller::{ControllerConfig, Mode};

/// softgrip's configuration for a scene: the finger as the scene gives it (without the
/// true contact's skew, which the controller does not know), the scene's controller
/// settings, and the scene's tick rate.
pub fn controller_config(scene: &Scene) -> Result<ControllerConfig, SceneError> {
    controller_config_for(&scene.finger, &scene.controller, scene.tick_hz)
}

/// softgrip's configuration for a finger, controller settings and tick rate (ellipse
/// mode; set `mode` on the result for table mode).
pub fn controller_config_for(
    f: &crate::sim::scene::Finger,
    s: &crate::sim::scene::ControllerSettings,
    tick_hz: f64,
) -> Result<ControllerConfig, SceneError> {
    let d = ControllerConfig::default();
    let cfg = ControllerConfig {
        // The μ the controller believes; the ground truth uses the finger's.
        mu: s.mu.unwrap_or(f.mu),
        shape: f.shape,
        k: f.k,
        skew: None,
        c_m_per_n_gamma: f.c,
        gamma: f.gamma,
        half_length_m: f.half_length_m,
        safety: s.safety.unwrap_or(d.safety),
        n_min_n: s.n_min_n.unwrap_or(d.n_min_n),
        n_max_n: s.n_max_n.unwrap_or(d.n_max_n),
        rise_rate_n_per_s: s.rise_rate_n_per_s.unwrap_or(d.rise_rate_n_per_s),
        fall_rate_n_per_s: s.fall_rate_n_per_s.unwrap_or(d.fall_rate_n_per_s),
        tick_period_s: 1.0 / tick_hz,
        stale_timeout_s: s
            .stale_timeout_s
            .unwrap_or(d.stale_timeout_s)
            .max(1.0 / tick_hz),
        fault_force_n: s.fault_force_n.unwrap_or(d.fault_force_n),
        force_range_n: s.force_range_n.unwrap_or(d.force_range_n),
        moment_range_nm: s.moment_range_nm.unwrap_or(d.moment_range_nm),
        actuator_lag_s: s.actuator_lag_s.unwrap_or(d.actuator_lag_s),
        actuator_slew_n_per_s: s.actuator_slew_n_per_s.unwrap_or(d.actuator_slew_n_per_s),
        mode: Mode::Ellipse,
        ..d
    };
    cfg.validate().map_err(|e| config_error(&e, s, &cfg))?;
    Ok(cfg)
}

/// The scene key a controller configuration field comes from, for errors: the finger's
/// keys under `finger.`, the settings under `controller.` (`mu` under `controller.` only
/// when the scene sets it there); the tick period is `tick_hz`. (The core's derived
/// `aspect`, `l/a`, is reported on `finger.half_length_m` by [`config_error`].)
pub fn scene_key(param: &str, s: &crate::sim::scene::ControllerSettings) -> String {
    match param {
        "mu" if s.mu.is_some() => "controller.mu".into(),
        "mu" => "finger.mu".into(),
        "c_m_per_n_gamma" => "finger.c".into(),
        "gamma" | "k" | "half_length_m" => format!("finger.{param}"),
        "tick_period_s" => "tick_hz".into(),
        other => format!("controller.{other}"),
    }
}

/// A controller configuration error naming the scene key (see [`scene_key`]), its value
/// shortened. The sensor-range overflow (`force_range_n`, `moment_range_nm`: the worst
/// admitted load times `safety/μ` overflows the tick) names μ first, then the safety
/// factor and the range, with their values.
pub fn config_error(
    e: &softgrip::ConfigError,
    s: &crate::sim::scene::ControllerSettings,
    cfg: &ControllerConfig,
) -> SceneError {
    use crate::input::short_num;
    if matches!(e.param(), "force_range_n" | "moment_range_nm") {
        let mu = if s.mu.is_some() {
            "controller.mu"
        } else {
            "finger.mu"
        };
        return SceneError(format!(
            "{mu} = {} with controller.safety = {} (safety/mu = {}) and \
             controller.{} = {}: the worst load the sensor range admits, times safety/mu, \
             overflows the tick's precision",
            short_num(cfg.mu),
            short_num(cfg.safety),
            short_num(cfg.safety / cfg.mu),
            e.param(),
            short_num(if e.param() == "force_range_n" {
                cfg.force_range_n
            } else {
                cfg.moment_range_nm
            })
        ));
    }
    if e.param() == "aspect" {
        return SceneError(format!(
            "finger.half_length_m = {} m with finger.c = {}, finger.gamma = {} \
             (a = c·N^gamma) gives a contact of l/a = {} at some force, whose limit \
             surface cannot be computed",
            short_num(cfg.half_length_m),
            short_num(cfg.c_m_per_n_gamma),
            short_num(cfg.gamma),
            match e {
                softgrip::ConfigError::OutOfRange { value, .. } => short_num(*value),
                _ => "∞".into(),
            }
        ));
    }
    let text = crate::input::config_error("", e);
    let reason = text.split_once(": ").map_or(text.as_str(), |(_, r)| r);
    SceneError(format!("{}: {reason}", scene_key(e.param(), s)))
}
