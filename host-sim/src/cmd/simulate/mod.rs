//! `host-sim simulate`: run grasp scenes against controllers and report. What the
//! firmware costs on the emulated target (`--link qemu`) is `target.rs`.

mod target;

use target::target_report;
pub use target::{check_firmware, elf_sections, Spread, TargetReport};

use crate::args::LinkName;
use crate::input::short;
use crate::link::handed;
use crate::link::qemu::default_paths;
use crate::sim::controllers::{self, ControllerChoice, ControllerKind, LinkKind};
use crate::sim::record::{RunSummary, Sample};
use crate::sim::report;
use crate::sim::run::{run_streaming, RunOptions, RunOutput};
use crate::sim::scene::Scene;
use crate::sim::stream::RunStream;
use crate::sim::trace::PlotTrace;
use crate::CliError;
use clap::Args;
use softgrip::controller::{Checked, Libm, Mode};
use std::path::{Path, PathBuf};

/// Arguments of `host-sim simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// The scene file (TOML). Omit with --all.
    scene: Option<PathBuf>,
    /// Run every scene in the scenes folder and end with a comparison table.
    #[arg(long)]
    all: bool,
    /// The scenes folder for --all.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes"))]
    scenes: PathBuf,
    /// The controllers, comma-separated: softgrip (default mode), softgrip-ellipse,
    /// softgrip-table, constant, coulomb, box, fixed-torsion, slip-servo, or all.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "softgrip")]
    controller: Vec<ControllerChoice>,
    /// The link to the device: `pty` (alias `inprocess`: the firmware loop on a thread,
    /// over a pseudo-terminal), `direct` (the same loop and bytes through memory, on this
    /// thread), `qemu` (the Cortex-M4F firmware in QEMU, over its USART) or `serial` (the
    /// firmware on a board, over the serial port --port).
    #[arg(long, value_enum, default_value = "pty")]
    link: LinkName,
    /// The serial port for `--link serial` (e.g. /dev/ttyUSB0, or a QEMU pty).
    #[arg(long)]
    port: Option<PathBuf>,
    /// The serial port's speed for `--link serial` [baud].
    #[arg(long, default_value_t = crate::link::serial::DEFAULT_BAUD)]
    baud: u32,
    /// The firmware ELF for `--link qemu` (default: what scripts/firmware-build.sh builds).
    #[arg(long)]
    firmware: Option<PathBuf>,
    /// Where QEMU is unpacked for `--link qemu` (default: .firmware/qemu, from
    /// scripts/firmware-setup.sh).
    #[arg(long)]
    qemu: Option<PathBuf>,
    /// A finger file (`host-sim calibrate --out`'s, or another scene) whose [finger]
    /// replaces every scene's, whose [controller] mu, if set, the μ softgrip believes,
    /// and whose [margins], if any, softgrip's measured margins (over the scene's
    /// [controller], under the flags below). On a limit-surface finger it is the truth
    /// and the belief alike.
    #[arg(long)]
    finger: Option<PathBuf>,
    /// softgrip's configuration over every scene's: `--config FILE` and one flag per
    /// field, as if written in each scene's `[controller]` table (the flags over the file).
    #[command(flatten)]
    config: crate::config::ConfigArgs,
    /// Where to write summary.json, the time series and the plots.
    #[arg(long, default_value = "sim-out")]
    out: PathBuf,
    /// No progress bar (there is none either when stderr is not a terminal).
    #[arg(long)]
    quiet: bool,
}

fn scenes(args: &SimulateArgs) -> Result<Vec<PathBuf>, CliError> {
    if args.all {
        let mut v: Vec<PathBuf> = std::fs::read_dir(&args.scenes)
            .map_err(|e| CliError::Usage(format!("--scenes: {}: {e}", args.scenes.display())))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "toml"))
            .collect();
        v.sort();
        if v.is_empty() {
            return Err(CliError::Usage(format!(
                "--scenes: no .toml scenes in {}",
                args.scenes.display()
            )));
        }
        Ok(v)
    } else {
        match &args.scene {
            Some(p) => Ok(vec![p.clone()]),
            None => Err(CliError::Usage(
                "simulate: give a scene file or --all".into(),
            )),
        }
    }
}

fn controllers(args: &SimulateArgs) -> Vec<ControllerKind> {
    ControllerChoice::kinds(&args.controller)
}

fn file_safe(s: &str) -> String {
    s.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The CSV of one run of `scene` against `controller`.
fn csv_path(out: &Path, scene: &str, controller: &str) -> PathBuf {
    out.join(format!(
        "timeseries_{}_{}.csv",
        file_safe(scene),
        file_safe(controller)
    ))
}

/// The plots of one scene, from each run's bounded trace (`sim::trace`).
fn write_scene_plots(
    out: &Path,
    scene: &str,
    runs: &[(RunOutput, PlotTrace)],
) -> Result<(), CliError> {
    let fail = |e: &dyn std::fmt::Display| CliError::Failed(format!("--out: {e}"));
    let kept: Vec<Vec<Sample>> = runs.iter().map(|(_, t)| t.samples()).collect();
    let slips: Vec<Vec<(f64, f64)>> = runs.iter().map(|(_, t)| t.slip_intervals()).collect();
    let traces: Vec<(&str, &[Sample])> = runs
        .iter()
        .zip(&kept)
        .map(|((r, _), s)| (r.summary.controller.as_str(), s.as_slice()))
        .collect();
    let surface = runs
        .first()
        .map(|(r, _)| r.surface.as_slice())
        .unwrap_or(&[]);
    report::plot_surface(
        &out.join(format!("surface_{}.svg", file_safe(scene))),
        &format!("{scene}: load against the limit surface"),
        &traces,
        surface,
    )
    .map_err(|e| fail(&e))?;
    report::plot_force_with_slips(
        &out.join(format!("force_{}.svg", file_safe(scene))),
        &format!("{scene}: normal force"),
        &traces,
        &slips,
    )
    .map_err(|e| fail(&e))?;
    Ok(())
}

/// Runs `host-sim simulate`: every scene is loaded and checked before the first run (a bad
/// one is a usage error before any output), then each runs against each controller.
pub fn run_cmd(args: &SimulateArgs) -> Result<(), CliError> {
    let link = link_kind(args)?;
    let paths = scenes(args)?;
    let names = controllers(args);
    check_link_use(args, &link, paths.len(), &names)?;
    let loaded = load_scenes(args, &paths, &names, &link)?;
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", args.out.display())))?;
    let all = run_all(args, &loaded, &names, &link)?;
    write_summary(&args.out.join("summary.json"), &link, &all)?;
    print_report(args, &all, names.len() > 1 || loaded.len() > 1);
    Ok(())
}

/// The link `--link` names (with its port, firmware and QEMU paths).
fn link_kind(args: &SimulateArgs) -> Result<LinkKind, CliError> {
    Ok(match args.link {
        LinkName::Pty => LinkKind::InProcess,
        LinkName::Direct => LinkKind::Direct,
        LinkName::Qemu => {
            // The ELF is checked in check_link_use, once the controllers need it.
            let (qemu_dir, firmware) = default_paths();
            LinkKind::Qemu {
                qemu_dir: args.qemu.clone().unwrap_or(qemu_dir),
                firmware: args.firmware.clone().unwrap_or(firmware),
            }
        }
        LinkName::Serial => serial_link(args)?,
    })
}

/// `--link serial`: its `--port` must be given and exist.
fn serial_link(args: &SimulateArgs) -> Result<LinkKind, CliError> {
    let Some(port) = args.port.clone() else {
        return Err(CliError::Usage(
            "--link serial needs --port PATH (the device's serial port)".into(),
        ));
    };
    if !port.exists() {
        return Err(CliError::Usage(format!(
            "--port: {} does not exist",
            port.display()
        )));
    }
    Ok(LinkKind::Serial {
        port,
        baud: args.baud,
    })
}

/// Refuses a link no controller would use, a missing firmware ELF, and more than one run
/// on a board.
fn check_link_use(
    args: &SimulateArgs,
    link: &LinkKind,
    scenes: usize,
    names: &[ControllerKind],
) -> Result<(), CliError> {
    // Only softgrip runs on the device; the baselines always run in this process.
    if args.link != LinkName::Pty && !names.iter().any(|k| k.is_softgrip()) {
        let given = names.iter().map(|k| k.name()).collect::<Vec<_>>().join(",");
        return Err(CliError::Usage(format!(
            "--link {}: --controller {given} runs in this process, not over a link; \
             add a softgrip controller (e.g. --controller softgrip,{given}) or drop --link",
            args.link.name(),
        )));
    }
    if let LinkKind::Qemu { firmware, .. } = link {
        check_firmware(firmware).map_err(CliError::Usage)?;
    }
    let device_runs = scenes * names.iter().filter(|k| k.is_softgrip()).count();
    if matches!(link, LinkKind::Serial { .. }) && device_runs > 1 {
        // A board keeps its controller between runs (a reconfiguration takes over the
        // running grasp), so a second run would not start from rest as the others do.
        return Err(CliError::Usage(format!(
            "--link serial: one softgrip run per invocation (this is {device_runs}): the \
             device keeps its grasp between runs; reset it between invocations"
        )));
    }
    Ok(())
}

/// Every scene, with `--finger` and the configuration flags applied, checked.
fn load_scenes(
    args: &SimulateArgs,
    paths: &[PathBuf],
    names: &[ControllerKind],
    link: &LinkKind,
) -> Result<Vec<(Scene, Checked)>, CliError> {
    let finger = match &args.finger {
        Some(path) => Some(crate::finger_file::FingerFile::load(path, "--finger")?),
        None => None,
    };
    let overrides = args.config.table()?;
    let mut loaded = Vec::new();
    for p in paths {
        let scene = Scene::load(p).map_err(|e| CliError::Usage(e.to_string()))?;
        let mut scene = match &finger {
            Some(f) => scene
                .with_finger(f.finger.clone(), f.controller.number("mu"))
                .map_err(|e| CliError::Usage(format!("--finger: {e}")))?,
            None => scene,
        };
        // The finger file's measured margins over the scene's, under the flags.
        if let Some(f) = &finger {
            scene.controller.config.extend(f.margins.clone());
        }
        scene.controller.config.extend(overrides.clone());
        let shown = short(&p.display().to_string());
        let cfg = check_scene(&scene, names, link)
            .map_err(|e| CliError::Usage(format!("{shown}: {e}")))?;
        loaded.push((scene, cfg));
    }
    Ok(loaded)
}

/// Checks a scene's settings before any run, so a bad one is a usage error: its effects,
/// its configuration (once), the precomputation of each softgrip mode that will run, and
/// the baselines' patch. On an in-process link the precomputed controllers are the ones
/// the runs use ([`handed`]); the firmware in QEMU or on a board precomputes its own.
fn check_scene(
    scene: &Scene,
    names: &[ControllerKind],
    link: &LinkKind,
) -> Result<Checked, String> {
    scene.pipeline().map_err(|e| e.to_string())?;
    let cfg = crate::sim::run::controller_config(scene).map_err(|e| e.to_string())?;
    let in_process = matches!(link, LinkKind::InProcess | LinkKind::Direct);
    let mut modes: Vec<Mode> = names
        .iter()
        .filter_map(|k| k.softgrip_mode(cfg.mode))
        .collect();
    // On an in-process link a mode two controllers share is precomputed once (the store
    // keeps it by configuration).
    if !in_process {
        // The device would only say that its configuration failed: check one mode here.
        modes.truncate(1);
    }
    for mode in modes {
        // The precomputation's own refusals (an l/a it cannot sample, an overflowing
        // sensor range), named by the scene's keys.
        let checked = cfg.with_mode(mode);
        let built = if in_process {
            handed::precompute::<Libm>(&checked).map(drop)
        } else {
            softgrip::controller::Controller::<f32>::from_checked(&checked).map(drop)
        };
        built.map_err(|e| {
            crate::sim::run::build_error(&e, &scene.controller, &checked).to_string()
        })?;
    }
    // The baselines' fixed patch (at controller.constant_force_n, unless given).
    let baseline = scene.controller.baseline(cfg.fault_force_n);
    for c in names.iter().filter(|c| !c.is_softgrip()) {
        controllers::Baseline::new(c.name(), &cfg, &baseline)?;
    }
    Ok(cfg)
}

/// Runs every scene against every controller, streaming each run to its CSV and drawing
/// each scene's plots.
fn run_all(
    args: &SimulateArgs,
    loaded: &[(Scene, Checked)],
    names: &[ControllerKind],
    link: &LinkKind,
) -> Result<Vec<RunSummary>, CliError> {
    let total: u64 = loaded
        .iter()
        .map(|(s, _)| (s.duration_s * s.tick_hz).round() as u64 * names.len() as u64)
        .sum();
    let bar = crate::progress::bar(total, "ticks", args.quiet);
    let mut all: Vec<RunSummary> = Vec::new();
    for (scene, cfg) in loaded {
        let mut runs = Vec::new();
        for c in names.iter().map(|k| k.name()) {
            bar.set_message(format!("{} / {c}", scene.name));
            runs.push(run_one(&args.out, scene, cfg, c, link, &bar)?);
        }
        write_scene_plots(&args.out, &scene.name, &runs)?;
        all.extend(runs.into_iter().map(|(r, _)| r.summary));
    }
    bar.finish_and_clear();
    Ok(all)
}

/// One run; each tick goes to the CSV as it is produced, the plots get a bounded trace.
fn run_one(
    out: &Path,
    scene: &Scene,
    cfg: &Checked,
    controller: &str,
    link: &LinkKind,
    bar: &indicatif::ProgressBar,
) -> Result<(RunOutput, PlotTrace), CliError> {
    let path = csv_path(out, &scene.name, controller);
    let mut stream = RunStream::create(&path)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", path.display())))?;
    let run = run_streaming(
        scene,
        cfg,
        controller,
        link,
        Some(bar),
        RunOptions::default(),
        &mut stream,
    )
    .map_err(CliError::Failed)?;
    let trace = stream
        .finish()
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", path.display())))?;
    Ok((run, trace))
}

/// summary.json: the runs, and on QEMU the firmware's costs on the target.
fn write_summary(path: &Path, link: &LinkKind, all: &[RunSummary]) -> Result<(), CliError> {
    match link {
        LinkKind::InProcess | LinkKind::Direct | LinkKind::Serial { .. } => {
            report::write_summary_json(path, all)
                .map_err(|e| CliError::Failed(format!("--out: {e}")))
        }
        LinkKind::Qemu { firmware, .. } => {
            let target = target_report(firmware, all)?;
            println!("{}", target.describe());
            let text = serde_json::to_string_pretty(&serde_json::json!({
                "runs": all,
                "target": target,
            }))
            .map_err(|e| CliError::Failed(e.to_string()))?;
            std::fs::write(path, text + "\n").map_err(|e| CliError::Failed(format!("--out: {e}")))
        }
    }
}

/// The summary table, each softgrip run's speed and step costs, and (for more than one
/// run) the comparison table.
fn print_report(args: &SimulateArgs, all: &[RunSummary], compare: bool) {
    print!("{}", report::summary_table(all));
    println!();
    for r in all
        .iter()
        .filter(|r| ControllerKind::name_is_softgrip(&r.controller))
    {
        let shares: Vec<String> = r
            .step_cost_share
            .iter()
            .map(|(k, v)| format!("{k} {:.0} %", 100.0 * v))
            .collect();
        println!(
            "{} / {}: real-time factor {:.1} ({} link), {} ticks in {:.2} s; \
             plant step cost: {}",
            r.scene,
            r.controller,
            r.real_time_factor,
            args.link.name(),
            r.ticks,
            r.wall_s,
            shares.join(", ")
        );
    }
    if compare {
        println!();
        print!("{}", report::comparison_table(all));
    }
    println!("wrote {}", args.out.display());
}
