//! What a tick reports about itself.

use serde::{Deserialize, Serialize};

/// The outcome of one tick. Ordered by severity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Status {
    /// The measurement was good and the command holds the load with the safety margin.
    Ok,
    /// The load needs more than `N_max` (with the safety margin): the command sits at
    /// `N_max` and cannot promise to hold.
    Saturated,
    /// The measurement had a non-finite or out-of-range value. The command holds the last
    /// safe value, and after the stale timeout moves to the fault force.
    SensorFault,
    /// The measurement was not newer than the last good one. Handled as a sensor fault.
    StaleInput,
}

impl Status {
    /// The name used in reports and JSON.
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Saturated => "saturated",
            Status::SensorFault => "sensor_fault",
            Status::StaleInput => "stale_input",
        }
    }
}
