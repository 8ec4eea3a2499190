//! A configuration of the knobs (a [`Variant`]) and what it measured ([`Measured`]).

use super::*;

/// The tick's precision and where the start-up precomputation runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Precision {
    /// f32 precomputation, f32 tick (the firmware's default).
    F32,
    /// f64 precomputation, f32 tick (`precompute-f64`).
    F64Precompute,
    /// f64 precomputation, f64 tick (the host).
    F64,
}

impl Precision {
    /// How the report names it.
    pub fn label(self) -> &'static str {
        match self {
            Precision::F32 => "f32 start-up, f32 tick",
            Precision::F64Precompute => "f64 start-up, f32 tick",
            Precision::F64 => "f64 start-up, f64 tick",
        }
    }
}

/// The tick's square root.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MathKind {
    /// `libm` (on the target the FPU's `VSQRT`, bit-identical).
    Libm,
    /// `micromath`'s approximation.
    Micromath,
}

/// How the tick decides.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Engine {
    /// The controller's start-up grid.
    Grid {
        /// Ellipse or table.
        table: bool,
        /// Precision.
        precision: Precision,
        /// Square root.
        math: MathKind,
    },
    /// The exact surface integrated at every trial force (f64).
    Exact,
}

/// One configuration: an engine and the grid sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Variant {
    /// How the tick decides.
    pub engine: Engine,
    /// Quadrature order.
    pub order: u16,
    /// Table samples (table mode only).
    pub samples: u16,
    /// Aspect grid size (table mode only).
    pub aspects: u16,
    /// Force nodes (grid only).
    pub nodes: u16,
}

impl Variant {
    /// The project's defaults in ellipse or table mode.
    pub fn default_mode(table: bool) -> Self {
        let d = ControllerConfig::default();
        Self {
            engine: Engine::Grid {
                table,
                precision: Precision::F32,
                math: MathKind::Libm,
            },
            order: d.quadrature_order,
            samples: d.table_samples,
            aspects: d.aspect_count,
            nodes: d.force_nodes,
        }
    }

    /// The same configuration with the settings it does not use set to the defaults, so
    /// that equal configurations compare equal.
    pub fn normalised(mut self) -> Self {
        let d = ControllerConfig::default();
        match self.engine {
            Engine::Grid { table: false, .. } => {
                self.samples = d.table_samples;
                self.aspects = d.aspect_count;
            }
            Engine::Grid { table: true, .. } => {}
            Engine::Exact => {
                self.samples = d.table_samples;
                self.aspects = d.aspect_count;
                self.nodes = d.force_nodes;
            }
        }
        self
    }

    /// The mode column: "ellipse", "table" or "exact".
    pub fn mode_name(&self) -> &'static str {
        match self.engine {
            Engine::Grid { table: false, .. } => "ellipse",
            Engine::Grid { table: true, .. } => "table",
            Engine::Exact => "exact",
        }
    }

    /// A full description, for the Pareto table.
    pub fn describe(&self) -> String {
        match self.engine {
            Engine::Exact => format!("exact per tick (f64, order {})", self.order),
            Engine::Grid {
                table,
                precision,
                math,
            } => {
                let p = match precision {
                    Precision::F32 => "f32",
                    Precision::F64Precompute => "f64→f32",
                    Precision::F64 => "f64",
                };
                let m = match math {
                    MathKind::Libm => "",
                    MathKind::Micromath => ", micromath",
                };
                if table {
                    format!(
                        "table, order {}, {} samples, {} aspects, {} nodes, {p}{m}",
                        self.order, self.samples, self.aspects, self.nodes
                    )
                } else {
                    format!(
                        "ellipse, order {}, {} nodes, {p}{m}",
                        self.order, self.nodes
                    )
                }
            }
        }
    }

    /// The controller configuration for `base`.
    pub fn config(&self, base: &ControllerConfig) -> ControllerConfig {
        let table = matches!(self.engine, Engine::Grid { table: true, .. });
        ControllerConfig {
            mode: if table { Mode::Table } else { Mode::Ellipse },
            quadrature_order: self.order,
            table_samples: self.samples,
            aspect_count: self.aspects,
            force_nodes: self.nodes,
            ..*base
        }
    }
}

/// What one configuration leaves in error and costs.
#[derive(Debug, Clone, Copy, Default)]
pub struct Measured {
    /// Pitch error (relative, worst over both fingers).
    pub pitch_err: f64,
    /// Surface error (relative radial), rectangle and disc.
    pub surface_err: [f64; 2],
    /// Force error against the configuration's own rule (relative, worst of both).
    pub n_err_own: f64,
    /// Force error against the exact surface (relative), rectangle and disc.
    pub n_err: [f64; 2],
    /// The largest under-ask against the exact surface (relative, ≥ 0).
    pub under_ask: f64,
    /// Host start-up time \[µs\] (rectangle, median).
    pub precompute_us: f64,
    /// Host time per tick \[ns\] (rectangle, median).
    pub tick_ns: f64,
}

impl Measured {
    /// The force error the Pareto front ranks by: the worse finger against the exact
    /// surface.
    pub fn error(&self) -> f64 {
        self.n_err[0].max(self.n_err[1])
    }
}
