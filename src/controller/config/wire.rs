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
        // One name a line (rustfmt would put the pattern on one long line).
        #[rustfmt::skip]
        let [
            c_m_per_n_gamma,
            gamma,
            half_length_m,
            safety,
            n_min_n,
            n_max_n,
            rise_rate_n_per_s,
            fall_rate_n_per_s,
            tick_period_s,
            stale_timeout_s,
            fault_force_n,
            force_range_n,
            moment_range_nm,
        ] = a;
        let [force_nodes, quadrature_order, table_samples, aspect_count] = sizes;
        #[rustfmt::skip]
        let [
            actuator_lag_s,
            actuator_slew_n_per_s,
            disc_torsion_factor,
            cyclic_factor,
            steady_factor,
            steady_ramp_s,
            slip_step_incipient,
            slip_step_gross,
            slip_margin_max,
            creep_margin_max,
            mu_floor_fraction,
            untold_lag_s,
        ] = b;
        Ok(ControllerConfig {
            mu,
            shape,
            k,
            skew,
            c_m_per_n_gamma,
            gamma,
            half_length_m,
            safety,
            n_min_n,
            n_max_n,
            rise_rate_n_per_s,
            fall_rate_n_per_s,
            tick_period_s,
            stale_timeout_s,
            fault_force_n,
            force_range_n,
            moment_range_nm,
            mode,
            force_nodes,
            quadrature_order,
            table_samples,
            aspect_count,
            actuator_lag_s,
            actuator_slew_n_per_s,
            disc_torsion_factor,
            cyclic_factor,
            steady_factor,
            steady_ramp_s,
            slip_step_incipient,
            slip_step_gross,
            slip_margin_max,
            creep_margin_max,
            mu_floor_fraction,
            untold_lag_s,
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
