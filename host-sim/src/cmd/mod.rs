//! The commands `fls`, `required-force`, `simulate`, `tables`, `experiment` and
//! `calibrate`: each parses its
//! arguments, calls the library and prints or writes what it found. Siblings: none uses
//! another; what two of them share lives in [`crate::args`] (argument types),
//! [`crate::input`] (capped file reads, error text) and [`crate::plot`] (surface plots).
//! `bench` and `accuracy` keep their command next to the work they do
//! ([`crate::bench::run_cmd`], [`crate::accuracy::run`]).

pub mod calibrate;
pub mod experiment;
pub mod fls;
pub mod required_force;
pub mod simulate;
pub mod tables;
