//! The effects' settings, typed. Each effect declares, beside its code, a serde struct of
//! its settings ([`Settings`]: its `[effect.NAME]` keys as fields, today's defaults, and
//! the range each setting must lie in); [`EffectSettings`] holds one of them per effect.
//!
//! The scene reads them: once, while it is parsed, it turns each listed effect's table
//! into that effect's struct through a [`Source`] ([`EffectSettings::read`] picks the
//! struct by name), checks the ranges, and reports a bad key or value with its line. The
//! effects only ever receive their own struct, checked; they never see the scene or its
//! TOML, and this module names no scene type: the scene depends on the effects' settings,
//! not the other way round.

use super::{
    actuator::ActuatorSettings, creep::CreepSettings, disturbance::DisturbanceSettings,
    gravity::GravitySettings, link_faults::LinkFaultsSettings, link_latency::LinkLatencySettings,
    partial_slip::PartialSlipSettings, sensor_faults::SensorFaultsSettings,
    sensor_noise::SensorNoiseSettings, skewed_pressure::SkewedPressureSettings,
    slip_sensor::SlipSensorSettings,
};
use serde::de::DeserializeOwned;

/// Every effect a scene may list, in pipeline order.
pub const NAMES: [&str; 11] = [
    "gravity",
    "disturbance",
    "sensor_noise",
    "sensor_faults",
    "slip_sensor",
    "link_latency",
    "link_faults",
    "actuator",
    "creep",
    "partial_slip",
    "skewed_pressure",
];

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
}

/// Where settings come from: the scene implements it over its `[effect.NAME]` tables.
pub trait Source {
    /// Why settings could not be read.
    type Error;
    /// The settings of effect `T::NAME`, read and checked (the defaults if it has no
    /// table).
    fn read<T: Settings>(&mut self) -> Result<T, Self::Error>;
}

/// One listed effect's settings.
#[derive(Debug, Clone, PartialEq)]
#[allow(missing_docs)]
pub enum EffectSettings {
    Gravity(GravitySettings),
    Disturbance(DisturbanceSettings),
    SensorNoise(SensorNoiseSettings),
    SensorFaults(SensorFaultsSettings),
    SlipSensor(SlipSensorSettings),
    LinkLatency(LinkLatencySettings),
    LinkFaults(LinkFaultsSettings),
    Actuator(ActuatorSettings),
    Creep(CreepSettings),
    PartialSlip(PartialSlipSettings),
    SkewedPressure(SkewedPressureSettings),
}

impl EffectSettings {
    /// The settings of the effect called `name`, read from `source`; `None` if no effect
    /// has that name (the names are [`NAMES`]).
    pub fn read<S: Source>(name: &str, source: &mut S) -> Option<Result<Self, S::Error>> {
        Some(match name {
            "gravity" => source.read().map(Self::Gravity),
            "disturbance" => source.read().map(Self::Disturbance),
            "sensor_noise" => source.read().map(Self::SensorNoise),
            "sensor_faults" => source.read().map(Self::SensorFaults),
            "slip_sensor" => source.read().map(Self::SlipSensor),
            "link_latency" => source.read().map(Self::LinkLatency),
            "link_faults" => source.read().map(Self::LinkFaults),
            "actuator" => source.read().map(Self::Actuator),
            "creep" => source.read().map(Self::Creep),
            "partial_slip" => source.read().map(Self::PartialSlip),
            "skewed_pressure" => source.read().map(Self::SkewedPressure),
            _ => return None,
        })
    }

    /// The effect's name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Gravity(_) => GravitySettings::NAME,
            Self::Disturbance(_) => DisturbanceSettings::NAME,
            Self::SensorNoise(_) => SensorNoiseSettings::NAME,
            Self::SensorFaults(_) => SensorFaultsSettings::NAME,
            Self::SlipSensor(_) => SlipSensorSettings::NAME,
            Self::LinkLatency(_) => LinkLatencySettings::NAME,
            Self::LinkFaults(_) => LinkFaultsSettings::NAME,
            Self::Actuator(_) => ActuatorSettings::NAME,
            Self::Creep(_) => CreepSettings::NAME,
            Self::PartialSlip(_) => PartialSlipSettings::NAME,
            Self::SkewedPressure(_) => SkewedPressureSettings::NAME,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A [`Source`] of the defaults.
    struct Defaults;

    impl Source for Defaults {
        type Error = std::convert::Infallible;
        fn read<T: Settings>(&mut self) -> Result<T, Self::Error> {
            Ok(T::default())
        }
    }

    #[test]
    fn every_name_has_its_settings_and_every_default_lies_in_its_range() {
        let names: Vec<&str> = NAMES
            .iter()
            .map(|n| {
                EffectSettings::read(n, &mut Defaults)
                    .unwrap()
                    .unwrap()
                    .name()
            })
            .collect();
        assert_eq!(names, NAMES);
        assert!(EffectSettings::read("nope", &mut Defaults).is_none());
        fn check<T: Settings>() {
            for r in T::default().ranges() {
                assert!(r.holds(), "{}.{}: {r:?}", T::NAME, r.key);
            }
        }
        check::<GravitySettings>();
        check::<DisturbanceSettings>();
        check::<SensorNoiseSettings>();
        check::<SensorFaultsSettings>();
        check::<SlipSensorSettings>();
        check::<LinkLatencySettings>();
        check::<LinkFaultsSettings>();
        check::<ActuatorSettings>();
        check::<CreepSettings>();
        check::<PartialSlipSettings>();
        check::<SkewedPressureSettings>();
    }
}
