//! Reading one effect's `[effect.NAME]` table into its typed settings: unknown keys,
//! values that are not numbers and values out of range are errors naming
//! `effect.NAME.key` and its line.

use super::{line_of, SceneError};
use crate::input::{short, short_num};
use crate::sim::effects::{self, Settings};
use serde::Deserialize;

/// The scene's [`effects::Source`]: one effect's `[effect.NAME]` table (absent: every
/// setting at its default) and the file's text, for line numbers.
pub(super) struct TableSource<'a> {
    pub(super) table: Option<&'a toml::Table>,
    pub(super) text: &'a str,
}

impl effects::Source for TableSource<'_> {
    type Error = SceneError;

    fn read<T: Settings>(&mut self) -> Result<T, SceneError> {
        let name = T::NAME;
        let bad = |key: &str, why: String| {
            let at = line_of(self.text, &format!("effect.{name}"), key)
                .map_or(String::new(), |l| format!("line {l}: "));
            SceneError(format!("{at}effect.{name}.{}: {why}", short(key)))
        };
        let Some(table) = self.table else {
            return Ok(T::default());
        };
        let known = fields_of::<T>();
        for key in table.keys() {
            if !known.contains(&key.as_str()) {
                let why = if known.is_empty() {
                    format!("unknown setting, {name} has none")
                } else {
                    format!("unknown setting, expected one of {}", known.join(", "))
                };
                return Err(bad(key, why));
            }
        }
        let settings: T = toml::Value::Table(table.clone()).try_into().map_err(|e| {
            // Every setting is a number: name the first value that is not one.
            let culprit = table.iter().find(|(k, v)| {
                let one = toml::Table::from_iter([((*k).clone(), (*v).clone())]);
                toml::Value::Table(one).try_into::<T>().is_err()
            });
            match culprit {
                Some((key, v)) => bad(key, format!("{} is not a number", short(&v.to_string()))),
                None => SceneError(format!("effect.{name}: {}", short(e.message().trim()))),
            }
        })?;
        for r in settings.ranges() {
            if !r.holds() {
                return Err(bad(
                    r.key,
                    format!(
                        "{} is out of range [{}, {}]",
                        short_num(r.value),
                        r.lo,
                        r.hi
                    ),
                ));
            }
        }
        Ok(settings)
    }
}

/// The field names of a struct with a derived `Deserialize` (serde hands them to
/// `deserialize_struct`; this deserializer notes them and stops).
fn fields_of<T: for<'de> Deserialize<'de>>() -> &'static [&'static str] {
    use serde::de::Visitor;

    #[derive(Debug)]
    struct Stop;
    impl std::fmt::Display for Stop {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("stop")
        }
    }
    impl std::error::Error for Stop {}
    impl serde::de::Error for Stop {
        fn custom<M: std::fmt::Display>(_: M) -> Self {
            Stop
        }
    }

    struct Probe<'a>(&'a mut &'static [&'static str]);
    impl<'de> serde::Deserializer<'de> for Probe<'_> {
        type Error = Stop;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Stop> {
            Err(Stop)
        }
        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _name: &'static str,
            fields: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Stop> {
            *self.0 = fields;
            Err(Stop)
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
            identifier ignored_any
        }
    }

    let mut fields: &'static [&'static str] = &[];
    let _ = T::deserialize(Probe(&mut fields));
    fields
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::effects::EffectSettings;
    use crate::sim::effects::{
        gravity::GravitySettings, link_latency::LinkLatencySettings,
        sensor_noise::SensorNoiseSettings, skewed_pressure::SkewedPressureSettings, NAMES,
    };
    use crate::sim::scene::Scene;

    const BASE: &str = "duration_s = 0.1\neffects = [EFFECTS]\n[finger]\nmu = 0.8\n\
                        c = 2.5e-3\ngamma = 0.5\n[object]\nmass_kg = 0.2\n";

    fn scene(effects: &str, extra: &str) -> Result<Scene, String> {
        Scene::parse(&format!("{}{extra}", BASE.replace("EFFECTS", effects))).map_err(|e| e.0)
    }

    #[test]
    fn every_setting_with_a_range_is_a_field_and_every_field_has_one() {
        fn check<T: Settings>(given: T) {
            let fields = fields_of::<T>();
            let keys: Vec<&str> = given.ranges().iter().map(|r| r.key).collect();
            assert_eq!(keys, fields, "{}", T::NAME);
        }
        use crate::sim::effects::*;
        check(GravitySettings::default());
        check(disturbance::DisturbanceSettings::default());
        check(SensorNoiseSettings::default());
        check(sensor_faults::SensorFaultsSettings::default());
        check(slip_sensor::SlipSensorSettings::default());
        check(LinkLatencySettings::default());
        check(link_faults::LinkFaultsSettings::default());
        check(actuator::ActuatorSettings::default());
        check(creep::CreepSettings::default());
        check(partial_slip::PartialSlipSettings::default());
        check(SkewedPressureSettings {
            locus_over_a: Some(0.0),
            ..Default::default()
        });
    }

    #[test]
    fn listed_effects_get_their_settings_in_pipeline_order_and_unlisted_ones_are_ignored() {
        let all = NAMES
            .iter()
            .map(|n| format!("\"{n}\""))
            .collect::<Vec<_>>()
            .join(", ");
        let s = scene(&all, "").unwrap();
        let names: Vec<&str> = s.effect_settings.iter().map(|e| e.name()).collect();
        assert_eq!(names, NAMES);
        // Listed twice and out of order: once, in pipeline order; a bad table of an
        // unlisted effect is not read.
        let s = scene(
            "\"sensor_noise\", \"gravity\", \"sensor_noise\"",
            "[effect.sensor_noise]\nforce_sd_n = 3\nbias_force_n = -0.5\n\
             [effect.creep]\nnope = \"x\"\n",
        )
        .unwrap();
        assert_eq!(
            s.effect_settings,
            [
                EffectSettings::Gravity(GravitySettings::default()),
                EffectSettings::SensorNoise(SensorNoiseSettings {
                    force_sd_n: 3.0,
                    bias_force_n: -0.5,
                    ..Default::default()
                }),
            ]
        );
        let s = scene(
            "\"link_latency\", \"skewed_pressure\"",
            "[effect.link_latency]\ndelay_ticks = 7\n[effect.skewed_pressure]\nalpha = 2\n",
        )
        .unwrap();
        assert_eq!(
            s.effect_settings,
            [
                EffectSettings::LinkLatency(LinkLatencySettings { delay_ticks: 7.0 }),
                EffectSettings::SkewedPressure(SkewedPressureSettings {
                    alpha: 2.0,
                    locus_over_a: None,
                    ..Default::default()
                }),
            ]
        );
    }

    #[test]
    fn bad_settings_name_the_key_the_value_and_the_line() {
        let noise = "\"gravity\", \"sensor_noise\"";
        for (effects, extra, want) in [
            (
                noise,
                "[effect.sensor_noise]\nforce_sd_n = 1e9\n",
                "line 10: effect.sensor_noise.force_sd_n: 1e9 is out of range [0, 1000000]",
            ),
            (
                noise,
                "[effect.sensor_noise]\nforce_sd_n = nan\n",
                "line 10: effect.sensor_noise.force_sd_n: NaN is out of range [0, 1000000]",
            ),
            (
                noise,
                "[effect.sensor_noise]\nmoment_sd_nm = -1\nforce_sd_n = -2\n",
                "line 11: effect.sensor_noise.force_sd_n: -2 is out of range [0, 1000000]",
            ),
            (
                noise,
                "[effect.sensor_noise]\nforce_sd_n = \"abc\"\n",
                "line 10: effect.sensor_noise.force_sd_n: \"abc\" is not a number",
            ),
            (
                noise,
                "[effect.sensor_noise]\nbias_force_n = true\n",
                "line 10: effect.sensor_noise.bias_force_n: true is not a number",
            ),
            (
                noise,
                "[effect.sensor_noise]\nforce_sd = 0.1\n",
                "line 10: effect.sensor_noise.force_sd: unknown setting, expected one of \
                 force_sd_n, moment_sd_nm, normal_sd_n, bias_force_n, bias_moment_nm",
            ),
            (
                "\"partial_slip\"",
                "[effect.partial_slip]\nx = 1\n",
                "line 10: effect.partial_slip.x: unknown setting, partial_slip has none",
            ),
            (
                "\"skewed_pressure\"",
                "[effect.skewed_pressure]\nlocus_over_a = 2\n",
                "line 10: effect.skewed_pressure.locus_over_a: 2 is out of range [0, 1]",
            ),
            (
                "\"sensor_faults\"",
                "[effect.sensor_faults]\nsaturation_n = -1\n",
                "line 10: effect.sensor_faults.saturation_n: -1 is out of range [0, inf]",
            ),
        ] {
            assert_eq!(scene(effects, extra).unwrap_err(), want);
        }
    }
}
