//! Helpers shared by the integration tests (and, through `#[path]`, by `benches/fls.rs`).
//! Each test binary uses a different subset, hence `dead_code` is allowed.
#![allow(dead_code)]

pub mod brute_force;
