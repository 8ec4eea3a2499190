//! The controller's configuration, validated once at start-up.

use crate::error::ConfigError;
use crate::fls::Shape;
use serde::{Deserialize, Serialize};

mod validate;
mod wire;

/// Defines a struct of named fields and, from the same field list, three constants on it:
/// `FIELDS`, the field names in declaration order, `SCHEMA`, its part of the protocol's
/// [`SCHEMA`](crate::protocol::SCHEMA) (`Name{field:type,...}`, types as written), and
/// its [`WireMaxLen::WIRE_MAX_LEN`]. So a field is written once, and the wire's
/// description and buffer sizes follow it.
macro_rules! with_schema {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $(#[$fmeta0:meta])* pub $f0:ident: $t0:ty,
            $( $(#[$fmeta:meta])* pub $f:ident: $t:ty, )*
        }
    ) => {
        $(#[$meta])*
        pub struct $name {
            $(#[$fmeta0])* pub $f0: $t0,
            $( $(#[$fmeta])* pub $f: $t, )*
        }

        impl $name {
            /// The field names, in declaration order (the order on the wire).
            pub const FIELDS: &'static [&'static str] = &[stringify!($f0), $(stringify!($f)),*];

            /// This type's part of the protocol's [`SCHEMA`](crate::protocol::SCHEMA):
            /// `Name{field:type,...}`, generated from the definition.
            pub const SCHEMA: &'static str = concat!(
                stringify!($name), "{", stringify!($f0), ":", stringify!($t0),
                $(",", stringify!($f), ":", stringify!($t),)* "}"
            );
        }

        impl WireMaxLen for $name {
            const WIRE_MAX_LEN: usize =
                <$t0 as WireMaxLen>::WIRE_MAX_LEN $(+ <$t as WireMaxLen>::WIRE_MAX_LEN)*;
        }
    };
}

/// The most bytes a value of the type takes in postcard, the wire's encoding: the
/// protocol's buffers ([`MAX_MESSAGE_LEN`](crate::protocol::MAX_MESSAGE_LEN)) are sized
/// from it, so a new configuration field resizes them by itself (tests/protocol.rs checks
/// the bound is met and tight on the largest message).
pub trait WireMaxLen {
    /// The bound \[bytes\].
    const WIRE_MAX_LEN: usize;
}

impl WireMaxLen for f64 {
    const WIRE_MAX_LEN: usize = 8;
}

/// A varint: 7 bits a byte.
impl WireMaxLen for u16 {
    const WIRE_MAX_LEN: usize = 3;
}

/// A presence byte, then the value.
impl<T: WireMaxLen> WireMaxLen for Option<T> {
    const WIRE_MAX_LEN: usize = 1 + T::WIRE_MAX_LEN;
}

/// A unit variant's index, one varint byte (fewer than 128 variants).
impl WireMaxLen for FingerShape {
    const WIRE_MAX_LEN: usize = 1;
}

/// A unit variant's index, one varint byte (fewer than 128 variants).
impl WireMaxLen for Mode {
    const WIRE_MAX_LEN: usize = 1;
}

/// Which fingertip the contact belongs to: the one shape type of the crate and its tools
/// (the limit surface's [`Shape`] is this plus the aspect ratio, see
/// `ControllerConfig::fls_shape`). Text formats (scene files, the command line) spell it
/// by [`FingerShape::name`]; the wire (postcard) by its variant index.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FingerShape {
    /// Hemicylinder: the rectangular patch `[-l, l] × [-a, a]` (the paper's case).
    Rect,
    /// Hemisphere: the disc of radius `a`.
    Disc,
}

impl FingerShape {
    /// Every shape, in declaration order.
    pub const ALL: [FingerShape; 2] = [FingerShape::Rect, FingerShape::Disc];

    /// The name the command line and scene files use.
    pub fn name(self) -> &'static str {
        match self {
            FingerShape::Rect => "rect",
            FingerShape::Disc => "disc",
        }
    }

    /// The shape called `name` ([`FingerShape::name`]), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }
}

// The margins' defaults ([`ControllerConfig::DEFAULT`]), here so that the modules that
// use the margins import the configuration and not the other way round.

/// Default `disc_torsion_factor` \[-\]: a round patch's moment carries `1.5·s`, for a rim
/// that creeps under a sustained twist (docs/decisions/round-patch-torsion-factor.md).
pub const DISC_TORSION_SAFETY_FACTOR: f64 = 1.5;
/// Default `cyclic_factor` \[-\]: the factor on `s` while the load cycles
/// (docs/decisions/cyclic-factor.md).
pub const CYCLIC_SAFETY_FACTOR: f64 = 1.45;
/// Default `steady_factor` \[-\]: at `s = 1.35` a steady hold asks `1.15·N_slip`
/// (docs/decisions/steady-margin.md).
pub const STEADY_SAFETY_FACTOR: f64 = 0.85;
/// Default `steady_ramp_s` \[s\]: the steady factor is eased in, not stepped
/// (docs/decisions/steady-ramp.md).
pub const STEADY_RAMP_S: f64 = 0.5;
/// Default `slip_step_incipient` \[-\]: the margin added on a confirmed incipient slip
/// (docs/decisions/slip-response-steps.md).
pub const MARGIN_STEP_INCIPIENT: f64 = 0.05;
/// Default `slip_step_gross` \[-\]: the margin added on a gross slip
/// (docs/decisions/slip-response-steps.md).
pub const MARGIN_STEP_GROSS: f64 = 0.3;
/// Default `slip_margin_max` \[-\]: the largest slip margin; `N_max` caps the command in
/// any case (docs/decisions/slip-response-steps.md).
pub const MARGIN_MAX: f64 = 3.0;
/// Default `creep_margin_max` \[-\]: the most margin creep alone can ask for
/// (`tests/creep.rs`).
pub const CREEP_MARGIN_MAX: f64 = 1.1;
/// Default `mu_floor_fraction` \[-\]: the lowest `μ̂` a slip can teach, as a fraction of
/// `μ` (docs/decisions/slip-response-steps.md).
pub const MU_FLOOR_FRACTION: f64 = 0.5;
/// Default `untold_lag_s` \[s\]: the slow end of tendon, cable and geared-motor grippers,
/// which also leads an undescribed slew (docs/decisions/untold-actuator-lag.md).
pub const UNTOLD_LAG_S: f64 = 0.04;

/// How the tick tests the load against the limit surface (docs/model.md, "The slip-prevention
/// rule").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// The Eq. 10 ellipse with the exact pitch at `l/a(N)`, shrunk at start-up into the exact
    /// surface (inside Eq. 10 by up to 12 % radially for `k = 2`): cheapest, never asks less
    /// (docs/decisions/conservative-capacity.md; checked by `tests/conservative.rs`).
    Ellipse,
    /// The exact limit surface, precomputed as a table on a grid of aspect ratios.
    Table,
}

impl Mode {
    /// Every mode, in declaration order.
    pub const ALL: [Mode; 2] = [Mode::Ellipse, Mode::Table];

    /// The mode called `name` ([`Mode::name`]), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|m| m.name() == name)
    }

    /// The name the command line uses.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Ellipse => "ellipse",
            Mode::Table => "table",
        }
    }
}

with_schema! {
    /// The skew of the pressure peak (Eq. 16, 17), in units of the half-width `a`. Text
    /// formats give all three fields and no other (`deny_unknown_fields`).
    #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct SkewParams {
        /// `Δ/a ∈ [0, 1)`: how far the peak can move (the paper's: [`SkewParams::PAPER`]).
        pub delta_over_a: f64,
        /// `α > 0`: how fast it moves with the centre of rotation.
        pub alpha: f64,
        /// `h/a`: the bulge of the peak's locus (`Δ/2` is the paper's circular path; only
        /// the disc feels it).
        pub locus_over_a: f64,
    }
}

impl SkewParams {
    /// The paper's case, with its circular locus `h = Δ/2` (docs/model.md, "Pressure").
    pub const PAPER: Self = Self {
        delta_over_a: 0.9,
        alpha: 1.1,
        locus_over_a: 0.45,
    };
}

with_schema! {
    /// Everything the controller depends on. Plain data: build it, then hand it to
    /// [`Controller::new`](super::Controller::new), which validates it and precomputes the
    /// limit surfaces. Parameter names in errors are the field names.
    ///
    /// The one list of the fields: text formats (scene TOML, JSON, Python keywords) give any
    /// subset of them, the rest taken from [`ControllerConfig::DEFAULT`] (`serde(default)`),
    /// and an unknown key is refused by name (`deny_unknown_fields`); the wire (postcard)
    /// sends every field in this order, and the protocol's
    /// [`SCHEMA`](crate::protocol::SCHEMA) lists them from [`ControllerConfig::SCHEMA`].
    ///
    /// The derived serde code is `ControllerConfig::serialize` and
    /// `ControllerConfig::deserialize` (`remote = "Self"`); the traits' impls call it,
    /// except that a binary format (the wire) is decoded by a hand-written loop over the
    /// same fields (`config::wire`).
    #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
    #[serde(remote = "Self", default, deny_unknown_fields)]
    pub struct ControllerConfig {
        /// Coulomb friction coefficient `μ > 0`.
        pub mu: f64,
        /// Fingertip shape.
        pub shape: FingerShape,
        /// Pressure exponent `k ≥ 1` (`f64::INFINITY` for uniform pressure).
        pub k: f64,
        /// Skew of the pressure peak, or `None` for the symmetric profile. Only table mode sees
        /// it: the skew cannot change the pitch, hence not the ellipse either.
        pub skew: Option<SkewParams>,
        /// `c` in `a = c·N^γ` [m/N^γ].
        pub c_m_per_n_gamma: f64,
        /// `γ ∈ [0, 1/2]` in `a = c·N^γ`.
        pub gamma: f64,
        /// Half-length `l` of the rectangular patch along the cylinder axis \[m\] (ignored for
        /// the disc).
        pub half_length_m: f64,
        /// Safety factor `s ≥ 1`: the load times `s` must lie inside the limit surface.
        /// While the load cycles it is multiplied by `cyclic_factor`; once the load has
        /// been steady for the lead's `STEADY_HOLD_S` (and no slip is remembered) by a
        /// factor that ramps down to `steady_factor` over `steady_ramp_s`, the product
        /// never below 1 (`controller::lead`).
        pub safety: f64,
        /// Least commanded normal force `N_min > 0` \[N\].
        pub n_min_n: f64,
        /// Greatest commanded normal force `N_max > N_min` \[N\].
        pub n_max_n: f64,
        /// Fastest rise of the command [N/s].
        pub rise_rate_n_per_s: f64,
        /// Fastest fall of the command [N/s].
        pub fall_rate_n_per_s: f64,
        /// Time between ticks \[s\]: the rate limits are applied per tick with this step.
        pub tick_period_s: f64,
        /// How long the controller holds its last safe command without a good measurement
        /// (bad, stale or no frames at all) before it moves to the fault target \[s\].
        pub stale_timeout_s: f64,
        /// The least force to go to once the input has been bad, stale or silent for
        /// `stale_timeout_s` \[N\], within `[N_min, N_max]`. The fault target is the greater of
        /// this and the last required force (capped at `N_max`): a dead link never opens the
        /// hand, and this force is the floor when nothing was held.
        pub fault_force_n: f64,
        /// Sensor range for each tangential force component and the measured normal force
        /// \[N\]: a reading beyond it is a sensor fault.
        pub force_range_n: f64,
        /// Sensor range for the torsional moment [N·m]: a reading beyond it is a sensor fault.
        pub moment_range_nm: f64,
        /// Ellipse or table.
        pub mode: Mode,
        /// Normal forces in the start-up grid, spaced evenly in `ln N` over `[N_min, N_max]`
        /// (2 to [`MAX_FORCE_NODES`](super::MAX_FORCE_NODES)). The tick interpolates the moment
        /// arm `a(N)·pitch(l/a(N))` linearly between them.
        pub force_nodes: u16,
        /// Quadrature order for the start-up precomputation (nodes per side, 4–128).
        pub quadrature_order: u16,
        /// Centres of rotation per limit-surface sweep in table mode (at most
        /// [`MAX_TABLE_SAMPLES`](super::MAX_TABLE_SAMPLES)).
        pub table_samples: u16,
        /// Aspect ratios `l/a` in table mode's grid for the rectangle with `γ > 0` (at most
        /// [`MAX_ASPECTS`](super::MAX_ASPECTS); the disc and `γ = 0` need one).
        pub aspect_count: u16,
        /// Time constant of the actuator that applies the command \[s\], `0 ≤ τ ≤ 1`: the
        /// prior of the lag the controller identifies online and commands ahead of a
        /// rising load by (see [`lead`](super::lead)). 0 says "not told": the identifier
        /// starts from `untold_lag_s` (a 40 ms guess by default).
        /// A lag under [`LAG_FLOOR_TICKS`](super::actuator::LAG_FLOOR_TICKS) tick periods
        /// (one tick, say) describes an ideal actuator, which gets no lead.
        pub actuator_lag_s: f64,
        /// Fastest rise of the actuator itself [N/s] (`> 0`; `f64::INFINITY` when it is not
        /// slew-limited). Planned into the lead horizon so that a slew-limited actuator
        /// starts early enough; the prior of the slew the controller identifies.
        pub actuator_slew_n_per_s: f64,
        /// Margins: factors on the model's slip force that a finger's own behaviour calls
        /// for (docs/controller.md, "Margins"; docs/experiments.md says which protocol
        /// measures each). The factor on the safety factor that a round patch's
        /// ([`FingerShape::Disc`]) torsional moment carries \[-\], `≥ 1`: a margin for a
        /// rim that creeps under a sustained twist (a hemicylinder's is 1).
        pub disc_torsion_factor: f64,
        /// The factor on the safety factor while the load cycles \[-\], `≥ 1`: the
        /// inverse of the share of its static capacity a finger keeps under cyclic load
        /// without ratcheting ([`lead`](super::lead), "Cyclic loads").
        pub cyclic_factor: f64,
        /// The factor on the safety factor once the load has been steady \[-\],
        /// `0 < x ≤ 1` (the product with `safety` is never below 1). A finger that
        /// creeps under a sustained load needs `safety·steady_factor` above the inverse of
        /// the share of its onset it holds ([`lead`](super::lead), "Steady loads").
        pub steady_factor: f64,
        /// How long the steady factor takes to fall from 1 to `steady_factor` \[s\], `≥ 0`
        /// (whole ticks, rounded up, at least one).
        pub steady_ramp_s: f64,
        /// The slip margin added on a confirmed incipient slip \[-\], `≥ 0`
        /// ([`slip`](super::slip)).
        pub slip_step_incipient: f64,
        /// The slip margin added on a gross slip \[-\], `≥ 0`.
        pub slip_step_gross: f64,
        /// The largest slip margin \[-\], `≥ 1` (the command is capped by `n_max_n` in any
        /// case).
        pub slip_margin_max: f64,
        /// The most slip margin creep alone can ask for \[-\], in `[1, slip_margin_max]`.
        pub creep_margin_max: f64,
        /// The lowest friction coefficient a slip can teach, as a fraction of `mu` \[-\],
        /// `0 < x ≤ 1`.
        pub mu_floor_fraction: f64,
        /// The actuator lag assumed when `actuator_lag_s` is 0 ("not told"), until the
        /// actuator's own samples say otherwise \[s\], `0 ≤ x ≤ 1`: the lead the first rise
        /// gets.
        pub untold_lag_s: f64,
    }
}

impl Serialize for ControllerConfig {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        ControllerConfig::serialize(self, s)
    }
}

impl<'de> Deserialize<'de> for ControllerConfig {
    /// Text formats through the derived code (defaults, names, unknown keys refused);
    /// binary ones, which carry every field in order, through `wire`.
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        if d.is_human_readable() {
            ControllerConfig::deserialize(d)
        } else {
            wire::deserialize(d)
        }
    }
}

impl Default for ControllerConfig {
    /// [`ControllerConfig::DEFAULT`].
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl ControllerConfig {
    /// The defaults, the one place they are written: a hemicylindrical silicone fingertip in
    /// the paper's range, an actuator nobody described. Mode and `s` are the held-out run's
    /// choice (docs/decisions/default-choice-rule.md, docs/decisions/held-out-seeds.md),
    /// checked by `host-sim/tests/default_choice.rs::the_default_is_the_held_out_runs_choice`.
    pub const DEFAULT: Self = Self {
        mu: 0.8,
        shape: FingerShape::Rect,
        k: 2.0,
        skew: None,
        c_m_per_n_gamma: 2.5e-3,
        gamma: 0.5,
        half_length_m: 10e-3,
        safety: 1.35,
        n_min_n: 0.2,
        n_max_n: 20.0,
        rise_rate_n_per_s: 400.0,
        fall_rate_n_per_s: 20.0,
        tick_period_s: 1e-3,
        stale_timeout_s: 20e-3,
        fault_force_n: 10.0,
        force_range_n: 100.0,
        moment_range_nm: 2.0,
        mode: Mode::Ellipse,
        force_nodes: 48,
        quadrature_order: 28,
        table_samples: 48,
        aspect_count: 8,
        actuator_lag_s: 0.0,
        actuator_slew_n_per_s: f64::INFINITY,
        disc_torsion_factor: DISC_TORSION_SAFETY_FACTOR,
        cyclic_factor: CYCLIC_SAFETY_FACTOR,
        steady_factor: STEADY_SAFETY_FACTOR,
        steady_ramp_s: STEADY_RAMP_S,
        slip_step_incipient: MARGIN_STEP_INCIPIENT,
        slip_step_gross: MARGIN_STEP_GROSS,
        slip_margin_max: MARGIN_MAX,
        creep_margin_max: CREEP_MARGIN_MAX,
        mu_floor_fraction: MU_FLOOR_FRACTION,
        untold_lag_s: UNTOLD_LAG_S,
    };
}

impl ControllerConfig {
    /// The factor on the safety factor that the torsional moment carries in the tick's
    /// requirement \[-\]: `disc_torsion_factor` on a round patch, 1 on a hemicylinder.
    pub const fn torsion_factor(&self) -> f64 {
        match self.shape {
            FingerShape::Rect => 1.0,
            FingerShape::Disc => self.disc_torsion_factor,
        }
    }

    /// The core's shape at aspect `l/a` (ignored for the disc).
    pub(crate) fn fls_shape(&self, aspect: f64) -> Shape {
        match self.shape {
            FingerShape::Rect => Shape::Rect { aspect },
            FingerShape::Disc => Shape::Disc,
        }
    }
}

/// A configuration that passed [`ControllerConfig::check`]: the one value the host builds
/// controllers from ([`Controller::from_checked`](super::Controller::from_checked)), so
/// that a configuration is validated once and passed down. Read it through `Deref`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Checked(ControllerConfig);

impl ControllerConfig {
    /// Validates the configuration ([`ControllerConfig::validate`]) into a [`Checked`].
    pub fn check(self) -> Result<Checked, ConfigError> {
        self.validate()?;
        Ok(Checked(self))
    }

    /// The base of the required-force rule's configuration (`host-sim required-force`,
    /// Python's `required_force`): the defaults with a finer grid of 64 force nodes. The
    /// caller sets its fields, then [`ControllerConfig::for_loads`] derives the rest.
    pub fn rule_base() -> Self {
        Self {
            force_nodes: 64,
            ..Self::default()
        }
    }

    /// The configuration the required-force rule evaluates loads up to `ft_max_n` and
    /// `mn_max_nm` with: this one with the fault force at `n_min_n` and sensor ranges that can
    /// read the loads (twice the largest, at least the defaults). Those three fields are
    /// derived: see [`ControllerConfig::rule_input`].
    pub fn for_loads(self, ft_max_n: f64, mn_max_nm: f64) -> Self {
        let d = Self::default();
        Self {
            fault_force_n: self.n_min_n,
            force_range_n: (2.0 * ft_max_n).max(d.force_range_n),
            moment_range_nm: (2.0 * mn_max_nm).max(d.moment_range_nm),
            ..self
        }
    }

    /// The required-force rule's input a field of [`ControllerConfig::for_loads`] comes
    /// from: `ft` for `force_range_n`, `mn` for `moment_range_nm`, `n_min_n` for
    /// `fault_force_n`; any other field is its own input.
    pub fn rule_input(field: &'static str) -> &'static str {
        match field {
            "force_range_n" => "ft",
            "moment_range_nm" => "mn",
            "fault_force_n" => "n_min_n",
            other => other,
        }
    }
}

impl Checked {
    /// The validated configuration.
    pub fn config(&self) -> &ControllerConfig {
        &self.0
    }

    /// The same configuration in another mode (the mode is not validated: both are valid).
    pub fn with_mode(self, mode: Mode) -> Self {
        Self(ControllerConfig { mode, ..self.0 })
    }
}

impl core::ops::Deref for Checked {
    type Target = ControllerConfig;

    fn deref(&self) -> &ControllerConfig {
        &self.0
    }
}
