//! The commands `fls`, `required-force`, `simulate`, `tables`, `bench`, `accuracy`,
//! `experiment` and `calibrate`: each parses its arguments, calls the library and prints
//! or writes what it found. Siblings: none uses another; what two of them share lives in
//! [`crate::args`] (argument types), [`crate::input`] (capped file reads, error text) and
//! [`crate::plot`] (surface plots). `bench` and `accuracy` are thin: their work is the
//! library's [`crate::bench`] and [`crate::accuracy`], on plain options.

pub mod accuracy;
pub mod bench;
pub mod calibrate;
pub mod experiment;
pub mod fls;
pub mod required_force;
pub mod simulate;
pub mod tables;
