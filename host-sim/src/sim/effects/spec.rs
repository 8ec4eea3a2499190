//! What an effect declares beside its code: a serde struct of its settings
//! ([`Settings`]: its `[effect.NAME]` keys as fields, today's defaults, the range each
//! setting must lie in, and how the effect is built from them), and where settings come
//! from ([`Source`]: the scene, over its `[effect.NAME]` tables). A leaf: it names no
//! effect, so every effect can use it and the registry ([`super`]) can list them all
//! without a circle.

use super::Effect;
use crate::sim::finger::Finger;
use rand_chacha::ChaCha8Rng;
use serde::de::DeserializeOwned;

/// One setting's value and the closed range `[lo, hi]` it must lie in (a NaN lies in
/// none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// The setting's key (its field's name).
    pub key: &'static str,
    /// Its value.
    pub value: f64,
    /// Least allowed value.
    pub lo: f64,
    /// Greatest allowed value.
    pub hi: f64,
}

impl Range {
    /// `key = value` must lie in `[lo, hi]`.
    pub fn new(key: &'static str, value: f64, lo: f64, hi: f64) -> Self {
        Self { key, value, lo, hi }
    }

    /// Whether the value lies in the range.
    pub fn holds(&self) -> bool {
        (self.lo..=self.hi).contains(&self.value)
    }
}

/// One effect's settings: a struct whose fields are the keys of its `[effect.NAME]` table
/// (every one a number; an integer is taken as a float), with
/// `#[serde(deny_unknown_fields, default)]` and a [`Default`] giving each absent key its
/// default.
pub trait Settings: Default + DeserializeOwned {
    /// The effect's name, as a scene lists it.
    const NAME: &'static str;

    /// Each setting with its allowed range, in the order they are checked (a setting
    /// whose default depends on others, an `Option`, only when given).
    fn ranges(&self) -> Vec<Range>;

    /// The effect, built from its checked settings and what it may need besides: its own
    /// random stream ([`rng`](super::rng)) and the true fingertip.
    fn build(&self, rng: ChaCha8Rng, finger: &Finger) -> Result<Box<dyn Effect>, String>;
}

/// Where settings come from: the scene implements it over its `[effect.NAME]` tables.
pub trait Source {
    /// Why settings could not be read.
    type Error;
    /// The settings of effect `T::NAME`, read and checked (the defaults if it has no
    /// table).
    fn read<T: Settings>(&mut self) -> Result<T, Self::Error>;
}
