//! Grasp scenes: TOML files that say what to simulate and which effects to include.
//!
//! An example (illustrative values; `host-sim/tests/simulate.rs` runs the shipped scenes
//! of `host-sim/scenes/`, written in this form):
//! ```toml
//! description = "Lift a 200 g object and hold it"
//! duration_s = 3.0
//! tick_hz = 1000.0
//! seed = 1
//! expected_slip = false
//! effects = ["gravity", "sensor_noise"]
//! [finger]            # the true fingertip (the controller is told the same, less skew)
//! shape = "rect"      # rect | disc
//! k = 2.0
//! mu = 0.8
//! c = 2.5e-3          # a = c·N^γ [m]
//! gamma = 0.5
//! half_length_m = 0.01
//! young_modulus_pa = 3e5
//! poisson = 0.45
//! [object]
//! mass_kg = 0.2
//! com_offset_m = 0.02      # lever arm of gravity about the grasp axis
//! inertia_kg_m2 = 2e-4     # about the grasp axis
//! [[task]]                 # load phases; they add up where they overlap
//! kind = "lift"            # lift | hold | twist | shake | pull
//! start_s = 0.2
//! end_s = 0.8
//! accel_m_s2 = 4.0
//! [controller]             # any field of softgrip's ControllerConfig (all optional)
//! safety = 1.3
//! mu = 0.7                 # the μ the controller believes (default: [finger] mu, the true one)
//! actuator_lag_s = 0.015   # the measured actuator lag [s] (default 0: no anticipation)
//! actuator_slew_n_per_s = 300.0  # the measured slew limit [N/s] (default: unlimited)
//! [effect.sensor_noise]    # settings of an effect (read only if it is listed)
//! force_sd_n = 0.02
//! ```
//!
//! A bad file is reported with the key and its line.
//!
//! The effects' settings are typed: each effect declares its settings struct
//! ([`effects::Settings`]), and [`Scene::parse`] reads each listed effect's
//! `[effect.NAME]` table into it, once, checking keys, types and ranges
//! ([`Scene::effect_settings`]). The effects are then built from those structs alone; they
//! never see the scene.

use crate::input::{short, short_num, SCENE_CAP_BYTES};
use crate::sim::effects::{self, EffectSettings, NAMES as EFFECT_NAMES};
pub use crate::sim::finger::{Finger, FingerModel};
pub use crate::sim::task::Phase;
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

mod effect_settings;
use effect_settings::TableSource;

/// The whole scene.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Name; defaults to the file stem.
    #[serde(default)]
    pub name: String,
    /// What the scene exercises, for people.
    #[serde(default)]
    pub description: String,
    /// Simulated time \[s\].
    pub duration_s: f64,
    /// Control rate \[Hz\]: one plant step and one controller tick per period.
    #[serde(default = "default_tick_hz")]
    pub tick_hz: f64,
    /// Seed of every random effect.
    #[serde(default)]
    pub seed: u64,
    /// `true` for an overload no allowed force can hold.
    #[serde(default)]
    pub expected_slip: bool,
    /// The effects to simulate, by name. Only these are built and stepped.
    #[serde(default)]
    pub effects: Vec<String>,
    /// The fingertip.
    pub finger: Finger,
    /// The held object.
    pub object: Object,
    /// The load phases.
    #[serde(default)]
    pub task: Vec<Phase>,
    /// Controller settings.
    #[serde(default)]
    pub controller: ControllerSettings,
    /// The controller's margins measured of the finger (`[margins]`, as a calibrated
    /// finger TOML has it; [`crate::config::margins`]): [`Scene::parse`] adds them to
    /// `controller`.
    #[serde(default)]
    pub margins: toml::Table,
    /// Settings of each effect, by name, as written (ignored for effects not listed); read
    /// into [`Scene::effect_settings`].
    #[serde(default)]
    pub effect: BTreeMap<String, toml::Table>,
    /// The listed effects' settings, typed and checked, in pipeline order
    /// ([`effects::NAMES`]): filled by [`Scene::parse`] from `effect`.
    #[serde(skip)]
    pub effect_settings: Vec<EffectSettings>,
}

fn default_tick_hz() -> f64 {
    1000.0
}

/// The held object.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Object {
    /// Mass \[kg\].
    pub mass_kg: f64,
    /// Distance of the centre of mass from the grasp axis \[m\]: gravity's lever arm.
    #[serde(default)]
    pub com_offset_m: f64,
    /// Moment of inertia about the grasp axis [kg·m²].
    #[serde(default = "default_inertia")]
    pub inertia_kg_m2: f64,
}

fn default_inertia() -> f64 {
    1e-4
}

/// The scene's `[controller]` table: softgrip's configuration fields, overlaid on the
/// configuration the finger gives (`crate::sim::run::controller_config`; `mu` defaults to
/// the finger's, the true one, which the ground truth always uses), and the baselines'
/// own settings.
#[derive(Debug, Clone, Default, Deserialize)]
pub struct ControllerSettings {
    /// The force of the `constant` baseline \[N\]; default the fault force.
    pub constant_force_n: Option<f64>,
    /// The μ the cone, box and fixed-torsion baselines believe (e.g. from a slip test);
    /// default softgrip's `mu`.
    pub baseline_mu: Option<f64>,
    /// The torsion arm `μ_t/μ` \[m\] of the box and fixed-torsion baselines' fixed patch
    /// (e.g. from a torsion test); default `a·pitch` of the contact at
    /// `constant_force_n`.
    pub baseline_torsion_arm_m: Option<f64>,
    /// Fields of softgrip's `ControllerConfig`, as written (read by
    /// [`crate::config::overlay`]: a key it does not have is an error).
    #[serde(flatten)]
    pub config: toml::Table,
}

impl ControllerSettings {
    /// The baselines' settings, with `fault_force_n` \[N\] the constant force's default.
    pub fn baseline(&self, fault_force_n: f64) -> crate::sim::controllers::BaselineSettings {
        crate::sim::controllers::BaselineSettings {
            constant_n: self.constant_force_n.unwrap_or(fault_force_n),
            mu: self.baseline_mu,
            torsion_arm_m: self.baseline_torsion_arm_m,
        }
    }

    /// The number the table sets for `field`, if any (an integer is read as a float, as
    /// the configuration reads it).
    pub fn number(&self, field: &str) -> Option<f64> {
        let v = self.config.get(field)?;
        v.as_float().or_else(|| v.as_integer().map(|i| i as f64))
    }

    /// Sets `field` to `value`.
    pub fn set(&mut self, field: &str, value: f64) {
        self.config.insert(field.to_string(), value.into());
    }
}

/// Most ticks a scene may have (1e8: 28 hours at 1 kHz). `simulate` streams its samples,
/// so the cap bounds run time, not memory.
pub const MAX_TICKS: f64 = 1e8;

/// A scene file that could not be used.
#[derive(Debug)]
pub struct SceneError(pub String);

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SceneError {}

/// The 1-based line where `key` is set in `[table]` (or at the top level for `""`), if it
/// is written on a line of its own.
pub fn line_of(text: &str, table: &str, key: &str) -> Option<usize> {
    let mut current = String::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if let Some(name) = line
            .strip_prefix("[[")
            .and_then(|l| l.strip_suffix("]]"))
            .or_else(|| line.strip_prefix('[').and_then(|l| l.strip_suffix(']')))
        {
            current = name.trim().to_string();
            continue;
        }
        let Some((k, _)) = line.split_once('=') else {
            continue;
        };
        if current == table && k.trim() == key {
            return Some(i + 1);
        }
    }
    None
}

impl Scene {
    /// The scene's effects, built: [`effects::Pipeline::new`] from its typed settings
    /// ([`Scene::effect_settings`], read and checked when the scene was parsed), seed and
    /// finger.
    pub fn pipeline(&self) -> Result<effects::Pipeline, SceneError> {
        effects::Pipeline::new(&self.effect_settings, self.seed, &self.finger).map_err(SceneError)
    }

    /// Reads and checks a scene file. Errors name the file, the key and its line. The
    /// file is read with a cap of [`SCENE_CAP_BYTES`] (`crate::input`): a larger or
    /// endless one (`/dev/zero`) is refused after reading at most the cap.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let shown = short(&path.display().to_string());
        let text = crate::input::read_capped_text(path, "scene", SCENE_CAP_BYTES)
            .map_err(|e| SceneError(e.message))?;
        let mut scene = Self::parse(&text).map_err(|e| SceneError(format!("{shown}: {e}")))?;
        if scene.name.is_empty() {
            scene.name = path
                .file_stem()
                .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        }
        Ok(scene)
    }

    /// Parses and checks scene text.
    pub fn parse(text: &str) -> Result<Self, SceneError> {
        let mut scene: Scene = toml::from_str(text).map_err(|e| {
            // toml's message: "TOML parse error at line L, column C\n  |\nL | ...\n ... msg".
            let msg = e.message().trim().to_string();
            let line = e
                .span()
                .and_then(|s| text.get(..s.start))
                .map(|before| before.matches('\n').count() + 1);
            match line {
                Some(l) => SceneError(format!("line {l}: {msg}")),
                None => SceneError(msg),
            }
        })?;
        scene.take_margins(text)?;
        scene.check(text)?;
        scene.effect_settings = scene.read_effect_settings(text)?;
        Ok(scene)
    }

    /// Checks `[margins]` and adds its keys to `[controller]` (a key in both is refused),
    /// each error naming `margins.KEY` and its line.
    fn take_margins(&mut self, text: &str) -> Result<(), SceneError> {
        use crate::config::margins::{check, merged};
        let config = check(&self.margins)
            .and_then(|()| merged(&self.controller.config, &self.margins))
            .map_err(|e| {
                let at = line_of(text, "margins", &e.key)
                    .map_or(String::new(), |l| format!("line {l}: "));
                SceneError(format!("{at}margins.{e}"))
            })?;
        self.controller.config = config;
        Ok(())
    }

    /// The scene with another finger (`simulate --finger`): `finger` replaces its
    /// `[finger]`, and `believed_mu`, if given, its `[controller] mu`. The whole scene is
    /// checked again (without line numbers: the finger came from another file).
    pub fn with_finger(
        mut self,
        finger: Finger,
        believed_mu: Option<f64>,
    ) -> Result<Self, SceneError> {
        self.finger = finger;
        if let Some(mu) = believed_mu {
            self.controller.set("mu", mu);
        }
        self.check("")?;
        Ok(self)
    }

    /// Reads each listed effect's `[effect.NAME]` table into its typed settings (the one
    /// place effect settings are read), in pipeline order. A key the effect does not
    /// know, a value that is not a number, or one out of its range is an error naming
    /// `effect.NAME.key` (and its line).
    fn read_effect_settings(&self, text: &str) -> Result<Vec<EffectSettings>, SceneError> {
        let mut settings = Vec::new();
        for &name in EFFECT_NAMES {
            if !self.effects.iter().any(|e| e == name) {
                continue;
            }
            let mut source = TableSource {
                table: self.effect.get(name),
                text,
            };
            if let Some(s) = EffectSettings::read(name, &mut source) {
                settings.push(s?);
            }
        }
        Ok(settings)
    }

    /// Whether the finger is a brush finger whose controller beliefs `c` and `gamma` are
    /// not given (the lab has yet to calibrate it: `experiment` can still measure it, but
    /// no controller can run on it).
    fn brush_uncalibrated(&self) -> bool {
        self.finger.model == FingerModel::Brush
            && self.finger.c.is_nan()
            && self.finger.gamma.is_nan()
    }

    /// The `[finger]` keys that depend on `model`: `c` and `gamma` for `fls` (and no
    /// `[finger.brush]`); for `brush`, the brush's parameters, `c` and `gamma` both given
    /// or both left to the fit, and no effect that models softgrip's own contact.
    fn check_model(&self, text: &str) -> Result<(), SceneError> {
        let at = |table: &str, key: &str| {
            line_of(text, table, key).map_or(String::new(), |l| format!("line {l}: "))
        };
        let f = &self.finger;
        if f.model == FingerModel::Fls {
            if f.brush.is_some() {
                return Err(SceneError(
                    "finger.brush: only for finger.model = \"brush\"".into(),
                ));
            }
            if !(f.c > 0.0 && f.c.is_finite()) {
                return Err(SceneError(format!(
                    "{}finger.c: {} must be a finite number > 0 (required for \
                     finger.model = \"fls\")",
                    at("finger", "c"),
                    short_num(f.c)
                )));
            }
            return Ok(());
        }
        if let Err(e) = f.brush_finger() {
            return Err(SceneError(format!("{}{e}", at(e.table, e.param.key))));
        }
        if f.c.is_nan() != f.gamma.is_nan() {
            return Err(SceneError(format!(
                "{}finger.c, finger.gamma: give both (the controller's contact law, \
                 calibrated from the finger's lab data) or neither (a finger to measure)",
                at("finger", if f.c.is_nan() { "gamma" } else { "c" })
            )));
        }
        if !(f.c.is_nan() || f.c > 0.0 && f.c.is_finite()) {
            return Err(SceneError(format!(
                "{}finger.c: {} must be a finite number > 0",
                at("finger", "c"),
                short_num(f.c)
            )));
        }
        for name in &self.effects {
            if matches!(name.as_str(), "skewed_pressure" | "creep" | "partial_slip") {
                return Err(SceneError(format!(
                    "{}effects: \"{name}\" models softgrip's own contact and does not apply \
                     to finger.model = \"brush\" (the brush plant has its own skew, creep \
                     and partial slip)",
                    at("", "effects")
                )));
            }
        }
        Ok(())
    }

    /// The `[controller]` table's keys: each a configuration field with a value of its type
    /// ([`crate::config::overlay`]), named with its line.
    fn check_controller_keys(&self, text: &str) -> Result<(), SceneError> {
        let base = softgrip::controller::ControllerConfig::default();
        crate::config::overlay(&base, &self.controller.config)
            .map(|_| ())
            .map_err(|e| {
                let at = line_of(text, "controller", &e.key)
                    .map_or(String::new(), |l| format!("line {l}: "));
                SceneError(format!("{at}controller.{e}"))
            })
    }

    fn check(&self, text: &str) -> Result<(), SceneError> {
        self.check_length(text)?;
        self.check_effect_names(text)?;
        positive(text, "finger", "mu", self.finger.mu)?;
        self.check_controller_keys(text)?;
        self.check_model(text)?;
        self.check_finger(text)?;
        positive(text, "object", "mass_kg", self.object.mass_kg)?;
        positive(text, "object", "inertia_kg_m2", self.object.inertia_kg_m2)?;
        if !self.object.com_offset_m.is_finite() {
            return Err(bad(text, "object", "com_offset_m", "must be finite".into()));
        }
        for p in &self.task {
            let (start_s, end_s) = p.span_s();
            if p.values().iter().any(|v| !v.is_finite()) || end_s <= start_s {
                return Err(bad(
                    text,
                    "task",
                    "end_s",
                    format!(
                        "phase \"{}\" needs finite values and end_s > start_s",
                        p.kind()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `duration_s` and `tick_hz`: between one tick and [`MAX_TICKS`].
    fn check_length(&self, text: &str) -> Result<(), SceneError> {
        positive(text, "", "duration_s", self.duration_s)?;
        positive(text, "", "tick_hz", self.tick_hz)?;
        let ticks = (self.duration_s * self.tick_hz).round();
        let at = format!(
            "{} s at tick_hz {}",
            short_num(self.duration_s),
            short_num(self.tick_hz)
        );
        if ticks > MAX_TICKS {
            return Err(bad(
                text,
                "",
                "duration_s",
                format!("{at} is more than 1e8 ticks"),
            ));
        }
        if ticks < 1.0 {
            return Err(bad(
                text,
                "",
                "duration_s",
                format!("{at} is 0 ticks; a scene needs at least one (duration_s >= 0.5/tick_hz)"),
            ));
        }
        Ok(())
    }

    /// Every effect listed in `effects` and every `[effect.NAME]` table names an effect.
    fn check_effect_names(&self, text: &str) -> Result<(), SceneError> {
        for name in &self.effects {
            if !EFFECT_NAMES.contains(&name.as_str()) {
                return Err(bad(
                    text,
                    "",
                    "effects",
                    format!(
                        "unknown effect \"{}\", expected one of {}",
                        short(name),
                        EFFECT_NAMES.join(", ")
                    ),
                ));
            }
        }
        for name in self.effect.keys() {
            if !EFFECT_NAMES.contains(&name.as_str()) {
                return Err(bad(
                    text,
                    &format!("effect.{}", short(name)),
                    "",
                    format!("unknown effect \"{}\"", short(name)),
                ));
            }
        }
        Ok(())
    }

    /// The finger's length, stiffness, pressure exponent, contact law and Poisson ratio.
    fn check_finger(&self, text: &str) -> Result<(), SceneError> {
        let f = &self.finger;
        positive(text, "finger", "half_length_m", f.half_length_m)?;
        positive(text, "finger", "young_modulus_pa", f.young_modulus_pa)?;
        if f.k.is_nan() || f.k < 1.0 {
            let why = format!("{} must be >= 1", short_num(f.k));
            return Err(bad(text, "finger", "k", why));
        }
        if !(0.0..=0.5).contains(&f.gamma) && !self.brush_uncalibrated() {
            let why = format!("{} must lie in [0, 1/2]", short_num(f.gamma));
            return Err(bad(text, "finger", "gamma", why));
        }
        if !(0.0..0.5).contains(&f.poisson) {
            let why = format!("{} must lie in [0, 1/2)", short_num(f.poisson));
            return Err(bad(text, "finger", "poisson", why));
        }
        Ok(())
    }
}

/// A bad setting `table.key` (or a top-level `key`), with its line in `text` if found.
fn bad(text: &str, table: &str, key: &str, why: String) -> SceneError {
    let at = line_of(text, table, key).map_or(String::new(), |l| format!("line {l}: "));
    let full = if table.is_empty() {
        key.to_string()
    } else {
        format!("{table}.{key}")
    };
    SceneError(format!("{at}{full}: {why}"))
}

/// `table.key = v` must be a finite number > 0.
fn positive(text: &str, table: &str, key: &str, v: f64) -> Result<(), SceneError> {
    if v > 0.0 && v.is_finite() {
        Ok(())
    } else {
        let why = format!("{} must be a finite number > 0", short_num(v));
        Err(bad(text, table, key, why))
    }
}
