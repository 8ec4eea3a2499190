//! The configuration's decoding from a binary format (the wire's postcard, whose
//! deserializer is not human-readable): the same fields in the same order as the derived
//! decoding reads them, with the runs of `f64` and `u16` fields each read by one loop.
//! The derived decoding took about 2 KB of the firmware's flash, some 30 bytes a field
//! (docs/decisions/firmware-size-levers.md). It accepts exactly the bytes the derived one
//! accepts, as the same configuration (`tests/protocol.rs` compares the two).

use super::ControllerConfig;
use core::fmt;
use serde::de::{DeserializeSeed, Deserializer, Error, SeqAccess, Visitor};
use serde::Deserialize;

/// Decodes a configuration as a sequence of its fields.
pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<ControllerConfig, D::Error> {
    // The elements `Fields::visit_seq` reads: four fields, a run of 13 `f64`, one field, a
    // run of 4 `u16`, a run of 12 `f64`.
    d.deserialize_tuple(9, Fields)
}

/// The next element of `seq`, which must be there.
fn next<'de, A: SeqAccess<'de>, T: Deserialize<'de>>(seq: &mut A) -> Result<T, A::Error> {
    seq.next_element()?
        .ok_or_else(|| A::Error::custom("too few configuration fields"))
}

/// Fills the slice, in order, from as many consecutive elements of a binary format (one
/// tuple element each, which is how postcard lays out consecutive struct fields).
struct Run<'a, T>(&'a mut [T]);

impl<'de, T: Deserialize<'de>> DeserializeSeed<'de> for Run<'_, T> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_tuple(self.0.len(), self)
    }
}

impl<'de, T: Deserialize<'de>> Visitor<'de> for Run<'_, T> {
    type Value = ();

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a run of configuration fields")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<(), A::Error> {
        for slot in self.0.iter_mut() {
            *slot = next(&mut seq)?;
        }
        Ok(())
    }
}

/// Reads the configuration's fields in declaration order.
struct Fields;

impl<'de> Visitor<'de> for Fields {
    type Value = ControllerConfig;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("the fields of a ControllerConfig")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<ControllerConfig, A::Error> {
        let mu = next(&mut seq)?;
        let shape = next(&mut seq)?;
        let k = next(&mut seq)?;
        let skew = next(&mut seq)?;
        let mut a = [0.0; 13];
        next_run(&mut seq, &mut a)?;
        let mode = next(&mut seq)?;
        let mut sizes = [0u16; 4];
        next_run(&mut seq, &mut sizes)?;
        let mut b = [0.0; 12];
        next_run(&mut seq, &mut b)?;
        Ok(ControllerConfig {
            mu,
            shape,
            k,
            skew,
            c_m_per_n_gamma: a[0],
            gamma: a[1],
            half_length_m: a[2],
            safety: a[3],
            n_min_n: a[4],
            n_max_n: a[5],
            rise_rate_n_per_s: a[6],
            fall_rate_n_per_s: a[7],
            tick_period_s: a[8],
            stale_timeout_s: a[9],
            fault_force_n: a[10],
            force_range_n: a[11],
            moment_range_nm: a[12],
            mode,
            force_nodes: sizes[0],
            quadrature_order: sizes[1],
            table_samples: sizes[2],
            aspect_count: sizes[3],
            actuator_lag_s: b[0],
            actuator_slew_n_per_s: b[1],
            disc_torsion_factor: b[2],
            cyclic_factor: b[3],
            steady_factor: b[4],
            steady_ramp_s: b[5],
            slip_step_incipient: b[6],
            slip_step_gross: b[7],
            slip_margin_max: b[8],
            creep_margin_max: b[9],
            mu_floor_fraction: b[10],
            untold_lag_s: b[11],
        })
    }
}

/// Fills `out` from the next element of `seq`, a run of `out.len()` fields.
fn next_run<'de, A: SeqAccess<'de>, T: Deserialize<'de>>(
    seq: &mut A,
    out: &mut [T],
) -> Result<(), A::Error> {
    seq.next_element_seed(Run(out))?
        .ok_or_else(|| A::Error::custom("too few configuration fields"))
}
