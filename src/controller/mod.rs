//! The per-tick slip-prevention controller (docs/model.md, "The slip-prevention rule").

pub mod actuator;
pub mod blob;
mod capacity;
mod config;
pub mod lead;
mod math;
pub mod slip;
mod status;
mod tick;

pub use capacity::{
    max_illinois_iterations, Capacity, Solution, TableError, Tables, DIRECTIONS, MAX_ASPECTS,
    MAX_FORCE_NODES, MAX_ILLINOIS_ITERATIONS, MAX_ILLINOIS_ITERATIONS_F32, MAX_TABLE_SAMPLES,
    UTILISATION_MAX,
};
pub use config::{
    Checked, ControllerConfig, FingerShape, Mode, SkewParams, WireMaxLen, CREEP_MARGIN_MAX,
    CYCLIC_SAFETY_FACTOR, DISC_TORSION_SAFETY_FACTOR, MARGIN_MAX, MARGIN_STEP_GROSS,
    MARGIN_STEP_INCIPIENT, MU_FLOOR_FRACTION, STEADY_RAMP_S, STEADY_SAFETY_FACTOR, UNTOLD_LAG_S,
};
pub use math::{Libm, Micromath, TickMath};
pub use slip::SlipSignal;
pub use status::Status;
pub use tick::{Controller, FromTablesError, Measurement, TickOutput, RESYNC_FRAMES};
