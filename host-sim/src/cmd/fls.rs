//! `host-sim fls`: sweep one limit surface and print it for people (`table`), for
//! spreadsheets (`csv`) or for programs (`json`).

use crate::args::{PatchArgs, Precision};
use crate::input::{config_error, config_reason, short, short_num};
use crate::CliError;
use clap::{Args, ValueEnum};
use serde::Serialize;
use softgrip::controller::FingerShape;
use softgrip::fls::{EllipseFit, InscribedEllipse, RadialGap};
use softgrip::{
    ConfigError, FlsConfig, FlsModel, FlsPoint, FlsTable, QuadratureOrder, Real, Shape,
};
use std::io::Write;

/// Largest `--samples`: the sweep table's fixed capacity less its closing point.
pub const MAX_SAMPLES: usize = 4096;

/// Output format of `fls`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// Aligned columns for people.
    Table,
    /// Comma-separated values with a header row.
    Csv,
    /// One JSON object.
    Json,
}

/// Arguments of `host-sim fls`.
#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct FlsArgs {
    /// Shape, pressure exponent, skew.
    #[command(flatten)]
    patch: PatchArgs,
    /// Aspect ratio l/a of the rectangle (ignored for the disc).
    #[arg(long, default_value_t = 1.0)]
    aspect: f64,
    /// Evaluate at these d_c/a (comma-separated) instead of along the sweep.
    #[arg(long, value_delimiter = ',')]
    at: Vec<f64>,
    /// Number of sweep samples (the ellipse fit always uses the sweep).
    #[arg(long, default_value_t = 64)]
    samples: usize,
    /// Tanh-sinh nodes on each side of an interval's centre.
    #[arg(long, default_value_t = QuadratureOrder::DEFAULT.nodes_per_side())]
    order: usize,
    /// Arithmetic of the computation.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    precision: Precision,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Table)]
    format: Format,
    /// Also draw the surface and its Eq. 10 ellipse into this SVG file (f64, 128 samples).
    #[arg(long)]
    plot: Option<std::path::PathBuf>,
}

#[derive(Debug, Serialize)]
struct Sample {
    d: f64,
    f: f64,
    m: f64,
}

#[derive(Debug, Serialize)]
struct EllipseOut {
    /// Least-squares semi-axis along f̃.
    f_semi_axis: f64,
    /// Least-squares semi-axis along m̃.
    m_semi_axis: f64,
    /// RMS residual of the fit.
    rms_residual: f64,
    /// Largest radial gap between the exact surface and the Eq. 10 ellipse.
    max_radial_gap: f64,
    /// That gap over the ellipse's radius.
    max_relative_gap: f64,
    /// Where the gap is largest.
    max_gap_at: Sample,
    /// How far the exact surface pokes outside the ellipse (0 if it never does).
    max_outside: f64,
}

/// The ellipse inscribed in the exact surface, as ellipse mode fits it at start-up, and
/// what it costs in force over the exact surface.
#[derive(Debug, Serialize)]
struct InscribedOut {
    /// Semi-axis along f̃.
    f_semi_axis: f64,
    /// Semi-axis along m̃/pitch (1 is Eq. 10's).
    m_over_pitch_semi_axis: f64,
    /// Largest extra force it asks over the exact surface, over load directions [%]
    /// (for a contact of fixed size; less when the contact grows with the force).
    force_over_exact_max_pct: f64,
    /// Mean of the same over 91 load directions [%].
    force_over_exact_mean_pct: f64,
}

#[derive(Debug, Serialize)]
struct Report {
    shape: &'static str,
    k: f64,
    aspect: Option<f64>,
    skew: f64,
    alpha: f64,
    locus: Option<f64>,
    precision: &'static str,
    order: usize,
    pitch: f64,
    /// Whether each ray from the origin meets the swept curve once (needed for table lookup).
    star_shaped: bool,
    ellipse: EllipseOut,
    inscribed: InscribedOut,
    samples: Vec<Sample>,
}

fn usage(e: ConfigError) -> CliError {
    CliError::Usage(config_error(e.param(), &e))
}

/// How far `f̃ = f_t/(μN)` may exceed its physical bound 1 before the answer is refused as
/// a quadrature too coarse for the surface: f32's documented accuracy (2e-6); at the
/// default order the error is below 1e-9 in f64 (tests/fls_accuracy.rs).
pub const F_NORM_EXCESS_MAX: f64 = 2e-6;

fn sample<T: Real>(p: &FlsPoint<T>) -> Sample {
    Sample {
        d: p.d.to_f64(),
        f: p.f.to_f64(),
        m: p.m.to_f64(),
    }
}

/// Validates the arguments into a limit-surface configuration.
fn config(args: &FlsArgs) -> Result<FlsConfig, CliError> {
    // The surface's moment scale grows like l/a: beyond these the ellipse fit's fourth
    // powers overflow f32 (and, far out, f64).
    let rect = args.patch.shape == FingerShape::Rect;
    if rect && args.aspect.is_finite() && !(1e-6..=1e6).contains(&args.aspect) {
        return Err(CliError::Usage(format!(
            "--aspect: {} is out of range, expected 1e-6 <= aspect <= 1e6",
            short_num(args.aspect)
        )));
    }
    let order = QuadratureOrder::new(args.order).map_err(usage)?;
    let shape = match args.patch.shape {
        FingerShape::Rect => Shape::Rect {
            aspect: args.aspect,
        },
        FingerShape::Disc => Shape::Disc,
    };
    for (name, v) in [("alpha", args.patch.alpha), ("aspect", args.aspect)] {
        if !v.is_finite() && (rect || name != "aspect") {
            return Err(CliError::Usage(format!(
                "--{name}: must be a finite number"
            )));
        }
    }
    let skew = if args.patch.skew.is_nan() || args.patch.skew != 0.0 {
        Some((
            args.patch.skew,
            args.patch.alpha,
            args.patch.locus.unwrap_or(args.patch.skew / 2.0),
        ))
    } else {
        if let Some(h) = args.patch.locus {
            if !h.is_finite() || h < 0.0 {
                return Err(CliError::Usage(format!(
                    "--locus: {} is out of range, expected locus >= 0",
                    short_num(h)
                )));
            }
        }
        None
    };
    if !(2..=MAX_SAMPLES).contains(&args.samples) {
        return Err(CliError::Usage(format!(
            "--samples: {} is out of range, expected 2 ..= {MAX_SAMPLES}",
            short(&args.samples.to_string())
        )));
    }
    for &d in &args.at {
        if !(d.is_finite() && d >= 0.0) {
            return Err(CliError::Usage(format!(
                "--at: {} is out of range, expected finite d_c/a >= 0",
                short_num(d)
            )));
        }
    }
    Ok(FlsConfig {
        shape,
        k: args.patch.k,
        skew,
        order,
    })
}

/// Runs `host-sim fls`.
pub fn run(args: &FlsArgs) -> Result<(), CliError> {
    let cfg = config(args)?;
    match args.precision {
        Precision::F64 => run_in::<f64>(args, cfg),
        Precision::F32 => run_in::<f32>(args, cfg),
    }?;
    if let Some(path) = &args.plot {
        plot(path, cfg)?;
    }
    Ok(())
}

fn plot(path: &std::path::Path, cfg: FlsConfig) -> Result<(), CliError> {
    use crate::plot::{ellipse, plot_curves, Curve};
    let model = FlsModel::<f64>::new(cfg).map_err(usage)?;
    let table = FlsTable::<f64, 129>::sweep(&model, 128).map_err(usage)?;
    let label = format!(
        "{} k = {}{}",
        cfg.shape.name(),
        cfg.k,
        cfg.skew.map_or(String::new(), |(d, a, h)| format!(
            ", skew {d}, α {a}, locus {h}"
        ))
    );
    let curves = [
        Curve {
            label: label.clone(),
            points: table.points().iter().map(|p| (p.f, p.m)).collect(),
            dashed: false,
        },
        ellipse(model.pitch(), "Eq. 10 ellipse"),
    ];
    plot_curves(
        path,
        &format!("Friction limit surface: {label}"),
        "f̃ = f_t / (μN)",
        "m̃ = m_n / (μNa)",
        &curves,
    )
    .map_err(|e| CliError::Failed(format!("--plot: {e}")))
}

/// A model error naming the flag the user typed: `locus` when `--locus` was not given
/// (it defaults to `--skew`/2) is reported on `--skew`.
fn model_usage(args: &FlsArgs, e: ConfigError) -> CliError {
    if e.param() == "locus" && args.patch.locus.is_none() {
        let reason = config_reason(&e);
        return CliError::Usage(format!(
            "--skew: {} with the default --locus (skew/2 = {}): {reason}",
            short_num(args.patch.skew),
            short_num(args.patch.skew / 2.0)
        ));
    }
    usage(e)
}

/// Refuses an answer with `f̃ > 1 +` [`F_NORM_EXCESS_MAX`]: no load can exceed `μN`, so
/// such an `f̃` is quadrature error, from an `--order` too low for the surface.
fn check_physical(args: &FlsArgs, samples: &[Sample]) -> Result<(), CliError> {
    let worst = samples.iter().map(|s| s.f).fold(0.0_f64, f64::max);
    if worst > 1.0 + F_NORM_EXCESS_MAX {
        return Err(CliError::Usage(format!(
            "--order: {} is too low for this surface: f_t/(μN) reaches {worst:.7} > 1, \
             which no load can; raise --order (default {})",
            args.order,
            QuadratureOrder::DEFAULT.nodes_per_side()
        )));
    }
    Ok(())
}

fn run_in<T: Real>(args: &FlsArgs, cfg: FlsConfig) -> Result<(), CliError> {
    let model = FlsModel::<T>::new(cfg).map_err(|e| model_usage(args, e))?;
    let table: Box<FlsTable<T, { MAX_SAMPLES + 1 }>> =
        Box::new(FlsTable::sweep(&model, args.samples).map_err(usage)?);
    let fit = EllipseFit::fit(table.points())
        .ok_or_else(|| CliError::Failed("the sweep does not determine an ellipse".into()))?;
    let gap = RadialGap::find(&model, &table);
    let inscribed = InscribedEllipse::fit_within(table.points(), &[table.points()])
        .ok_or_else(|| CliError::Failed("no ellipse fits inside the sweep".into()))?;
    let (over_max, over_mean) = inscribed.force_overhead(table.points(), 91);
    let samples: Vec<Sample> = if args.at.is_empty() {
        table
            .points()
            .iter()
            .filter(|p| p.d.is_finite())
            .map(sample)
            .collect()
    } else {
        args.at
            .iter()
            .map(|&d| sample(&model.point(T::of(d))))
            .collect()
    };
    let swept: Vec<Sample> = table
        .points()
        .iter()
        .filter(|p| p.d.is_finite())
        .map(sample)
        .collect();
    check_physical(args, &swept)?;
    check_physical(args, &samples)?;
    let report = Report {
        shape: cfg.shape.name(),
        k: args.patch.k,
        aspect: matches!(cfg.shape, Shape::Rect { .. }).then_some(args.aspect),
        skew: args.patch.skew,
        alpha: args.patch.alpha,
        locus: cfg.skew.map(|s| s.2),
        precision: match args.precision {
            Precision::F64 => "f64",
            Precision::F32 => "f32",
        },
        order: args.order,
        pitch: table.pitch().to_f64(),
        star_shaped: table.is_star_shaped(),
        ellipse: EllipseOut {
            f_semi_axis: fit.f_semi_axis.to_f64(),
            m_semi_axis: fit.m_semi_axis.to_f64(),
            rms_residual: fit.rms_residual.to_f64(),
            max_radial_gap: gap.max_gap.to_f64(),
            max_relative_gap: gap.max_relative_gap.to_f64(),
            max_gap_at: sample(&gap.at),
            max_outside: gap.max_outside.to_f64(),
        },
        inscribed: InscribedOut {
            f_semi_axis: inscribed.x_semi_axis.to_f64(),
            m_over_pitch_semi_axis: inscribed.y_semi_axis.to_f64(),
            force_over_exact_max_pct: 100.0 * over_max.to_f64(),
            force_over_exact_mean_pct: 100.0 * over_mean.to_f64(),
        },
        samples,
    };
    let mut out = std::io::stdout().lock();
    let written = match args.format {
        Format::Json => serde_json::to_writer_pretty(&mut out, &report)
            .map_err(std::io::Error::other)
            .and_then(|()| writeln!(out)),
        Format::Csv => write_csv(&mut out, &report),
        Format::Table => write_table(&mut out, &report),
    };
    written.map_err(|e| CliError::Failed(format!("writing the output: {e}")))
}

fn write_csv(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    writeln!(out, "d_over_a,f_over_mu_n,m_over_mu_n_a")?;
    for s in &r.samples {
        writeln!(out, "{:e},{:e},{:e}", s.d, s.f, s.m)?;
    }
    Ok(())
}

fn write_table(out: &mut impl Write, r: &Report) -> std::io::Result<()> {
    let aspect = r.aspect.map_or(String::new(), |a| format!(", l/a = {a}"));
    let skew = if r.skew > 0.0 {
        format!(
            ", skew Δ/a = {}, α = {}, locus h/a = {}",
            r.skew,
            r.alpha,
            r.locus.unwrap_or(0.0)
        )
    } else {
        ", no skew".to_string()
    };
    writeln!(
        out,
        "# friction limit surface: {} patch, k = {}{aspect}{skew} ({}, order {})",
        r.shape, r.k, r.precision, r.order
    )?;
    writeln!(out, "# pitch m̃(0) (Eq. 22)           {:.10}", r.pitch)?;
    writeln!(
        out,
        "# least-squares ellipse         f̃ semi-axis {:.6}, m̃ semi-axis {:.6} (rms residual {:.2e})",
        r.ellipse.f_semi_axis, r.ellipse.m_semi_axis, r.ellipse.rms_residual
    )?;
    writeln!(
        out,
        "# largest gap to Eq. 10 ellipse {:.6} ({:.3} % of its radius) at d_c/a = {:.4}",
        r.ellipse.max_radial_gap,
        100.0 * r.ellipse.max_relative_gap,
        r.ellipse.max_gap_at.d
    )?;
    writeln!(
        out,
        "# inscribed ellipse (ellipse mode): semi-axes {:.6} (f), {:.6} (m/pitch); force over \
         the exact surface: max {:.2} %, mean {:.2} %",
        r.inscribed.f_semi_axis,
        r.inscribed.m_over_pitch_semi_axis,
        r.inscribed.force_over_exact_max_pct,
        r.inscribed.force_over_exact_mean_pct
    )?;
    if !r.star_shaped {
        writeln!(
            out,
            "# the swept curve is not star-shaped: a ray from the origin meets it twice"
        )?;
    }
    if r.ellipse.max_outside > 0.0 {
        writeln!(
            out,
            "# the surface leaves the ellipse by up to {:.6} (strong skew)",
            r.ellipse.max_outside
        )?;
    }
    writeln!(
        out,
        "{:>16} {:>16} {:>16}",
        "d_c/a [1]", "|f_t|/(μN) [1]", "|m_n|/(μNa) [1]"
    )?;
    for s in &r.samples {
        writeln!(out, "{:>16.6e} {:>16.12} {:>16.12}", s.d, s.f, s.m)?;
    }
    Ok(())
}
