//! Instruction counts on the emulated Cortex-M4F (`host-sim accuracy --target`): each
//! configuration the report measured on the host is sent to the firmware in QEMU
//! (`-icount shift=0`, TIM2 counts instructions) with `Configure`, its start-up cost read
//! back with `GetStats`, and the 256 timing loads of [`super::knobs::timing_loads`] ticked
//! over the UART. The quadrature order, samples, aspects, nodes and mode are runtime
//! settings of one firmware; precision and square root are firmware variants
//! (`scripts/firmware-build.sh default precompute-f64 fast-math`). An f64 tick has no
//! firmware, nor has the exact rule.

use super::knobs::{median, rect_config, timing_loads, Budget, Engine, MathKind, Measured};
use super::knobs::{Precision, Variant};
use crate::link::qemu::{self, default_paths, QemuLink};
use crate::link::Link;
use softgrip::protocol::{CostUnit, Reply, Request, SensorFrame};
use std::collections::BTreeMap;

/// One configuration's cost on the target, in instructions.
#[derive(Debug, Clone, Copy)]
pub struct TargetCost {
    /// Start-up precomputation.
    pub startup: f64,
    /// Median tick over the timing loads.
    pub tick_median: f64,
    /// Largest tick.
    pub tick_max: f64,
}

/// What `--target` measured.
#[derive(Debug, Clone, Default)]
pub struct TargetResults {
    /// Cost by configuration.
    pub costs: BTreeMap<Variant, TargetCost>,
    /// The firmware ELFs used.
    pub firmware: Vec<String>,
    /// Configurations or variants that could not be measured, and why.
    pub skipped: Vec<String>,
}

/// The firmware variant a configuration needs, if there is one.
pub fn firmware_variant(v: &Variant) -> Option<&'static str> {
    match v.engine {
        Engine::Exact => None,
        Engine::Grid {
            precision, math, ..
        } => match (precision, math) {
            (Precision::F32, MathKind::Libm) => Some("default"),
            (Precision::F32, MathKind::Micromath) => Some("fast-math"),
            (Precision::F64Precompute, MathKind::Libm) => Some("precompute-f64"),
            _ => None,
        },
    }
}

fn run_one(link: &mut QemuLink, v: &Variant, loads: usize) -> Result<TargetCost, String> {
    let cfg = v.config(&rect_config());
    match link
        .exchange(&Request::Configure(cfg))
        .map_err(|e| e.to_string())?
    {
        Reply::Configured(Ok(())) => {}
        other => return Err(format!("Configure: {other:?}")),
    }
    let Reply::Stats(stats) = link
        .exchange(&Request::GetStats)
        .map_err(|e| e.to_string())?
    else {
        return Err("GetStats: no stats".into());
    };
    if stats.cost_unit != CostUnit::Instructions {
        return Err(format!("the device counts {:?}", stats.cost_unit));
    }
    let mut costs = Vec::new();
    for (i, (fx, fy, mn, n)) in timing_loads().into_iter().take(loads).enumerate() {
        let frame = SensorFrame {
            seq: i as u32,
            timestamp_us: 1000 * (i as u64 + 1),
            tangential_force_n: [fx as f32, fy as f32],
            torsional_moment_nm: mn as f32,
            normal_force_n: n as f32,
            slip: Default::default(),
        };
        match link
            .exchange(&Request::Sensor(frame))
            .map_err(|e| e.to_string())?
        {
            Reply::Command(c) => costs.push(f64::from(c.tick_cost)),
            other => return Err(format!("Sensor: {other:?}")),
        }
    }
    let tick_max = costs.iter().copied().fold(0.0, f64::max);
    Ok(TargetCost {
        startup: f64::from(stats.startup_cost),
        tick_median: median(costs),
        tick_max,
    })
}

/// Measures every configuration of `measured` that a firmware variant can run.
pub fn measure(
    measured: &BTreeMap<Variant, Measured>,
    b: &Budget,
    progress: &super::Progress,
) -> Result<TargetResults, String> {
    let (qemu_dir, _) = default_paths();
    if !qemu::binary(&qemu_dir).exists() {
        return Err(format!(
            "no QEMU in {} (run scripts/firmware-setup.sh)",
            qemu_dir.display()
        ));
    }
    let loads = if b.quick { 64 } else { 256 };
    let mut by_variant: BTreeMap<&'static str, Vec<Variant>> = BTreeMap::new();
    let mut out = TargetResults::default();
    for v in measured.keys() {
        match firmware_variant(v) {
            Some(fw) => by_variant.entry(fw).or_default().push(*v),
            None => {
                out.skipped
                    .push(format!("{}: no firmware for it", v.describe()));
                progress.steps(1);
            }
        }
    }
    for (fw, variants) in by_variant {
        let elf = qemu::firmware(fw);
        if !elf.exists() {
            out.skipped.push(format!(
                "{fw}: {} missing (scripts/firmware-build.sh {fw})",
                elf.display()
            ));
            progress.steps(variants.len() as u64);
            continue;
        }
        progress.phase(&format!("QEMU: {fw} ({} configurations)", variants.len()));
        let mut link = QemuLink::boot(&qemu_dir, &elf).map_err(|e| format!("{fw}: {e}"))?;
        for v in variants {
            match run_one(&mut link, &v, loads) {
                Ok(c) => {
                    out.costs.insert(v, c);
                }
                Err(e) => out.skipped.push(format!("{}: {e}", v.describe())),
            }
            progress.steps(1);
        }
        let _ = link.shutdown(0);
        let shown = elf
            .to_string_lossy()
            .split("/../")
            .last()
            .map_or_else(|| elf.display().to_string(), str::to_string);
        out.firmware.push(format!("{fw}: {shown}"));
    }
    Ok(out)
}
