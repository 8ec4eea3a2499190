//! A value as a Rust expression, through its serde serialization: so the tables export
//! writes `ControllerConfig` from its definition, not from a hand-kept copy of its fields.
//!
//! Floats are written as exact bit patterns (`f64::from_bits` of a hex literal), integers
//! in decimal, `Option`s as `None`/`Some(…)`, enums and structs under
//! `softgrip::controller::`. An enum variant's Rust name is its serde name with the first
//! letter upper-cased (the crate's enums spell a one-word variant `Rect` as `rect` or
//! `Rect`; a test checks every variant of the configuration's enums).

use serde::ser::{self, Impossible, Serialize, SerializeStruct};
use std::fmt;

/// The path the written types are under.
const PATH: &str = "softgrip::controller::";

/// `x`'s bit pattern as a Rust `f32` expression.
pub(super) fn f32_lit(x: f32) -> String {
    format!("f32::from_bits({:#010x})", x.to_bits())
}

/// `x`'s bit pattern as a Rust `f64` expression.
pub(super) fn f64_lit(x: f64) -> String {
    format!("f64::from_bits({:#018x})", x.to_bits())
}

/// A serialized value: an expression, or a struct's name and its fields (as expressions,
/// in declaration order), which the caller may lay out as it likes.
#[derive(Debug)]
pub(super) enum Lit {
    /// A Rust expression.
    Expr(String),
    /// A struct's name and its `(field, expression)`s.
    Struct(&'static str, Vec<(&'static str, String)>),
}

impl Lit {
    /// The value as one expression (a struct on one line).
    pub(super) fn expr(self) -> String {
        match self {
            Lit::Expr(e) => e,
            Lit::Struct(name, fields) => {
                let body: Vec<String> = fields.iter().map(|(f, v)| format!("{f}: {v}")).collect();
                format!("{PATH}{name} {{ {} }}", body.join(", "))
            }
        }
    }
}

/// What the writer cannot write (a kind of value the configuration does not have).
#[derive(Debug)]
pub(super) struct Unsupported(String);

impl fmt::Display for Unsupported {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot write {} as a Rust literal", self.0)
    }
}

impl std::error::Error for Unsupported {}

impl ser::Error for Unsupported {
    fn custom<T: fmt::Display>(msg: T) -> Self {
        Unsupported(msg.to_string())
    }
}

/// `value` as a Rust literal.
pub(super) fn to_lit<T: Serialize + ?Sized>(value: &T) -> Result<Lit, Unsupported> {
    value.serialize(RustLit)
}

fn unsupported<T>(what: &str) -> Result<T, Unsupported> {
    Err(Unsupported(what.to_string()))
}

fn variant_name(serde_name: &str) -> String {
    let mut c = serde_name.chars();
    c.next().map_or_else(String::new, |first| {
        first.to_uppercase().chain(c).collect::<String>()
    })
}

/// The serializer to [`Lit`].
struct RustLit;

/// Collects a struct's fields.
struct Fields(&'static str, Vec<(&'static str, String)>);

macro_rules! decimal {
    ($($method:ident: $t:ty),*) => {
        $(fn $method(self, v: $t) -> Result<Lit, Unsupported> {
            Ok(Lit::Expr(v.to_string()))
        })*
    };
}

macro_rules! refuse {
    ($($method:ident($($arg:ty),*) -> $ok:ty: $what:literal),*) => {
        $(fn $method(self, $(_: $arg),*) -> Result<$ok, Unsupported> {
            unsupported($what)
        })*
    };
}

impl ser::Serializer for RustLit {
    type Ok = Lit;
    type Error = Unsupported;
    type SerializeSeq = Impossible<Lit, Unsupported>;
    type SerializeTuple = Impossible<Lit, Unsupported>;
    type SerializeTupleStruct = Impossible<Lit, Unsupported>;
    type SerializeTupleVariant = Impossible<Lit, Unsupported>;
    type SerializeMap = Impossible<Lit, Unsupported>;
    type SerializeStruct = Fields;
    type SerializeStructVariant = Impossible<Lit, Unsupported>;

    decimal!(serialize_u8: u8, serialize_u16: u16, serialize_u32: u32, serialize_u64: u64,
             serialize_i8: i8, serialize_i16: i16, serialize_i32: i32, serialize_i64: i64,
             serialize_bool: bool);

    fn serialize_f32(self, v: f32) -> Result<Lit, Unsupported> {
        Ok(Lit::Expr(f32_lit(v)))
    }

    fn serialize_f64(self, v: f64) -> Result<Lit, Unsupported> {
        Ok(Lit::Expr(f64_lit(v)))
    }

    fn serialize_none(self) -> Result<Lit, Unsupported> {
        Ok(Lit::Expr("None".to_string()))
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<Lit, Unsupported> {
        Ok(Lit::Expr(format!("Some({})", to_lit(value)?.expr())))
    }

    fn serialize_unit_variant(
        self,
        name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<Lit, Unsupported> {
        Ok(Lit::Expr(format!(
            "{PATH}{name}::{}",
            variant_name(variant)
        )))
    }

    fn serialize_struct(self, name: &'static str, len: usize) -> Result<Fields, Unsupported> {
        Ok(Fields(name, Vec::with_capacity(len)))
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<Lit, Unsupported> {
        to_lit(value)
    }

    refuse!(
        serialize_char(char) -> Lit: "a char",
        serialize_str(&str) -> Lit: "a string",
        serialize_bytes(&[u8]) -> Lit: "bytes",
        serialize_unit() -> Lit: "()",
        serialize_unit_struct(&'static str) -> Lit: "a unit struct",
        serialize_seq(Option<usize>) -> Self::SerializeSeq: "a sequence",
        serialize_tuple(usize) -> Self::SerializeTuple: "a tuple",
        serialize_tuple_struct(&'static str, usize) -> Self::SerializeTupleStruct:
            "a tuple struct",
        serialize_tuple_variant(&'static str, u32, &'static str, usize)
            -> Self::SerializeTupleVariant: "a tuple variant",
        serialize_map(Option<usize>) -> Self::SerializeMap: "a map",
        serialize_struct_variant(&'static str, u32, &'static str, usize)
            -> Self::SerializeStructVariant: "a struct variant"
    );

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _value: &T,
    ) -> Result<Lit, Unsupported> {
        unsupported("a newtype variant")
    }
}

impl SerializeStruct for Fields {
    type Ok = Lit;
    type Error = Unsupported;

    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), Unsupported> {
        self.1.push((key, to_lit(value)?.expr()));
        Ok(())
    }

    fn end(self) -> Result<Lit, Unsupported> {
        Ok(Lit::Struct(self.0, self.1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use softgrip::controller::{ControllerConfig, FingerShape, Mode, SkewParams};

    #[test]
    fn every_variant_of_the_configuration_enums_is_written_by_its_rust_name() {
        for shape in FingerShape::ALL {
            let e = to_lit(&shape).unwrap().expr();
            assert_eq!(e, format!("{PATH}FingerShape::{shape:?}"));
        }
        for mode in [Mode::Ellipse, Mode::Table] {
            let e = to_lit(&mode).unwrap().expr();
            assert_eq!(e, format!("{PATH}Mode::{mode:?}"));
        }
    }

    #[test]
    fn the_configuration_is_its_fields_in_order_with_exact_values() {
        let cfg = ControllerConfig {
            skew: Some(SkewParams::PAPER),
            ..ControllerConfig::DEFAULT
        };
        let Lit::Struct(name, fields) = to_lit(&cfg).unwrap() else {
            panic!("not a struct")
        };
        assert_eq!(name, "ControllerConfig");
        let names: Vec<&str> = fields.iter().map(|f| f.0).collect();
        assert_eq!(names, ControllerConfig::FIELDS);
        let get = |n: &str| fields.iter().find(|f| f.0 == n).unwrap().1.clone();
        assert_eq!(get("safety"), f64_lit(ControllerConfig::DEFAULT.safety));
        assert_eq!(get("force_nodes"), "48");
        assert_eq!(
            get("skew"),
            format!(
                "Some({PATH}SkewParams {{ delta_over_a: {}, alpha: {}, locus_over_a: {} }})",
                f64_lit(0.9),
                f64_lit(1.1),
                f64_lit(0.45)
            )
        );
    }
}
