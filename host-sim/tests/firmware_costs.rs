//! The firmware's costs on the emulated Cortex-M4F, over a trace built to contain the
//! longest tick paths, and the cost table of docs/firmware-costs.md, which is generated
//! from them.
//!
//! QEMU's instruction counts (`-icount shift=0`) and the ELF's sizes are deterministic for
//! a given firmware, so this is not a timing test: the table of docs/firmware-costs.md
//! between the `firmware-costs` markers must equal what this test measures, or the test
//! fails and prints the table (`SOFTGRIP_WRITE_DOCS=1` writes it into that page). The budgets of
//! the firmware issue are asserted too (flash, static RAM + stack peak, the worst tick with
//! every solve at its cap, the start-ups): the test fails on any budget missed, naming it.
//!
//! Needs `scripts/firmware-setup.sh` and `scripts/firmware-build.sh default
//! prebuilt-tables solve-to-cap`; compiled as ignored without them (`host-sim/build.rs`) unless
//! `SOFTGRIP_REQUIRE_QEMU=1`.
//!
//! The trace (docs/firmware.md, "The worst tick"): the qemu_link test's 300 smooth ticks,
//! then every load of a grid over `|f_t|`, `m_n` and `N` (inside, below and above the
//! force grid), each after a far load so that the previous tick's node hint misses and the
//! node search runs in full, with slip signals on a third of them (the slip response's
//! second utilisation and its emergency rise), then the loads a host-side scan found to
//! need the most Illinois iterations, each after a far load and with a gross slip signal.

use host_sim::cmd::simulate::elf_sections;
use host_sim::link::qemu::QemuLink;
use host_sim::link::Link;
use softgrip::controller::{Controller, ControllerConfig, Libm, Measurement, Mode, SlipSignal};
use softgrip::protocol::{Reply, Request, SensorFrame};
use std::path::{Path, PathBuf};

mod common;

const BEGIN: &str = "<!-- firmware-costs:begin";
const END: &str = "<!-- firmware-costs:end -->";
/// The page that holds the table, relative to the repository's root.
const DOCS_PAGE: &str = "docs/firmware-costs.md";

fn frame(seq: u32, ft: [f32; 2], mn: f32, n: f32, slip: SlipSignal) -> SensorFrame {
    SensorFrame {
        seq,
        timestamp_us: 1000 * u64::from(seq) + 1,
        tangential_force_n: ft,
        torsional_moment_nm: mn,
        normal_force_n: n,
        slip,
    }
}

const FT_N: [f32; 15] = [
    0.0, 0.001, 0.01, 0.05, 0.1, 0.3, 0.7, 1.5, 3.0, 5.0, 8.0, 12.0, 16.0, 25.0, 40.0,
];
const MN_NM: [f32; 10] = [0.0, 1e-5, 1e-4, 5e-4, 1e-3, 3e-3, 6e-3, 0.01, 0.02, 0.05];
const N_N: [f32; 6] = [3.0, 0.05, 19.5, 30.0, 1.0, 8.0];

/// The far load that precedes each hard one: alternately nothing and a large load.
fn far(k: usize) -> ([f32; 2], f32) {
    if k.is_multiple_of(2) {
        ([0.0, 0.0], 0.0)
    } else {
        ([30.0, 0.0], 0.04)
    }
}

/// The loads (of a dense grid) whose tick takes the most Illinois iterations on the host,
/// each right after a far load, with a gross slip signal.
fn hardest_loads(cfg: ControllerConfig, count: usize) -> Vec<([f32; 2], f32)> {
    let mut base = Controller::<f32, Libm>::new(cfg).unwrap();
    let mut scored = Vec::new();
    for i in 0..48 {
        for j in 0..48 {
            let ft = 40.0 * (i as f32 / 47.0).powi(2);
            let mn = 0.05 * (j as f32 / 47.0).powi(2);
            for (k, slip) in [SlipSignal::None, SlipSignal::Gross]
                .into_iter()
                .enumerate()
            {
                let mut c = base.clone();
                let (fa, ma) = far(i + j + k);
                let f0 = frame(1, fa, ma, 3.0, SlipSignal::None);
                c.tick(&Measurement::from(&f0));
                let f1 = frame(2, [ft * 0.8, ft * 0.6], mn, 3.0, slip);
                let out = c.tick(&Measurement::from(&f1));
                scored.push((out.iterations, [ft * 0.8, ft * 0.6], mn));
            }
        }
    }
    base.tick(&Measurement::from(&frame(
        0,
        [0.0; 2],
        0.0,
        3.0,
        SlipSignal::None,
    )));
    scored.sort_by_key(|s| std::cmp::Reverse(s.0));
    scored.dedup_by(|a, b| a.1 == b.1 && a.2 == b.2);
    scored.into_iter().take(count).map(|s| (s.1, s.2)).collect()
}

/// The whole trace for `cfg` (see the module docs).
fn trace(cfg: ControllerConfig) -> Vec<SensorFrame> {
    let mut out = Vec::new();
    let mut push = |ft, mn, n, slip| {
        let seq = out.len() as u32;
        out.push(frame(seq, ft, mn, n, slip));
    };
    for i in 0..300u32 {
        let p = i as f32 * 0.05;
        let n = if i % 97 == 5 { f32::NAN } else { 3.0 + p.cos() };
        push(
            [3.0 * p.sin().abs(), 0.5 * p.cos()],
            0.01 * (0.7 * p).sin(),
            n,
            SlipSignal::None,
        );
    }
    let mut k = 0;
    for &ft in &FT_N {
        for &mn in &MN_NM {
            let (fa, ma) = far(k);
            push(fa, ma, 3.0, SlipSignal::None);
            let slip = [SlipSignal::None, SlipSignal::Gross, SlipSignal::Incipient][k % 3];
            push([ft, 0.0], mn, N_N[k % N_N.len()], slip);
            k += 1;
        }
    }
    for (ft, mn) in hardest_loads(cfg, 40) {
        let (fa, ma) = far(k);
        push(fa, ma, 3.0, SlipSignal::None);
        push(ft, mn, 3.0, SlipSignal::Gross);
        k += 1;
    }
    out
}

/// What one boot of a firmware measured in one mode.
#[derive(Debug, Clone, Copy)]
struct ModeCost {
    startup: u32,
    tick_median: u32,
    tick_max: u32,
    stack_peak: u32,
}

/// How a firmware's commands must match the host controller's.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Match {
    /// Bit for bit.
    Exact,
    /// Within 1e-3 relative: the `solve-to-cap` build's solves have no tolerance and stop
    /// at the iteration cap, with a bracket (and an answer) that may differ from the host's
    /// in the fifth digit.
    Close,
}

/// Boots `elf`, configures `cfg`, runs the trace, checks every command against the host
/// controller (`reference`) as `matching` says, and returns the costs.
fn run(
    qemu: &Path,
    elf: &Path,
    cfg: ControllerConfig,
    mut reference: Controller<f32, Libm>,
    matching: Match,
) -> ModeCost {
    let mut link = QemuLink::boot(qemu, elf).unwrap();
    assert_eq!(
        link.exchange(&Request::Configure(cfg)).unwrap(),
        Reply::Configured(Ok(()))
    );
    let frames = trace(cfg);
    let mut costs = Vec::with_capacity(frames.len());
    let mut worst = (0u32, 0usize, 0u8);
    for (i, f) in frames.iter().enumerate() {
        let Reply::Command(cmd) = link.exchange(&Request::Sensor(*f)).unwrap() else {
            panic!("no command at tick {i}")
        };
        let want = reference.tick(&Measurement::from(f));
        match matching {
            Match::Exact => assert_eq!(
                cmd.normal_force_n.to_bits(),
                want.command_n.to_bits(),
                "tick {i}"
            ),
            Match::Close => assert!(
                (cmd.normal_force_n - want.command_n).abs() <= 1e-3 * want.command_n.abs(),
                "tick {i}: {} against {}",
                cmd.normal_force_n,
                want.command_n
            ),
        }
        assert_eq!(
            cmd.utilisation.to_bits(),
            want.utilisation.to_bits(),
            "tick {i}"
        );
        if cmd.tick_cost > worst.0 {
            worst = (cmd.tick_cost, i, want.iterations);
        }
        costs.push(cmd.tick_cost);
    }
    let Reply::Stats(s) = link.exchange(&Request::GetStats).unwrap() else {
        panic!("no stats")
    };
    assert_eq!(link.shutdown(0).unwrap(), 0);
    let w = &frames[worst.1];
    eprintln!(
        "{} {:?}: worst tick {} instructions at trace index {} (|f_t| {:?} N, m_n {} N·m, \
         N {} N, slip {:?}; {} Illinois iterations on the host)",
        elf.parent()
            .and_then(Path::file_name)
            .unwrap()
            .to_string_lossy(),
        cfg.mode,
        worst.0,
        worst.1,
        w.tangential_force_n,
        w.torsional_moment_nm,
        w.normal_force_n,
        w.slip,
        worst.2
    );
    costs.sort_unstable();
    ModeCost {
        startup: s.startup_cost,
        tick_median: costs[costs.len() / 2],
        tick_max: costs[costs.len() - 1],
        stack_peak: s.stack_peak_bytes,
    }
}

/// Flash and static RAM of an ELF [bytes].
fn sizes(elf: &Path) -> (u64, u64) {
    let s = elf_sections(elf).unwrap();
    let get = |k: &str| s.get(k).copied().unwrap_or(0);
    (
        get(".vector_table") + get(".text") + get(".rodata") + get(".data"),
        get(".data") + get(".bss") + get(".uninit"),
    )
}

/// `12345678` as `12 345 678`.
fn grouped(n: u64) -> String {
    let s = n.to_string();
    let mut out = String::new();
    for (i, c) in s.chars().enumerate() {
        if i > 0 && (s.len() - i).is_multiple_of(3) {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

struct Firmware {
    name: &'static str,
    /// Only its ticks count: the `solve-to-cap` measurement build, whose flash, RAM and
    /// start-up are the default firmware's.
    ticks_only: bool,
    flash: u64,
    static_ram: u64,
    ellipse: Option<ModeCost>,
    table: ModeCost,
}

fn render(toolchain: &str, ticks: usize, rows: &[Firmware]) -> String {
    let mut t = format!(
        "{BEGIN} (generated by host-sim/tests/firmware_costs.rs; SOFTGRIP_WRITE_DOCS=1 \
         rewrites it) -->\n\
         | firmware (rustc {toolchain}, {ticks}-tick worst-case trace per mode) | flash | \
         static RAM + stack peak, ellipse / table | start-up, ellipse / table | tick max \
         (median), ellipse | tick max (median), table |\n\
         | --- | ---: | ---: | ---: | ---: | ---: |\n"
    );
    let tick = |m: &ModeCost| {
        format!(
            "{} ({})",
            grouped(u64::from(m.tick_max)),
            grouped(u64::from(m.tick_median))
        )
    };
    for f in rows {
        let e = f.ellipse;
        let ellipse_tick = e.as_ref().map_or("–".into(), tick);
        if f.ticks_only {
            t += &format!(
                "| `{}`: `default` with every solve run to its iteration cap (the worst tick) \
                 | – | – | – | {ellipse_tick} | {} |\n",
                f.name,
                tick(&f.table),
            );
            continue;
        }
        let ram = |m: Option<ModeCost>| {
            m.map_or("–".into(), |m| {
                format!("{} B", grouped(f.static_ram + u64::from(m.stack_peak)))
            })
        };
        let startup = e.map_or("–".into(), |m| grouped(u64::from(m.startup)));
        t += &format!(
            "| `{}` | {} B | {} / {} | {startup} / {} | {ellipse_tick} | {} |\n",
            f.name,
            grouped(f.flash),
            ram(e),
            ram(Some(f.table)),
            grouped(u64::from(f.table.startup)),
            tick(&f.table),
        );
    }
    t += &format!(
        "| budget | {} B | {} B | {} (table); prebuilt {} | {} | {} |\n",
        grouped(FLASH_BUDGET_BYTES),
        grouped(RAM_BUDGET_BYTES),
        grouped(STARTUP_TABLE_BUDGET),
        grouped(STARTUP_PREBUILT_BUDGET),
        grouped(TICK_ELLIPSE_BUDGET),
        grouped(TICK_TABLE_BUDGET),
    );
    t += &margin_row(rows);
    t += END;
    t
}

/// The budgets (the item 1), one per column of the table's last rows.
const FLASH_BUDGET_BYTES: u64 = 64 * 1024;
const RAM_BUDGET_BYTES: u64 = 16 * 1024;
const STARTUP_TABLE_BUDGET: u64 = 8_000_000;
const STARTUP_PREBUILT_BUDGET: u64 = 1_000_000;
const TICK_ELLIPSE_BUDGET: u64 = 2_000;
const TICK_TABLE_BUDGET: u64 = 5_000;

/// One budgeted figure of one firmware: what it is, as measured, and its limit.
struct Budgeted {
    firmware: &'static str,
    what: &'static str,
    value: u64,
    limit: u64,
}

/// Every budgeted figure the rows measured.
fn budgeted(rows: &[Firmware]) -> Vec<Budgeted> {
    let mut all = Vec::new();
    for f in rows {
        let mut add = |what, value: u64, limit| {
            all.push(Budgeted {
                firmware: f.name,
                what,
                value,
                limit,
            });
        };
        if let Some(e) = &f.ellipse {
            add("tick, ellipse", u64::from(e.tick_max), TICK_ELLIPSE_BUDGET);
        }
        add(
            "tick, table",
            u64::from(f.table.tick_max),
            TICK_TABLE_BUDGET,
        );
        if f.ticks_only {
            continue;
        }
        add("flash", f.flash, FLASH_BUDGET_BYTES);
        let ram = |m: &ModeCost| f.static_ram + u64::from(m.stack_peak);
        if let Some(e) = &f.ellipse {
            add("static RAM + stack, ellipse", ram(e), RAM_BUDGET_BYTES);
        }
        add("static RAM + stack, table", ram(&f.table), RAM_BUDGET_BYTES);
        let startup = u64::from(f.table.startup);
        if f.ellipse.is_some() {
            add("start-up, table", startup, STARTUP_TABLE_BUDGET);
        } else {
            add("start-up, prebuilt", startup, STARTUP_PREBUILT_BUDGET);
        }
    }
    all
}

/// The budgets missed, by firmware and name.
fn check_budgets(rows: &[Firmware]) -> Vec<String> {
    budgeted(rows)
        .into_iter()
        .filter(|b| b.value > b.limit)
        .map(|b| format!("{}: {}", b.firmware, b.what))
        .collect()
}

/// The table's last row: what is left of each budget after the largest figure measured
/// against it (negative when a budget is missed, which `check_budgets` then names).
fn margin_row(rows: &[Firmware]) -> String {
    let all = budgeted(rows);
    let left = |whats: &[&str]| {
        let m = all
            .iter()
            .filter(|b| whats.contains(&b.what))
            .map(|b| b.limit as i64 - b.value as i64)
            .min()
            .unwrap_or(0);
        let g = grouped(m.unsigned_abs());
        if m < 0 {
            format!("−{g}")
        } else {
            g
        }
    };
    format!(
        "| left (budget − largest measured) | {} B | {} B | {} (table); prebuilt {} | {} | {} |\n",
        left(&["flash"]),
        left(&["static RAM + stack, ellipse", "static RAM + stack, table"]),
        left(&["start-up, table"]),
        left(&["start-up, prebuilt"]),
        left(&["tick, ellipse"]),
        left(&["tick, table"]),
    )
}

/// The default configuration in `mode` (both modes at the default's other settings).
fn in_mode(mode: Mode) -> ControllerConfig {
    ControllerConfig {
        mode,
        ..ControllerConfig::default()
    }
}

/// Measures the three firmware builds in QEMU (`qemu`): the default in both modes, the
/// prebuilt tables in table mode, and the default with every solve run to its cap.
fn measure(qemu: &Path) -> [Firmware; 3] {
    let (default_elf, prebuilt_elf, cap_elf) = (
        host_sim::link::qemu::firmware("default"),
        host_sim::link::qemu::firmware("prebuilt-tables"),
        host_sim::link::qemu::firmware("solve-to-cap"),
    );
    // Both modes at the default's other settings.
    let ellipse = in_mode(Mode::Ellipse);
    let table = in_mode(Mode::Table);
    let ctl = |cfg| Controller::<f32, Libm>::new(cfg).unwrap();
    let (flash, static_ram) = sizes(&default_elf);
    let default = Firmware {
        name: "default",
        ticks_only: false,
        flash,
        static_ram,
        ellipse: Some(run(qemu, &default_elf, ellipse, ctl(ellipse), Match::Exact)),
        table: run(qemu, &default_elf, table, ctl(table), Match::Exact),
    };
    let (flash, static_ram) = sizes(&prebuilt_elf);
    let prebuilt = Firmware {
        name: "prebuilt-tables",
        ticks_only: false,
        flash,
        static_ram,
        ellipse: None,
        table: run(
            qemu,
            &prebuilt_elf,
            table,
            Controller::<f32, Libm>::new_precomputed_in::<f64>(table).unwrap(),
            Match::Exact,
        ),
    };
    let to_cap = Firmware {
        name: "solve-to-cap",
        ticks_only: true,
        flash: 0,
        static_ram: 0,
        ellipse: Some(run(qemu, &cap_elf, ellipse, ctl(ellipse), Match::Close)),
        table: run(qemu, &cap_elf, table, ctl(table), Match::Close),
    };
    [default, prebuilt, to_cap]
}

/// The firmware's toolchain channel (firmware/rust-toolchain.toml), `root` the workspace.
fn toolchain(root: &Path) -> String {
    let toolchain = std::fs::read_to_string(root.join("firmware/rust-toolchain.toml")).unwrap();
    toolchain
        .lines()
        .find_map(|l| l.strip_prefix("channel = \""))
        .and_then(|l| l.strip_suffix('"'))
        .unwrap()
        .to_string()
}

/// The docs page's cost table is `table_md` (with `SOFTGRIP_WRITE_DOCS=1`, made so).
fn check_docs_page(root: &Path, table_md: &str) {
    let page_path = root.join(DOCS_PAGE);
    let page = std::fs::read_to_string(&page_path).unwrap_or_else(|e| panic!("{DOCS_PAGE}: {e}"));
    let (start, end) = (
        page.find(BEGIN)
            .unwrap_or_else(|| panic!("{DOCS_PAGE} has no firmware-costs table")),
        page.find(END)
            .unwrap_or_else(|| panic!("{DOCS_PAGE}'s firmware-costs table has no end marker"))
            + END.len(),
    );
    if page[start..end] != *table_md {
        if std::env::var("SOFTGRIP_WRITE_DOCS").is_ok_and(|v| v == "1") {
            let new = format!("{}{table_md}{}", &page[..start], &page[end..]);
            std::fs::write(&page_path, new).unwrap();
            eprintln!("{DOCS_PAGE}: cost table rewritten");
        } else {
            panic!(
                "{DOCS_PAGE}'s firmware cost table is stale; the measured one is above \
                 (SOFTGRIP_WRITE_DOCS=1 writes it)"
            );
        }
    }
}

#[test]
#[cfg_attr(
    no_qemu_prebuilt,
    ignore = "needs QEMU and the firmware: bash scripts/firmware-setup.sh && bash scripts/firmware-build.sh default prebuilt-tables solve-to-cap"
)]
fn the_readme_cost_table_is_the_measured_one_and_every_budget_holds() {
    let Some(qemu) = common::qemu_for(&["default", "prebuilt-tables", "solve-to-cap"]) else {
        return;
    };
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let rows = measure(&qemu);
    let toolchain = toolchain(&root);
    let table_md = render(&toolchain, trace(in_mode(Mode::Ellipse)).len(), &rows);
    eprintln!("{table_md}");

    check_docs_page(&root, &table_md);

    let missed = check_budgets(&rows);
    assert!(missed.is_empty(), "budgets missed: {}", missed.join(", "));
}
