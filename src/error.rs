//! Configuration errors: small `Copy` values that name the offending parameter and say why.
//!
//! The parameter ([`ConfigError::param`]) is the core's name for it: a
//! [`ControllerConfig`](crate::controller::ControllerConfig) field name (`mu`,
//! `half_length_m`, `force_nodes`, ...), or, where a part of the core checks a value of its
//! own, that part's name for it: `c` (the contact size's coefficient, the field
//! `c_m_per_n_gamma`), `order` (the quadrature order, the field `quadrature_order`), `skew`,
//! `alpha` and `locus` (the skew law's `Δ/a`, `α` and `h/a`, the field `skew`), `k` (the
//! pressure exponent) and `aspect` (a limit surface's `l/a`, derived from `half_length_m` and
//! the contact size). [`field_of`] maps a parameter to its field. Front-ends rename fields to
//! their own spelling (flags, scene keys) and print [`ConfigError::reason`] after it: they
//! never parse the text.

use core::fmt;

/// Why a configuration was rejected: the parameter ([`ConfigError::param`], named as the
/// module documentation says) and the reason ([`ConfigError::reason`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ConfigError {
    /// The parameter is NaN or infinite where a finite value is required.
    NonFinite(&'static str),
    /// The parameter is finite but outside its domain.
    OutOfRange {
        /// Name of the parameter.
        param: &'static str,
        /// The rejected value.
        value: f64,
        /// The domain it must lie in, for people.
        expected: &'static str,
    },
    /// A count exceeds the fixed capacity chosen at compile time, or is too small.
    Capacity {
        /// Name of the parameter.
        param: &'static str,
        /// The requested count.
        requested: usize,
        /// The capacity of the type (or the minimum, when `requested` is too small).
        limit: usize,
    },
}

impl ConfigError {
    /// The name of the parameter this error is about.
    pub fn param(&self) -> &'static str {
        match self {
            ConfigError::NonFinite(p) => p,
            ConfigError::OutOfRange { param, .. } | ConfigError::Capacity { param, .. } => param,
        }
    }

    /// The [`ControllerConfig`](crate::controller::ControllerConfig) field this error is
    /// about ([`field_of`] of [`ConfigError::param`]).
    pub fn field(&self) -> &'static str {
        field_of(self.param())
    }

    /// What is wrong, without the parameter's name: the text a front-end prints after its
    /// own name for the parameter.
    pub fn reason(&self) -> Reason<'_> {
        Reason(self)
    }
}

/// The [`ControllerConfig`](crate::controller::ControllerConfig) field a parameter name of
/// [`ConfigError::param`] belongs to: `c` is `c_m_per_n_gamma`, `order` is
/// `quadrature_order`, `aspect` is `half_length_m`; the skew law's `skew`, `alpha` and
/// `locus` keep their names (the parts of the field `skew`); a field name is itself.
pub fn field_of(param: &'static str) -> &'static str {
    match param {
        "c" => "c_m_per_n_gamma",
        "order" => "quadrature_order",
        "aspect" => "half_length_m",
        other => other,
    }
}

/// [`ConfigError::reason`]: the error's text without its parameter.
#[derive(Debug, Clone, Copy)]
pub struct Reason<'a>(&'a ConfigError);

impl fmt::Display for Reason<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self.0 {
            ConfigError::NonFinite(_) => f.write_str("must be a finite number"),
            ConfigError::OutOfRange {
                value, expected, ..
            } => write!(f, "{value} is out of range, expected {expected}"),
            ConfigError::Capacity {
                requested, limit, ..
            } => write!(
                f,
                "{requested} does not fit the fixed capacity (limit {limit})"
            ),
        }
    }
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.param(), self.reason())
    }
}

/// Which factor of the tick's worst demand (the sensor range's largest load times
/// `safety/μ`, over the moment arm) overflows the tick's precision, when a controller
/// build refuses the sensor ranges ([`BuildError::RangeOverflow`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RangeOverflow {
    /// `safety/μ`: the ranges and the arm would fit at `safety/μ = 1`.
    SafetyOverMu,
    /// The sensor ranges `force_range_n`, `moment_range_nm`: the default ranges would fit.
    SensorRange,
    /// The contact (its moment arm, from `half_length_m` and the contact size): neither of
    /// the above helps.
    Contact,
}

/// Why a controller could not be built from a checked configuration
/// ([`Controller::from_checked`](crate::controller::Controller::from_checked)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BuildError {
    /// The precomputation refused a parameter.
    Config(ConfigError),
    /// The sensor ranges' worst load overflows the tick's precision; the variant says which
    /// factor causes it.
    RangeOverflow(RangeOverflow),
}

impl BuildError {
    /// The [`ControllerConfig`](crate::controller::ControllerConfig) field the error is
    /// about (`force_range_n` for an overflow).
    pub fn field(&self) -> &'static str {
        match self {
            BuildError::Config(e) => e.field(),
            BuildError::RangeOverflow(_) => "force_range_n",
        }
    }
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::Config(e) => e.fmt(f),
            BuildError::RangeOverflow(_) => f.write_str(
                "force_range_n: the worst load the sensor range admits, times safety/mu, \
                 overflows the tick's precision",
            ),
        }
    }
}

impl core::error::Error for BuildError {}

impl core::error::Error for ConfigError {}

/// Checks that `value` is finite and satisfies `ok`, naming `param` otherwise. Out of line:
/// a configuration has some twenty checks, each a call here instead of the error's
/// construction inlined (about 1 KB of firmware flash; configuration is not a hot path).
#[inline(never)]
pub(crate) fn check(
    param: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), ConfigError> {
    if value.is_nan() {
        return Err(ConfigError::NonFinite(param));
    }
    if ok {
        Ok(())
    } else if value.is_infinite() {
        Err(ConfigError::NonFinite(param))
    } else {
        Err(ConfigError::OutOfRange {
            param,
            value,
            expected,
        })
    }
}
