//! `host-sim simulate`: run grasp scenes against controllers and report.

use crate::sim::controllers;
use crate::sim::record::{RunSummary, Sample};
use crate::sim::report;
use crate::sim::run::{run, RunOutput};
use crate::sim::scene::Scene;
use crate::CliError;
use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
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
    /// The controller: softgrip (default mode), softgrip-ellipse, softgrip-table,
    /// constant, coulomb, box, fixed-torsion, slip-servo, or all.
    #[arg(long, default_value = "softgrip")]
    controller: String,
    /// The link to the device: `inprocess` (the firmware loop on a thread, over a
    /// pseudo-terminal). `qemu` and a serial device path come with the firmware work.
    #[arg(long, default_value = "inprocess")]
    link: String,
    /// Where to write summary.json, the time series and the plots.
    #[arg(long, default_value = "sim-out")]
    out: PathBuf,
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

fn controllers(args: &SimulateArgs) -> Result<Vec<String>, CliError> {
    if args.controller == "all" {
        return Ok(controllers::ALL.iter().map(|s| s.to_string()).collect());
    }
    let names: Vec<String> = args
        .controller
        .split(',')
        .map(|s| s.trim().to_string())
        .collect();
    for n in &names {
        if !controllers::NAMES.contains(&n.as_str()) {
            return Err(CliError::Usage(format!(
                "--controller: unknown controller \"{n}\", expected all or one of {}",
                controllers::NAMES.join(", ")
            )));
        }
    }
    Ok(names)
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

fn write_scene_outputs(out: &Path, scene: &str, runs: &[RunOutput]) -> Result<(), CliError> {
    let fail = |e: &dyn std::fmt::Display| CliError::Failed(format!("--out: {e}"));
    for r in runs {
        let name = format!(
            "timeseries_{}_{}.csv",
            file_safe(scene),
            file_safe(&r.summary.controller)
        );
        report::write_csv(&out.join(name), &r.samples).map_err(|e| fail(&e))?;
    }
    let traces: Vec<(&str, &[Sample])> = runs
        .iter()
        .map(|r| (r.summary.controller.as_str(), r.samples.as_slice()))
        .collect();
    let surface = runs.first().map(|r| r.surface.as_slice()).unwrap_or(&[]);
    report::plot_surface(
        &out.join(format!("surface_{}.svg", file_safe(scene))),
        &format!("{scene}: load against the limit surface"),
        &traces,
        surface,
    )
    .map_err(|e| fail(&e))?;
    report::plot_force(
        &out.join(format!("force_{}.svg", file_safe(scene))),
        &format!("{scene}: normal force"),
        &traces,
    )
    .map_err(|e| fail(&e))?;
    Ok(())
}

/// Runs `host-sim simulate`.
pub fn run_cmd(args: &SimulateArgs) -> Result<(), CliError> {
    if args.link != "inprocess" {
        return Err(CliError::Usage(format!(
            "--link: \"{}\" is not available yet; only inprocess (the firmware loop over a \
             pseudo-terminal) is",
            args.link
        )));
    }
    let paths = scenes(args)?;
    let names = controllers(args)?;
    let mut loaded = Vec::new();
    for p in &paths {
        let text = std::fs::read_to_string(p)
            .map_err(|e| CliError::Usage(format!("{}: {e}", p.display())))?;
        let scene = Scene::load(p).map_err(|e| CliError::Usage(e.to_string()))?;
        loaded.push((scene, text));
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| CliError::Failed(format!("--out: {}: {e}", args.out.display())))?;
    let total: u64 = loaded
        .iter()
        .map(|(s, _)| (s.duration_s * s.tick_hz).round() as u64 * names.len() as u64)
        .sum();
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} ticks {msg} [{elapsed}<{eta}]")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut all: Vec<RunSummary> = Vec::new();
    for (scene, text) in &loaded {
        let mut runs = Vec::new();
        for c in &names {
            bar.set_message(format!("{} / {c}", scene.name));
            let out = run(scene, Some(text), c, Some(&bar)).map_err(CliError::Failed)?;
            runs.push(out);
        }
        write_scene_outputs(&args.out, &scene.name, &runs)?;
        all.extend(runs.into_iter().map(|r| r.summary));
    }
    bar.finish_and_clear();
    report::write_summary_json(&args.out.join("summary.json"), &all)
        .map_err(|e| CliError::Failed(format!("--out: {e}")))?;
    print!("{}", report::summary_table(&all));
    println!();
    for r in &all {
        if r.controller.starts_with("softgrip") {
            let shares: Vec<String> = r
                .step_cost_share
                .iter()
                .map(|(k, v)| format!("{k} {:.0} %", 100.0 * v))
                .collect();
            println!(
                "{} / {}: real-time factor {:.1} (in-process link), {} ticks in {:.2} s; \
                 plant step cost: {}",
                r.scene,
                r.controller,
                r.real_time_factor,
                r.ticks,
                r.wall_s,
                shares.join(", ")
            );
        }
    }
    if names.len() > 1 || loaded.len() > 1 {
        println!();
        print!("{}", report::comparison_table(&all));
    }
    println!("wrote {}", args.out.display());
    Ok(())
}
