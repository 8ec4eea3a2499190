//! What the firmware costs on the emulated Cortex-M4F (`simulate --link qemu`):
//! `summary.json`'s `target` from the runs' device metrics and the ELF's sections, and
//! the check that `--firmware` is an ELF QEMU can boot.

use crate::input::short;
use crate::sim::controllers::ControllerKind;
use crate::sim::record::RunSummary;
use crate::CliError;
use serde::Serialize;
use softgrip::controller::Mode;
use std::collections::BTreeMap;
use std::path::Path;

/// Minimum, median and maximum of a set of counts.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Spread {
    /// Smallest.
    pub min: f64,
    /// Median.
    pub median: f64,
    /// Largest.
    pub max: f64,
}

/// What the firmware costs on the emulated Cortex-M4F: `summary.json`'s `target`.
#[derive(Debug, Clone, Serialize)]
pub struct TargetReport {
    /// The firmware ELF.
    pub firmware: String,
    /// Instructions of the start-up precomputation in the default mode (ellipse, or the
    /// only mode run), the most over the scenes run (each scene configures its finger).
    pub startup_instructions: f64,
    /// Start-up instructions by mode (the most over the scenes).
    pub startup_instructions_by_mode: BTreeMap<String, f64>,
    /// Instructions per tick by mode, over all ticks of all scenes run (median of the
    /// per-run medians, and the extremes).
    pub tick_instructions: BTreeMap<String, Spread>,
    /// Section sizes \[bytes\]: `.vector_table`, `.text`, `.rodata`, `.data`, `.bss`,
    /// `.uninit`.
    pub sections: BTreeMap<String, u64>,
    /// Flash use \[bytes\]: vector table, code, read-only data and the initial values of
    /// `.data`.
    pub flash_bytes: u64,
    /// Static RAM \[bytes\]: `.data`, `.bss`, `.uninit`.
    pub static_ram_bytes: u64,
    /// The deepest stack of any run \[bytes\], by stack painting.
    pub stack_peak_bytes: f64,
    /// Static RAM plus the stack peak \[bytes\].
    pub ram_bytes: f64,
}

impl TargetReport {
    pub(super) fn describe(&self) -> String {
        let ticks: Vec<String> = self
            .tick_instructions
            .iter()
            .map(|(m, s)| format!("{m} {:.0}/{:.0}/{:.0}", s.min, s.median, s.max))
            .collect();
        format!(
            "target (QEMU netduinoplus2, instructions): start-up {:.0}; tick min/median/max {}; \
             flash {} B, RAM {} B static + {:.0} B stack peak",
            self.startup_instructions,
            ticks.join(", "),
            self.flash_bytes,
            self.static_ram_bytes,
            self.stack_peak_bytes
        )
    }
}

/// The mode a softgrip run's costs are filed under (`softgrip` runs the default mode,
/// the ellipse); `None` for a baseline.
fn mode_of(controller: &str) -> Option<&'static str> {
    match ControllerKind::from_name(controller)? {
        ControllerKind::Softgrip | ControllerKind::SoftgripEllipse => Some(Mode::Ellipse.name()),
        ControllerKind::SoftgripTable => Some(Mode::Table.name()),
        _ => None,
    }
}

/// Refuses, in one line naming `--firmware`, a file QEMU's Cortex-M4F could not boot: not
/// an ELF, an ELF for another machine or word size, or one without the vector table a
/// `cortex-m-rt` firmware starts from (QEMU would otherwise start and the link would end
/// in "Broken pipe").
pub fn check_firmware(path: &Path) -> Result<(), String> {
    use object::{Architecture, Object, ObjectSection};
    let shown = short(&path.display().to_string());
    let data = crate::input::read_capped(path, "--firmware", crate::input::ELF_CAP_BYTES)
        .map_err(|e| e.to_string())?;
    let file = object::File::parse(&*data)
        .map_err(|e| format!("--firmware: {shown} is not an ELF file ({e})"))?;
    if file.format() != object::BinaryFormat::Elf {
        return Err(format!(
            "--firmware: {shown} is a {:?} file, not an ELF",
            file.format()
        ));
    }
    if file.architecture() != Architecture::Arm || file.is_64() {
        return Err(format!(
            "--firmware: {shown} is an ELF for {:?}{}, not the 32-bit Arm Cortex-M4F \
             (build it with scripts/firmware-build.sh)",
            file.architecture(),
            if file.is_64() { " (64-bit)" } else { "" }
        ));
    }
    if file
        .section_by_name(".vector_table")
        .is_none_or(|s| s.size() == 0)
    {
        return Err(format!(
            "--firmware: {shown} has no .vector_table: not a cortex-m-rt firmware \
             (build it with scripts/firmware-build.sh)"
        ));
    }
    Ok(())
}

/// The section sizes of an ELF file.
pub fn elf_sections(path: &Path) -> Result<BTreeMap<String, u64>, String> {
    use object::{Object, ObjectSection};
    let data = crate::input::read_capped(path, "--firmware", crate::input::ELF_CAP_BYTES)
        .map_err(|e| e.to_string())?;
    let file = object::File::parse(&*data).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = BTreeMap::new();
    for name in [
        ".vector_table",
        ".text",
        ".rodata",
        ".data",
        ".bss",
        ".uninit",
    ] {
        let size = file.section_by_name(name).map_or(0, |s| s.size());
        out.insert(name.to_string(), size);
    }
    Ok(out)
}

pub(super) fn target_report(
    firmware: &Path,
    runs: &[RunSummary],
) -> Result<TargetReport, CliError> {
    let sections = elf_sections(firmware).map_err(CliError::Failed)?;
    let get = |k: &str| sections.get(k).copied().unwrap_or(0);
    let flash = get(".vector_table") + get(".text") + get(".rodata") + get(".data");
    let static_ram = get(".data") + get(".bss") + get(".uninit");
    let mut startup = BTreeMap::new();
    let mut ticks: BTreeMap<String, Vec<(f64, f64, f64)>> = BTreeMap::new();
    let mut stack: f64 = 0.0;
    for r in runs {
        let Some(mode) = mode_of(&r.controller) else {
            continue;
        };
        let m = &r.metrics;
        if let Some(v) = m.get("device_startup_instructions") {
            let e = startup.entry(mode.to_string()).or_insert(0.0);
            *e = f64::max(*e, *v);
        }
        if let (Some(a), Some(b), Some(c)) = (
            m.get("device_tick_min_instructions"),
            m.get("device_tick_median_instructions"),
            m.get("device_tick_max_instructions"),
        ) {
            ticks
                .entry(mode.to_string())
                .or_default()
                .push((*a, *b, *c));
        }
        stack = stack.max(m.get("device_stack_peak_bytes").copied().unwrap_or(0.0));
    }
    let tick_instructions = ticks
        .into_iter()
        .map(|(mode, v)| {
            let mut medians: Vec<f64> = v.iter().map(|x| x.1).collect();
            medians.sort_by(f64::total_cmp);
            let spread = Spread {
                min: v.iter().map(|x| x.0).fold(f64::INFINITY, f64::min),
                median: medians[medians.len() / 2],
                max: v.iter().map(|x| x.2).fold(0.0, f64::max),
            };
            (mode, spread)
        })
        .collect();
    Ok(TargetReport {
        firmware: firmware.display().to_string(),
        startup_instructions: startup
            .get(Mode::Ellipse.name())
            .or_else(|| startup.values().next())
            .copied()
            .unwrap_or(0.0),
        startup_instructions_by_mode: startup,
        tick_instructions,
        sections,
        flash_bytes: flash,
        static_ram_bytes: static_ram,
        stack_peak_bytes: stack,
        ram_bytes: static_ram as f64 + stack,
    })
}
