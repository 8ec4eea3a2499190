#![doc = include_str!("../README.md")]
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
// `!(x > 0)` is how the core rejects NaN together with non-positive values, on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
#![cfg_attr(
    not(test),
    deny(
        clippy::unwrap_used,
        clippy::expect_used,
        clippy::panic,
        clippy::indexing_slicing,
        clippy::unreachable,
        clippy::todo
    )
)]

mod checksum;
pub mod contact;
pub mod controller;
pub mod device;
pub mod error;
pub mod fls;
pub mod partial_slip;
pub mod pressure;
pub mod protocol;
pub mod quadrature;
pub mod real;
pub mod skew;

pub use error::{BuildError, ConfigError, RangeOverflow};
pub use fls::{FlsConfig, FlsModel, FlsPoint, FlsTable, Shape};
pub use quadrature::QuadratureOrder;
pub use real::Real;

/// The Rust examples of docs/core.md, run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../docs/core.md")]
pub struct CoreDocs;

/// The Rust examples of docs/controller.md, run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../docs/controller.md")]
pub struct ControllerDocs;
