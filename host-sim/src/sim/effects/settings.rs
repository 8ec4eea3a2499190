//! What an effect is built from, and all it sees of the scene: its own `[effect.NAME]`
//! table (with the file's text, for line numbers in errors), its random stream, and the
//! fingertip. The pipeline makes one per listed effect ([`EffectSettings::of`]); the
//! effects never see the [`Scene`] itself, so the scene format and the effects depend one
//! way only (effects on the scene's types, not the scene on the effects).

use crate::input::{short, short_num};
use crate::sim::scene::{line_of, Finger, Scene, SceneError};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// One effect's settings and the parts of the scene it may use.
#[derive(Debug, Clone, Copy)]
pub struct EffectSettings<'a> {
    name: &'a str,
    table: Option<&'a toml::Table>,
    text: Option<&'a str>,
    seed: u64,
    finger: &'a Finger,
}

impl<'a> EffectSettings<'a> {
    /// The settings of effect `name` in `scene` (`text` is the scene file, for line numbers
    /// in errors).
    pub fn of(scene: &'a Scene, name: &'a str, text: Option<&'a str>) -> Self {
        Self {
            name,
            table: scene.effect.get(name),
            text,
            seed: scene.seed,
            finger: &scene.finger,
        }
    }

    /// The effect's name.
    pub fn name(&self) -> &str {
        self.name
    }

    /// The true fingertip.
    pub fn finger(&self) -> &Finger {
        self.finger
    }

    /// A random stream of the effect's own: the scene seed mixed with the effect's name
    /// (FNV-1a), so listing an effect changes no other effect's random numbers.
    pub fn rng(&self) -> ChaCha8Rng {
        let mut h = 0xcbf2_9ce4_8422_2325u64;
        for b in self.name.bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        ChaCha8Rng::seed_from_u64(self.seed ^ h)
    }

    /// Refuses keys the effect does not know (typos would otherwise be silently ignored).
    pub fn check_keys(&self, known: &[&str]) -> Result<(), SceneError> {
        if let Some(table) = self.table {
            for key in table.keys() {
                if !known.contains(&key.as_str()) {
                    return Err(SceneError(format!(
                        "effect.{}.{key}: unknown setting, expected one of {}",
                        self.name,
                        known.join(", ")
                    )));
                }
            }
        }
        Ok(())
    }

    /// A number from the effect's table, or `default` when absent. A present value of the
    /// wrong type or out of `[lo, hi]` is an error naming the key (and its line).
    pub fn param(&self, key: &str, default: f64, lo: f64, hi: f64) -> Result<f64, SceneError> {
        let effect = self.name;
        let Some(v) = self.table.and_then(|t| t.get(key)) else {
            return Ok(default);
        };
        let x = v
            .as_float()
            .or_else(|| v.as_integer().map(|i| i as f64))
            .ok_or_else(|| {
                SceneError(format!(
                    "effect.{effect}.{key}: {} is not a number",
                    short(&v.to_string())
                ))
            })?;
        if !(lo..=hi).contains(&x) {
            let at = self
                .text
                .and_then(|t| line_of(t, &format!("effect.{effect}"), key))
                .map_or(String::new(), |l| format!("line {l}: "));
            return Err(SceneError(format!(
                "{at}effect.{effect}.{key}: {} is out of range [{lo}, {hi}]",
                short_num(x)
            )));
        }
        Ok(x)
    }
}
