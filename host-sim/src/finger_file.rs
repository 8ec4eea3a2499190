//! A finger file: a TOML with a `[finger]` table, as `host-sim calibrate --out` writes it
//! or as a scene has it. What each command takes from it:
//!
//! - the finger ([`Finger`]: shape, `k`, `mu`, `c`, `gamma`, `half_length_m`, and for a
//!   brush finger its plant);
//! - `[controller]`, if any: the settings a scene gives softgrip, among them the `mu` it
//!   believes when that differs from the finger's true one ([`FingerFile::believed_mu`]);
//! - `[margins]`, if any: the controller's margins measured of the finger
//!   ([`crate::config::margins`]); a command that configures a controller from the file
//!   puts them over its configuration ([`FingerFile::controller_settings`]);
//! - `tick_hz`, if any (default 1 kHz);
//! - `effects` and `[effect.NAME]` tables, if any, read by the commands that need them
//!   (the true skew of `experiment`).
//!
//! Other top-level keys of a scene (its object, task, duration) are ignored, so a scene
//! is a finger file too. Read through [`crate::input::read_capped_text`] (at most
//! [`FINGER_CAP_BYTES`]); every error names the flag and the file.

use crate::input::{read_capped_text, FINGER_CAP_BYTES};
use crate::sim::finger::Finger;
use crate::sim::scene::ControllerSettings;
use crate::CliError;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// The parts of a finger file the commands read.
#[derive(Debug, Clone, Deserialize)]
pub struct FingerFile {
    /// The `[finger]` table.
    pub finger: Finger,
    /// The `[controller]` table (empty when absent).
    #[serde(default)]
    pub controller: ControllerSettings,
    /// The control rate \[Hz\] (a scene's; default 1 kHz).
    #[serde(default = "default_tick_hz")]
    pub tick_hz: f64,
    /// The effects a scene lists.
    #[serde(default)]
    pub effects: Vec<String>,
    /// The effects' settings tables.
    #[serde(default)]
    pub effect: BTreeMap<String, toml::Table>,
    /// The `[margins]` table (empty when absent).
    #[serde(default)]
    pub margins: toml::Table,
}

fn default_tick_hz() -> f64 {
    1000.0
}

impl FingerFile {
    /// Reads `path`, given with the flag `flag` (e.g. `--finger`).
    pub fn load(path: &Path, flag: &str) -> Result<Self, CliError> {
        let text = read_capped_text(path, flag, FINGER_CAP_BYTES)
            .map_err(|e| CliError::Usage(e.to_string()))?;
        let file: Self = toml::from_str(&text).map_err(|e| {
            CliError::Usage(format!(
                "{flag}: {}: {}",
                path.display(),
                e.message().trim()
            ))
        })?;
        // The [controller] keys: configuration fields of their types.
        let base = softgrip::controller::ControllerConfig::default();
        crate::config::overlay(&base, &file.controller.config)
            .map_err(|e| CliError::Usage(format!("{flag}: {}: controller.{e}", path.display())))?;
        crate::config::margins::check(&file.margins)
            .and_then(|()| crate::config::margins::merged(&file.controller.config, &file.margins))
            .map_err(|e| CliError::Usage(format!("{flag}: {}: margins.{e}", path.display())))?;
        Ok(file)
    }

    /// The settings the file gives the controller: its `[controller]` table with the
    /// `[margins]` keys (which [`FingerFile::load`] checked do not repeat its keys).
    pub fn controller_settings(&self) -> ControllerSettings {
        let mut s = self.controller.clone();
        s.config.extend(self.margins.clone());
        s
    }

    /// The friction coefficient the controller believes: `[controller] mu` if the file
    /// sets it, else the finger's.
    pub fn believed_mu(&self) -> f64 {
        self.controller.number("mu").unwrap_or(self.finger.mu)
    }
}
