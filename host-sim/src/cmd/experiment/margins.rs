//! `experiment cyclic` and `experiment hold`: the margin protocols
//! ([`crate::experiment::cyclic`], [`crate::experiment::hold`]) on the plant, at one normal
//! force; writes `cyclic.csv`/`.svg` or `hold.csv`/`.svg` into `--out`.

use super::{finger, usage, write, ExperimentArgs, Kind, Plant};
use crate::experiment::cyclic::{self, CyclicPlan};
use crate::experiment::hold::{self, HoldPlan};
use crate::experiment::timed::{Frame, TimedRig};
use crate::experiment::{FingerSpec, FlsRig};
use crate::input::short_num;
use crate::plot::{plot_panels, Panel, Series};
use crate::CliError;
use clap::Args;
use softgrip_calibrate::margin_csv::{write_cyclic, write_hold, Axis, CyclicRow, HoldRow};
use softgrip_calibrate::margins::{
    CREEP_SLIDE_M_S, CREEP_TURN_RAD_S, RATCHET_SLIDE_M, RATCHET_TURN_RAD,
};
use std::path::{Path, PathBuf};

/// The fractions both protocols default to (docs/decisions/margin-protocols.md).
const FRACTIONS: [f64; 11] = cyclic::DEFAULT_FRACTIONS;

/// The margin protocols' settings (docs/experiments.md).
#[derive(Debug, Clone, Args)]
pub struct MarginArgs {
    /// cyclic, hold: the normal force they run at [N].
    #[arg(long, default_value_t = 2.0)]
    pub normal_force: f64,
    // docs/decisions/margin-protocols.md
    /// cyclic, hold: the loads as fractions of the measured onset, comma-separated
    /// [default: 0.5 to 1 in steps of 0.05].
    #[arg(long, value_delimiter = ',')]
    pub fractions: Option<Vec<f64>>,
    /// cyclic: load cycles per fraction.
    #[arg(long, default_value_t = cyclic::DEFAULT_CYCLES)]
    pub cycles: usize,
    // docs/decisions/margin-protocols.md
    /// cyclic: cycle frequency [Hz].
    #[arg(long, default_value_t = cyclic::DEFAULT_FREQUENCY_HZ)]
    pub cycle_hz: f64,
    // docs/decisions/margin-protocols.md
    /// hold: the ramp to each load [s].
    #[arg(long, default_value_t = hold::DEFAULT_RAMP_S)]
    pub ramp_s: f64,
    // docs/decisions/margin-protocols.md
    /// hold: how long each load is held [s].
    #[arg(long, default_value_t = hold::DEFAULT_HOLD_S)]
    pub hold_s: f64,
}

fn check(m: &MarginArgs) -> Result<Vec<f64>, CliError> {
    let bad = |flag: &str, v: f64, want: &str| {
        usage(format!("--{flag}: {} must be {want}", short_num(v)))
    };
    let n = m.normal_force;
    if !(n > 0.0 && n.is_finite()) {
        return Err(bad("normal-force", n, "a finite force > 0 [N]"));
    }
    let fractions = m.fractions.clone().unwrap_or(FRACTIONS.to_vec());
    if fractions.is_empty() {
        return Err(usage("--fractions: give at least one fraction"));
    }
    if let Some(&f) = fractions.iter().find(|f| !(**f > 0.0 && **f <= 2.0)) {
        return Err(bad("fractions", f, "in (0, 2]"));
    }
    if !(1..=1000).contains(&m.cycles) {
        return Err(usage(format!("--cycles: {} must be 1 to 1000", m.cycles)));
    }
    for (flag, v, lo, hi) in [
        ("cycle-hz", m.cycle_hz, 0.01, 100.0),
        ("ramp-s", m.ramp_s, 0.0, 60.0),
        ("hold-s", m.hold_s, 0.01, 600.0),
    ] {
        if !(v >= lo && v <= hi) {
            return Err(bad(flag, v, &format!("in [{lo}, {hi}]")));
        }
    }
    Ok(fractions)
}

/// Runs `experiment cyclic` or `experiment hold`.
pub fn run(args: &ExperimentArgs, spec: FingerSpec) -> Result<(), CliError> {
    let m = &args.margins;
    let fractions = check(m)?;
    let n = m.normal_force;
    let rig: Box<dyn TimedRig> = match args.plant {
        Plant::Fls => Box::new(FlsRig::new(spec, n, n).map_err(|e| usage(format!("finger: {e}")))?),
        Plant::Brush => Box::new(finger::brush(&args.finger)?),
    };
    let mut noise = super::start(args)?;
    let out = &args.out;
    let frame = Frame {
        normal_n: n,
        fractions,
        onsets: args.repeats,
    };
    let written = if args.kind == Kind::Cyclic {
        let plan = CyclicPlan {
            frame,
            cycles: m.cycles,
            frequency_hz: m.cycle_hz,
        };
        let rows = cyclic::cyclic(rig.as_ref(), &plan, &mut noise);
        [
            write(out, "cyclic.csv", &write_cyclic(&rows))?,
            plot_cyclic(&out.join("cyclic.svg"), &rows)?,
        ]
    } else {
        let plan = HoldPlan {
            frame,
            ramp_s: m.ramp_s,
            hold_s: m.hold_s,
        };
        let rows = hold::hold(rig.as_ref(), &plan, &mut noise);
        [
            write(out, "hold.csv", &write_hold(&rows))?,
            plot_hold(&out.join("hold.svg"), &rows)?,
        ]
    };
    for p in written {
        println!("wrote {}", p.display());
    }
    Ok(())
}

/// `log10(max(x, 1e-12))`: the plots' scale for slips that span many decades.
fn lg(x: f64) -> f64 {
    x.max(1e-12).log10()
}

fn panel(title: String, y_label: &str, points: Vec<(f64, f64)>, threshold: f64) -> Panel {
    let xs = points.iter().map(|p| p.0);
    let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
        (l.min(x), h.max(x))
    });
    let mut series = vec![Series {
        label: "measured".into(),
        points,
        line: false,
    }];
    if lo.is_finite() {
        series.push(Series {
            label: "threshold".into(),
            points: vec![(lo, lg(threshold)), (hi, lg(threshold))],
            line: true,
        });
    }
    Panel {
        title,
        x_label: "fraction of the onset".into(),
        y_label: y_label.into(),
        series,
    }
}

fn fail(e: String) -> CliError {
    CliError::Failed(format!("--out: {e}"))
}

/// One panel per axis (force, then torsion) with its y label and threshold from `axes`,
/// titled `title(axis)`, of `points(axis)` (fractions against log10 slips), to `path`.
fn plot_axes(
    path: &Path,
    title: impl Fn(Axis) -> String,
    axes: [(&str, f64); 2],
    points: impl Fn(Axis) -> Vec<(f64, f64)>,
) -> Result<PathBuf, CliError> {
    let panels: Vec<Panel> = [Axis::Force, Axis::Torsion]
        .into_iter()
        .zip(axes)
        .map(|(axis, (label, threshold))| panel(title(axis), label, points(axis), threshold))
        .collect();
    plot_panels(path, &panels).map_err(fail)?;
    Ok(path.to_path_buf())
}

/// Each cycle's slip on its axis (log10) against the fraction, with the threshold.
fn plot_cyclic(path: &Path, rows: &[CyclicRow]) -> Result<PathBuf, CliError> {
    plot_axes(
        path,
        |axis| format!("Cyclic {} (every cycle)", axis.name()),
        [
            ("log10 slide per cycle [m]", RATCHET_SLIDE_M),
            ("log10 turn per cycle [rad]", RATCHET_TURN_RAD),
        ],
        |axis| {
            rows.iter()
                .filter(|r| r.axis == axis && r.cycle > 0)
                .map(|r| {
                    let slip = if axis == Axis::Force {
                        r.slide_m
                    } else {
                        r.turn_rad
                    };
                    (r.fraction, lg(slip))
                })
                .collect()
        },
    )
}

/// Each hold's rate at its end (log10) against the fraction, with the threshold.
fn plot_hold(path: &Path, rows: &[HoldRow]) -> Result<PathBuf, CliError> {
    plot_axes(
        path,
        |axis| format!("Hold {}", axis.name()),
        [
            ("log10 slide rate at the end [m/s]", CREEP_SLIDE_M_S),
            ("log10 turn rate at the end [rad/s]", CREEP_TURN_RAD_S),
        ],
        |axis| {
            rows.iter()
                .filter(|r| r.axis == axis && r.time_s > 0.0)
                .map(|r| {
                    let rate = if axis == Axis::Force {
                        r.slide_rate_m_s
                    } else {
                        r.turn_rate_rad_s
                    };
                    (r.fraction, lg(rate))
                })
                .collect()
        },
    )
}
