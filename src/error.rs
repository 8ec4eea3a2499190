//! Configuration errors: small `Copy` values that name the offending parameter.

use core::fmt;

/// Why a configuration was rejected. Every variant names the parameter by the same name the
/// command line uses for it (`k`, `aspect`, `skew`, ...).
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
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ConfigError::NonFinite(p) => write!(f, "{p}: must be a finite number"),
            ConfigError::OutOfRange {
                param,
                value,
                expected,
            } => write!(f, "{param}: {value} is out of range, expected {expected}"),
            ConfigError::Capacity {
                param,
                requested,
                limit,
            } => write!(
                f,
                "{param}: {requested} does not fit the fixed capacity (limit {limit})"
            ),
        }
    }
}

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
