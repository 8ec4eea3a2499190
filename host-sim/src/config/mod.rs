//! How the host reads a controller configuration: one way for every front-end. A partial
//! TOML table (a scene's `[controller]`, a `--config FILE`, the per-field flags) is
//! overlaid onto a base [`ControllerConfig`] through its own serde: the base is serialized
//! to a table, the given keys replace its values, and the table is read back with
//! `deny_unknown_fields`. A key the configuration does not have, or a value of the wrong
//! type, is an error naming that key. Nothing here lists the fields: a new field of
//! [`ControllerConfig`] is read, and gets its flag ([`flags`]), without an edit.

pub mod flags;
pub mod margins;
pub mod names;

use serde::de::{self, Deserializer, Visitor};
use softgrip::controller::ControllerConfig;
use std::sync::OnceLock;

pub use flags::ConfigArgs;

/// A key of a partial configuration that could not be read.
#[derive(Debug, Clone, PartialEq)]
pub struct KeyError {
    /// The key as written (a field name).
    pub key: String,
    /// Why.
    pub reason: String,
}

impl std::fmt::Display for KeyError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.key, self.reason)
    }
}

/// The fields of [`ControllerConfig`], in declaration order, as its serde reads them.
pub fn fields() -> &'static [&'static str] {
    static FIELDS: OnceLock<&'static [&'static str]> = OnceLock::new();
    FIELDS.get_or_init(|| {
        let mut fields: &'static [&'static str] = &[];
        // The introspecting deserializer always fails after recording the fields.
        let _ = <ControllerConfig as serde::Deserialize>::deserialize(Introspect(&mut fields));
        fields
    })
}

/// `base` with the keys of `table` in place of its values. Every key must be a field
/// ([`fields`]) and its value of the field's type; the first that is not is the error.
/// Values are not validated here ([`ControllerConfig::check`] does that).
pub fn overlay(base: &ControllerConfig, table: &toml::Table) -> Result<ControllerConfig, KeyError> {
    let known = fields();
    if let Some(key) = table.keys().find(|k| !known.contains(&k.as_str())) {
        return Err(KeyError {
            key: key.clone(),
            reason: format!("unknown key, expected one of {}", known.join(", ")),
        });
    }
    let base_table = toml::Table::try_from(base).map_err(|e| KeyError {
        key: String::new(),
        reason: e.to_string(),
    })?;
    // Each key alone first, so that an ill-typed one is named.
    for (key, value) in table {
        let mut one = base_table.clone();
        one.insert(key.clone(), value.clone());
        read(one).map_err(|reason| KeyError {
            key: key.clone(),
            reason,
        })?;
    }
    let mut all = base_table;
    all.extend(table.iter().map(|(k, v)| (k.clone(), v.clone())));
    read(all).map_err(|reason| KeyError {
        key: table.keys().next().cloned().unwrap_or_default(),
        reason,
    })
}

fn read(table: toml::Table) -> Result<ControllerConfig, String> {
    table
        .try_into::<ControllerConfig>()
        .map_err(|e| e.message().trim().to_string())
}

/// A deserializer that records the field list a struct asks for, then fails.
struct Introspect<'a>(&'a mut &'static [&'static str]);

impl<'de> Deserializer<'de> for Introspect<'_> {
    type Error = de::value::Error;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(de::Error::custom("not a struct"))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Self::Error> {
        *self.0 = fields;
        Err(de::Error::custom("introspected"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fields_are_the_structs() {
        let f = fields();
        assert_eq!(f.first(), Some(&"mu"));
        assert!(f.contains(&"skew") && f.contains(&"actuator_slew_n_per_s"));
        let serialized = toml::Table::try_from(ControllerConfig::default()).unwrap();
        // Every serialized key is a field; only the absent skew is not serialized.
        assert!(serialized.keys().all(|k| f.contains(&k.as_str())));
        assert_eq!(serialized.len() + 1, f.len());
    }

    #[test]
    fn an_overlay_replaces_the_given_keys_only() {
        let base = ControllerConfig::default();
        let t: toml::Table =
            toml::from_str("mu = 0.5\nmode = \"table\"\nforce_nodes = 12\n").unwrap();
        let got = overlay(&base, &t).unwrap();
        let want = ControllerConfig {
            mu: 0.5,
            mode: softgrip::controller::Mode::Table,
            force_nodes: 12,
            ..base
        };
        assert_eq!(got, want);
        assert_eq!(overlay(&base, &toml::Table::new()).unwrap(), base);
    }

    #[test]
    fn an_unknown_or_ill_typed_key_is_named() {
        let base = ControllerConfig::default();
        for (text, key) in [
            ("mu = 0.5\nfriction = 1.0", "friction"),
            ("safety = \"high\"", "safety"),
            ("shape = \"cone\"", "shape"),
            ("force_nodes = -3", "force_nodes"),
        ] {
            let t: toml::Table = toml::from_str(text).unwrap();
            let e = overlay(&base, &t).unwrap_err();
            assert_eq!(e.key, key, "{text}: {e}");
            assert!(!e.reason.is_empty());
        }
    }
}
