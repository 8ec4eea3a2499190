//! `host-sim accuracy`: what accuracy costs in time.
//!
//! Regenerates a reproducible report, `accuracy.md` with tables and `accuracy.svg` with
//! the Pareto plot, in `--out`: for each knob of the limit-surface numerics and the
//! controller (quadrature order, centre-of-rotation samples, aspect grid, interpolation,
//! f32/f64 precomputation, `libm`/`micromath`, ellipse/table/exact per tick), the error it
//! leaves (pitch, limit-surface radius, commanded force against the exact f64 answer) and
//! what it costs (host time per precomputation and per tick, from the same run; on the
//! emulated Cortex-M4F with `--target`), the Pareto front, the defaults, and the core
//! against an independent brute-force 2-D integration at matched accuracy.
//!
//! - [`crate::exact`] (shared with `required-force`): the exact answers (and the
//!   exact-integration-per-tick rule).
//! - [`knobs`]: the configurations and their measurement.
//! - [`extras`]: the aspect grid's and the surface representations' own errors.
//! - [`brute`]: the brute-force comparison.
//! - [`target`]: instruction counts in QEMU (`--target`).
//! - [`report`]: the Markdown and the plot.
//!
//! [`run`] is the whole report on plain options ([`AccuracyOptions`]); the command
//! `host-sim accuracy` (`cmd::accuracy`) parses its arguments into them.

pub mod brute;
pub mod extras;
pub mod knobs;
pub mod report;
pub mod target;

use indicatif::ProgressBar;
use knobs::{Budget, FingerRef, Knob, Measured, Variant};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What an accuracy run measures and where it writes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct AccuracyOptions {
    /// Fewer settings, loads and repetitions ([`Budget::quick`]).
    pub quick: bool,
    /// Also count instructions on the emulated Cortex-M4F (needs the firmware set up and
    /// built; slow).
    pub target: bool,
    /// No progress bar, no progress lines.
    pub quiet: bool,
    /// The directory of `accuracy.md` and `accuracy.svg`.
    pub out: PathBuf,
}

/// Why an accuracy run failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum AccuracyError {
    /// A file or directory under the output directory could not be written (the path and
    /// the reason).
    Write(String),
    /// A measurement failed.
    Measure(String),
}

impl fmt::Display for AccuracyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            AccuracyError::Write(e) | AccuracyError::Measure(e) => f.write_str(e),
        }
    }
}

impl std::error::Error for AccuracyError {}

/// A finished run: what it measured and the files it wrote.
#[derive(Debug, Clone)]
pub struct Report {
    /// What was measured.
    pub results: Results,
    /// `accuracy.md`.
    pub markdown: PathBuf,
    /// `accuracy.svg`.
    pub plot: PathBuf,
}

/// Where and when the report was made.
#[derive(Debug, Clone)]
pub struct Header {
    /// CPU model and core count.
    pub machine: String,
    /// UTC date and time.
    pub date: String,
    /// `git rev-parse --short HEAD`, with a note on uncommitted changes, if available.
    pub commit: Option<String>,
    /// `rustc --version`, if available.
    pub rustc: Option<String>,
    /// The command line, as `cargo run` would take it.
    pub command: String,
}

/// Everything the report shows.
#[derive(Debug, Clone)]
pub struct Results {
    /// Where and when.
    pub header: Header,
    /// The run's size.
    pub budget: Budget,
    /// The two fingers and their references.
    pub fingers: [FingerRef; 2],
    /// Each knob's rows: setting label and configuration.
    pub sections: Vec<(Knob, Vec<(String, Variant)>)>,
    /// What each distinct configuration measured.
    pub measured: BTreeMap<Variant, Measured>,
    /// The core's aspect grid on its own.
    pub aspect_grid: Vec<extras::AspectGridRow>,
    /// Probe names of [`Results::representation`].
    pub probes: Vec<String>,
    /// Surface representations on their own.
    pub representation: Vec<extras::RepresentationRow>,
    /// Core against brute force.
    pub brute: brute::BruteReport,
    /// Instruction counts on the emulated target (`--target`), or why there are none.
    pub target: Result<target::TargetResults, String>,
    /// Seconds the measurements took.
    pub elapsed_s: f64,
}

fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    )
}

fn machine() -> String {
    let info = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let model = info
        .lines()
        .find(|l| l.starts_with("model name"))
        .and_then(|l| l.split(':').nth(1))
        .map_or_else(|| "unknown CPU".to_string(), |s| s.trim().to_string());
    let cores = info.lines().filter(|l| l.starts_with("processor")).count();
    let cores = if cores == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        cores
    };
    format!(
        "{model}, {cores} core{} ({} {})",
        if cores == 1 { "" } else { "s" },
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

fn command_output(program: &str, args: &[&str]) -> Option<String> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let out = std::process::Command::new(program)
        .args(args)
        .current_dir(root)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_string())
}

fn header() -> Header {
    let commit = command_output("git", &["rev-parse", "--short", "HEAD"]).map(|c| {
        match command_output("git", &["status", "--porcelain", "--untracked-files=no"]) {
            Some(s) if !s.is_empty() => format!("{c} (with uncommitted changes)"),
            _ => c,
        }
    });
    let args: Vec<String> = std::env::args().skip(1).collect();
    Header {
        machine: machine(),
        date: utc_now(),
        commit,
        rustc: command_output("rustc", &["--version"]),
        command: format!("cargo run --release -p host-sim -- {}", args.join(" ")),
    }
}

/// The progress of a run, on stderr: a bar (see [`crate::progress`]) over its steps (the
/// references, each configuration measured, each timing round, the extras, the brute
/// force, each configuration on the target), the phase as its message; and each phase as
/// a line `accuracy: PHASE`, above the bar on a terminal and alone when stderr is not
/// one. Nothing at all with `--quiet`.
pub struct Progress {
    bar: ProgressBar,
    quiet: bool,
}

impl Progress {
    /// Progress over `len` steps, silent if `quiet`.
    pub fn new(len: u64, quiet: bool) -> Self {
        Progress {
            bar: crate::progress::bar(len, "steps", quiet),
            quiet,
        }
    }

    /// A new phase.
    pub fn phase(&self, msg: &str) {
        if self.quiet {
            return;
        }
        let line = format!("accuracy: {msg}");
        if self.bar.is_hidden() {
            eprintln!("{line}");
        } else {
            self.bar.println(line);
        }
        self.bar.set_message(msg.to_string());
    }

    /// `n` more steps done.
    pub fn steps(&self, n: u64) {
        self.bar.inc(n);
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// Measures everything: quicker if `quick`, with the instruction counts on the target if
/// `with_target`, its progress on stderr unless `quiet`.
pub fn measure_all(quick: bool, with_target: bool, quiet: bool) -> Result<Results, String> {
    let started = Instant::now();
    let budget = if quick {
        Budget::quick()
    } else {
        Budget::full()
    };
    let header = header();
    let sections: Vec<(Knob, Vec<(String, Variant)>)> =
        Knob::ALL.iter().map(|&k| (k, k.rows(&budget))).collect();
    let distinct = sections
        .iter()
        .flat_map(|(_, rows)| rows.iter().map(|(_, v)| v))
        .collect::<BTreeSet<_>>()
        .len() as u64;
    // References, configurations, timing rounds, extras, brute force, target.
    let steps = 2 + distinct + budget.rounds as u64 + 2 + if with_target { distinct } else { 0 };
    let progress = Progress::new(steps, quiet);
    progress.phase("exact references (order 128, f64)");
    let fingers = [
        FingerRef::build("rectangle", knobs::rect_config(), &budget)?,
        FingerRef::build("disc", knobs::disc_config(), &budget)?,
    ];
    progress.steps(2);
    let mut measured = measure_configurations(&sections, &fingers, &progress)?;
    time_configurations(&mut measured, &fingers, &budget, &progress)?;
    progress.phase("aspect grid and surface representations");
    let extras = Extras::measure(&fingers, &budget)?;
    progress.steps(1);
    progress.phase("core against brute force");
    let brute = brute::compare(&budget)?;
    progress.steps(1);
    let target = if with_target {
        progress.phase("instruction counts in QEMU");
        target::measure(&measured, &budget, &progress)
    } else {
        Err("not measured in this run (`--target`)".into())
    };
    Ok(Results {
        header,
        budget,
        fingers,
        sections,
        measured,
        aspect_grid: extras.aspect_grid,
        probes: extras.probes,
        representation: extras.representation,
        brute,
        target,
        elapsed_s: started.elapsed().as_secs_f64(),
    })
}

/// Each distinct configuration of `sections`, measured once against `fingers` (its
/// timings left for [`time_configurations`]).
fn measure_configurations(
    sections: &[(Knob, Vec<(String, Variant)>)],
    fingers: &[FingerRef; 2],
    progress: &Progress,
) -> Result<BTreeMap<Variant, Measured>, String> {
    let mut measured: BTreeMap<Variant, Measured> = BTreeMap::new();
    for (knob, rows) in sections {
        progress.phase(&format!("{} ({} settings)", knob.title(), rows.len()));
        for (_, v) in rows {
            if !measured.contains_key(v) {
                let m = knobs::measure(v, fingers)?;
                measured.insert(*v, m);
                progress.steps(1);
            }
        }
    }
    Ok(measured)
}

/// The host time of each configuration of `measured`, per precomputation and per tick:
/// the median over the budget's rounds, every configuration timed once in each round.
fn time_configurations(
    measured: &mut BTreeMap<Variant, Measured>,
    fingers: &[FingerRef; 2],
    budget: &Budget,
    progress: &Progress,
) -> Result<(), String> {
    progress.phase(&format!(
        "timing {} configurations, {} rounds",
        measured.len(),
        budget.rounds
    ));
    let mut timers = measured
        .keys()
        .map(|v| {
            Ok((
                *v,
                knobs::timer(v, fingers, budget)?,
                Vec::new(),
                Vec::new(),
            ))
        })
        .collect::<Result<Vec<_>, String>>()?;
    for _ in 0..budget.rounds {
        for (_, timer, startups, ticks) in timers.iter_mut() {
            let (s, t) = timer();
            startups.push(s);
            ticks.push(t);
        }
        progress.steps(1);
    }
    for (v, _, startups, ticks) in timers {
        if let Some(m) = measured.get_mut(&v) {
            m.precompute_us = knobs::median(startups);
            m.tick_ns = knobs::median(ticks);
        }
    }
    Ok(())
}

/// The aspect grid's and the surface representations' own errors.
struct Extras {
    aspect_grid: Vec<extras::AspectGridRow>,
    probes: Vec<String>,
    representation: Vec<extras::RepresentationRow>,
}

impl Extras {
    /// Measured on the rectangle and the disc of `fingers`.
    fn measure(fingers: &[FingerRef; 2], budget: &Budget) -> Result<Self, String> {
        let rect = &fingers[0].reference;
        let aspect_grid = extras::aspect_grid_rows(rect, &budget.aspects, budget)?;
        let probes = extras::representation_probes(rect)
            .into_iter()
            .map(|(name, _)| name)
            .collect();
        let representation =
            extras::representation_rows(rect, &fingers[1].reference, &budget.samples, budget)?;
        Ok(Extras {
            aspect_grid,
            probes,
            representation,
        })
    }
}

/// Measures what `opts` asks for and writes `accuracy.md` and `accuracy.svg` in its
/// directory (checked writable before the measurements).
pub fn run(opts: &AccuracyOptions) -> Result<Report, AccuracyError> {
    let write_err =
        |p: &Path, e: &dyn fmt::Display| AccuracyError::Write(format!("{}: {e}", p.display()));
    std::fs::create_dir_all(&opts.out).map_err(|e| write_err(&opts.out, &e))?;
    let markdown = opts.out.join("accuracy.md");
    let plot = opts.out.join("accuracy.svg");
    // Fail now, not after the measurements, if the files cannot be written.
    for p in [&markdown, &plot] {
        std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(p)
            .map_err(|e| write_err(p, &e))?;
    }
    let results =
        measure_all(opts.quick, opts.target, opts.quiet).map_err(AccuracyError::Measure)?;
    report::plot(&plot, &results).map_err(AccuracyError::Write)?;
    let md = report::markdown(&results);
    std::fs::write(&markdown, md).map_err(|e| write_err(&markdown, &e))?;
    Ok(Report {
        results,
        markdown,
        plot,
    })
}
