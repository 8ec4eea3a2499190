//! The grasp simulator: scenes, effects, ground truth, controllers and reports.

pub mod controllers;
pub mod effects;
pub mod finger;
pub mod record;
pub mod report;
pub mod run;
pub mod scene;
pub mod stream;
pub mod task;
pub mod trace;
pub mod truth;
