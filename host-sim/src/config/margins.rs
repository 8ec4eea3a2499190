//! A finger file's `[margins]` table (`host-sim calibrate --cyclic/--hold` writes it;
//! docs/calibration.md): the controller's margins measured of the finger. Its keys are
//! configuration fields ([`KEYS`]) and reach the controller as the rest of its
//! configuration does, through [`super::overlay`]: a command that configures a controller
//! from a finger file puts them over the configuration the finger gives (and the scene's
//! `[controller]` table, with `simulate --finger`), under its own flags.

use super::{overlay, KeyError};
use softgrip::controller::ControllerConfig;

/// The keys a `[margins]` table may have.
pub const KEYS: [&str; 4] = [
    "cyclic_factor",
    "steady_factor",
    "steady_ramp_s",
    "disc_torsion_factor",
];

/// Checks a `[margins]` table: each key one of [`KEYS`], a configuration field of its
/// type whose value the configuration accepts (over the defaults); the error names the
/// key.
pub fn check(margins: &toml::Table) -> Result<(), KeyError> {
    if let Some(key) = margins.keys().find(|k| !KEYS.contains(&k.as_str())) {
        return Err(KeyError {
            key: key.clone(),
            reason: format!("unknown key, expected one of {}", KEYS.join(", ")),
        });
    }
    let cfg = overlay(&ControllerConfig::default(), margins)?;
    cfg.check().map(|_| ()).map_err(|e| KeyError {
        key: e.field().to_string(),
        reason: crate::input::config_reason(&e),
    })
}

/// `config` (a `[controller]` table) with the margins' keys added; a key both set is
/// refused (say it in one place).
pub fn merged(config: &toml::Table, margins: &toml::Table) -> Result<toml::Table, KeyError> {
    let mut out = config.clone();
    for (key, value) in margins {
        if out.contains_key(key) {
            return Err(KeyError {
                key: key.clone(),
                reason: "set in [margins] and in [controller]: keep one".into(),
            });
        }
        out.insert(key.clone(), value.clone());
    }
    Ok(out)
}
