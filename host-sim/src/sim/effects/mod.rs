//! The effects a scene may call for. Each is a module with its source; the simulator
//! builds its step pipeline from the scene's `effects` list, and an effect that is not
//! listed is neither built nor stepped (nor does it draw random numbers: each effect owns
//! a random stream seeded from the scene seed and its own name, [`rng`]).
//!
//! Each effect's module also declares its settings: a serde struct (`GravitySettings`,
//! `SensorNoiseSettings`, ...) of its `[effect.NAME]` keys with their defaults and
//! ranges ([`Settings`], in [`spec`]); [`EffectSettings`] is one of them, and the
//! registry below lists the effects ([`NAMES`]). The scene reads and checks every listed effect's settings once,
//! when it is parsed
//! ([`Scene::effect_settings`](crate::sim::scene::Scene::effect_settings)); [`build`]
//! then makes each effect from its own struct and what it needs besides (its random
//! stream, or the fingertip). An effect never sees the
//! [`Scene`](crate::sim::scene::Scene) or its TOML.
//!
//! An effect hooks into one or more stages of a plant step, in this order:
//! 1. [`Effect::load`]: forces and moments on the object (gravity, disturbances);
//! 2. [`Effect::sense`]: what the fingertip sensor reports (noise, bias, faults);
//! 3. [`Effect::link`]: what the serial link does to the sensor frame on its way
//!    (latency, faults);
//! 4. [`Effect::actuate`]: how the commanded normal force becomes the applied one (lag,
//!    limits);
//! 5. [`Effect::contact`]: the true contact (creep of its size, partial slip).
//!
//! Skewed pressure in the true contact changes the true limit surface itself, so it acts
//! when the ground truth is built ([`Effect::true_skew`]).

pub mod spec;

/// The registry: declares each effect's module and, from the same list, [`NAMES`] and
/// [`EffectSettings`] (its variants, reading one by name, its name, building its effect).
/// A new effect is its file (its settings struct implementing [`Settings`], with `NAME`
/// and `build`) plus one line in the list below.
macro_rules! effects {
    ($($module:ident :: $settings:ident => $variant:ident,)*) => {
        $(pub mod $module;)*

        /// Every effect a scene may list, in pipeline order.
        pub const NAMES: &[&str] = &[$(<$module::$settings as Settings>::NAME),*];

        /// One listed effect's settings.
        #[derive(Debug, Clone, PartialEq)]
        #[allow(missing_docs)]
        pub enum EffectSettings {
            $($variant($module::$settings),)*
        }

        impl EffectSettings {
            /// The settings of the effect called `name`, read from `source`; `None` if no
            /// effect has that name (the names are [`NAMES`]).
            pub fn read<S: Source>(name: &str, source: &mut S) -> Option<Result<Self, S::Error>> {
                $(if name == <$module::$settings as Settings>::NAME {
                    return Some(source.read().map(Self::$variant));
                })*
                None
            }

            /// The effect's name.
            pub fn name(&self) -> &'static str {
                match self {
                    $(Self::$variant(_) => <$module::$settings as Settings>::NAME,)*
                }
            }

            /// Each setting with its allowed range.
            pub fn ranges(&self) -> Vec<Range> {
                match self {
                    $(Self::$variant(s) => s.ranges(),)*
                }
            }

            fn build(&self, rng: ChaCha8Rng, finger: &Finger) -> Result<Box<dyn Effect>, String> {
                match self {
                    $(Self::$variant(s) => s.build(rng, finger),)*
                }
            }
        }
    };
}

effects! {
    gravity::GravitySettings => Gravity,
    disturbance::DisturbanceSettings => Disturbance,
    sensor_noise::SensorNoiseSettings => SensorNoise,
    sensor_faults::SensorFaultsSettings => SensorFaults,
    slip_sensor::SlipSensorSettings => SlipSensor,
    link_latency::LinkLatencySettings => LinkLatency,
    link_faults::LinkFaultsSettings => LinkFaults,
    actuator::ActuatorSettings => Actuator,
    creep::CreepSettings => Creep,
    partial_slip::PartialSlipSettings => PartialSlip,
    skewed_pressure::SkewedPressureSettings => SkewedPressure,
}

use crate::sim::finger::Finger;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use softgrip::controller::SkewParams;
use softgrip::protocol::SensorFrame;
pub use spec::{Range, Settings, Source};
use std::time::{Duration, Instant};

/// The plant's state as the effects see it during one step. Loads are on the whole
/// object; the two fingertips of the pinch each carry half.
#[derive(Debug, Clone, Default)]
pub struct World {
    /// Time \[s\].
    pub t_s: f64,
    /// Step \[s\].
    pub dt_s: f64,
    /// Object mass \[kg\].
    pub mass_kg: f64,
    /// Inertia about the grasp axis [kg·m²].
    pub inertia_kg_m2: f64,
    /// Lever arm of gravity about the grasp axis \[m\].
    pub com_offset_m: f64,
    /// How much of the object's weight the grasp carries (0 on the table, 1 lifted).
    pub support_fraction: f64,
    /// Tangential force the grasp must apply to the object: x along the cylinder axis,
    /// y across it (vertical) \[N\].
    pub force_n: [f64; 2],
    /// Moment the grasp must apply about its axis [N·m].
    pub moment_nm: f64,
    /// The controller's latest command \[N\].
    pub command_n: f64,
    /// The normal force each fingertip applies \[N\].
    pub normal_n: f64,
    /// Equilibrium contact half-width at `normal_n`, `c·N^γ` \[m\].
    pub half_width_eq_m: f64,
    /// True contact half-width \[m\] (equal to the equilibrium unless creep is on).
    pub half_width_m: f64,
    /// Tangential micro-displacement before gross slip (Eq. 5) \[m\], when partial slip
    /// is on.
    pub micro_slip_m: f64,
    /// The true utilisation of the last tick's load (≥ 1 slips), for sensors that see
    /// the contact itself (the slip sensor).
    pub true_utilisation: f64,
    /// Whether the object slid relative to the fingertips in the last tick.
    pub sliding: bool,
}

impl World {
    /// The tangential load on one contact: half the object's \[N\].
    pub fn contact_force_n(&self) -> [f64; 2] {
        [self.force_n[0] / 2.0, self.force_n[1] / 2.0]
    }

    /// The torsional load on one contact [N·m].
    pub fn contact_moment_nm(&self) -> f64 {
        self.moment_nm / 2.0
    }
}

/// What the link does to one sensor frame.
#[derive(Debug, Clone, PartialEq)]
pub enum LinkFate {
    /// Delivered intact.
    Deliver,
    /// Never arrives.
    Drop,
    /// Arrives with these bytes instead of its encoding (bit flips, truncation). A
    /// controller without a byte link loses it, as the CRC would.
    Corrupt(Vec<u8>),
}

/// One effect. Every hook defaults to doing nothing.
pub trait Effect: std::fmt::Debug {
    /// The name a scene lists.
    fn name(&self) -> &'static str;
    /// Stage 1: add forces and moments on the object.
    fn load(&mut self, _w: &mut World) {}
    /// Stage 2: change what the sensor reports.
    fn sense(&mut self, _w: &World, _frame: &mut SensorFrame) {}
    /// Stage 3: delay or damage the frame on the link. `frames` holds the frames due
    /// for delivery this tick (normally the one just sensed); `fates` their fates.
    fn link(&mut self, _frames: &mut Vec<(SensorFrame, LinkFate)>) {}
    /// Stage 4: turn the command into the applied normal force.
    fn actuate(&mut self, _w: &mut World) {}
    /// Stage 5: the true contact.
    fn contact(&mut self, _w: &mut World) {}
    /// The skew of the true contact, if this effect makes one.
    fn true_skew(&self) -> Option<SkewParams> {
        None
    }
}

/// The step pipeline: the listed effects, in [`NAMES`] order, with their step cost.
#[derive(Debug)]
pub struct Pipeline {
    effects: Vec<Box<dyn Effect>>,
    cost: Vec<Duration>,
    timed: bool,
}

/// A random stream of an effect's own: the scene seed mixed with the effect's name
/// (FNV-1a), so listing an effect changes no other effect's random numbers.
pub fn rng(seed: u64, name: &str) -> ChaCha8Rng {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for b in name.bytes() {
        h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
    }
    ChaCha8Rng::seed_from_u64(seed ^ h)
}

/// Builds one effect from its settings, with what it needs besides: its random stream
/// (from the scene's `seed`) or the true fingertip.
pub fn build(
    settings: &EffectSettings,
    seed: u64,
    finger: &Finger,
) -> Result<Box<dyn Effect>, String> {
    settings.build(rng(seed, settings.name()), finger)
}

impl Pipeline {
    /// Builds the effects of `settings` (the scene's typed, checked settings of the listed
    /// effects, in [`NAMES`] order), each from its own settings ([`build`]).
    pub fn new(settings: &[EffectSettings], seed: u64, finger: &Finger) -> Result<Self, String> {
        let effects = settings
            .iter()
            .map(|s| build(s, seed, finger))
            .collect::<Result<Vec<_>, _>>()?;
        let cost = vec![Duration::ZERO; effects.len()];
        Ok(Self {
            effects,
            cost,
            timed: true,
        })
    }

    /// The names of the built effects, in order.
    pub fn names(&self) -> Vec<String> {
        self.effects.iter().map(|e| e.name().to_string()).collect()
    }

    /// The true contact's skew, if an effect makes one.
    pub fn true_skew(&self) -> Option<SkewParams> {
        self.effects.iter().find_map(|e| e.true_skew())
    }

    /// Whether to time each effect (on by default; a clock reading costs about 60 ns,
    /// more than most effects' steps, so the bench turns it off).
    pub fn set_timed(&mut self, timed: bool) {
        self.timed = timed;
    }

    fn each(&mut self, mut f: impl FnMut(&mut dyn Effect)) {
        if !self.timed {
            for e in &mut self.effects {
                f(e.as_mut());
            }
            return;
        }
        for (e, c) in self.effects.iter_mut().zip(self.cost.iter_mut()) {
            let start = Instant::now();
            f(e.as_mut());
            *c += start.elapsed();
        }
    }

    /// Stage 1.
    pub fn load(&mut self, w: &mut World) {
        self.each(|e| e.load(w));
    }
    /// Stage 2.
    pub fn sense(&mut self, w: &World, frame: &mut SensorFrame) {
        self.each(|e| e.sense(w, frame));
    }
    /// Stage 3.
    pub fn link(&mut self, frames: &mut Vec<(SensorFrame, LinkFate)>) {
        self.each(|e| e.link(frames));
    }
    /// Stage 4.
    pub fn actuate(&mut self, w: &mut World) {
        self.each(|e| e.actuate(w));
    }
    /// Stage 5.
    pub fn contact(&mut self, w: &mut World) {
        self.each(|e| e.contact(w));
    }

    /// Time spent in each effect so far.
    pub fn costs(&self) -> Vec<(String, Duration)> {
        self.effects
            .iter()
            .zip(&self.cost)
            .map(|(e, c)| (e.name().to_string(), *c))
            .collect()
    }
}

#[cfg(test)]
mod registry_tests {
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
        for name in NAMES {
            let s = EffectSettings::read(name, &mut Defaults).unwrap().unwrap();
            assert_eq!(s.name(), *name);
            for r in s.ranges() {
                assert!(r.holds(), "{name}.{}: {r:?}", r.key);
            }
        }
        assert!(EffectSettings::read("nope", &mut Defaults).is_none());
    }
}
