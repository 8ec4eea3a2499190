//! Where the device's controllers come from: precomputed at start-up ([`Precompute`]) or
//! from tables linked into the firmware ([`Prebuilt`]), built in place into the slot the
//! device hands over.

use crate::controller::{Controller, ControllerConfig, Tables, TickMath};
use crate::protocol::WireConfigError;
use crate::real::Real;
use core::marker::PhantomData;

/// Where a device's controller comes from.
///
/// The controller is built into a slot the device owns (`slot`), in place where the
/// source can: a controller is kilobytes, and every copy of it on its way into the device
/// would be stack a microcontroller pays for (docs/decisions/firmware-size-levers.md). The device only ticks the slot after
/// an `Ok`; after an error the slot may hold anything. A source outside this crate can
/// simply assign a controller it built: `*slot = Controller::new(cfg)?`.
///
/// The error is the wire form itself (about 130 bytes, two fixed strings): there is no
/// heap to box it in, and it goes straight into the `Configured` reply.
#[allow(clippy::result_large_err)]
pub trait ControllerSource<M: TickMath<f32>> {
    /// Builds the controller for `cfg` into `slot`, or says why it cannot be had.
    fn build_into(
        &self,
        cfg: ControllerConfig,
        slot: &mut Controller<f32, M>,
    ) -> Result<(), WireConfigError>;
}

/// Precomputation at start-up, in precision `P`.
#[derive(Debug, Default, Clone, Copy)]
pub struct Precompute<P = f32>(PhantomData<P>);

#[allow(clippy::result_large_err)]
impl<M: TickMath<f32>, P: Real> ControllerSource<M> for Precompute<P> {
    fn build_into(
        &self,
        cfg: ControllerConfig,
        slot: &mut Controller<f32, M>,
    ) -> Result<(), WireConfigError> {
        slot.rebuild_precomputed_in::<P>(cfg)
            .map_err(|e| WireConfigError::from_config_error(&e))
    }
}

/// Tables made on the host (`host-sim tables --format rust`) and linked in: a
/// configuration is accepted only if it is the one the tables were made for.
#[derive(Debug, Clone, Copy)]
pub struct Prebuilt {
    /// The configuration the tables were made for.
    pub config: ControllerConfig,
    /// The tables.
    pub tables: Tables<'static, f32>,
}

#[allow(clippy::result_large_err)]
impl<M: TickMath<f32>> ControllerSource<M> for Prebuilt {
    fn build_into(
        &self,
        cfg: ControllerConfig,
        slot: &mut Controller<f32, M>,
    ) -> Result<(), WireConfigError> {
        if cfg != self.config {
            return Err(WireConfigError::text(
                "tables",
                "the prebuilt tables were made for another configuration",
            ));
        }
        slot.rebuild_from_tables(cfg, &self.tables)
            .map_err(|e| WireConfigError::from_tables_error(&e))
    }
}
