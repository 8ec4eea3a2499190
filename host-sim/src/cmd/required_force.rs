//! `host-sim required-force`: docs/model.md's slip-prevention rule for one load, computed by
//! the controller's own start-up grid and solver.

use crate::args::Precision;
use crate::config::names::{flag, scene_key};
use crate::config::ConfigArgs;
use crate::exact::{ExactSurface, Finger, Rule};
use crate::input::{config_reason, short_num};
use crate::CliError;
use clap::{Args, ValueEnum};
use serde::Serialize;
use softgrip::contact::ContactSize;
use softgrip::controller::{
    Checked, Controller, ControllerConfig, Libm, Micromath, SkewParams, Status, TickMath,
};
use softgrip::{BuildError, ConfigError, RangeOverflow, Real};

/// Output format of `required-force`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum OutFormat {
    /// Aligned lines for people.
    Table,
    /// One JSON object.
    Json,
}

/// Math backend of the solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MathArg {
    /// libm's correctly rounded sqrt.
    Libm,
    /// micromath's approximate sqrt (f32 only).
    Micromath,
}

/// Arguments of `host-sim required-force`.
#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct RequiredForceArgs {
    /// Tangential force |f_t| [N] (the sign is ignored).
    #[arg(long)]
    ft: f64,
    /// Torsional moment |m_n| [N·m] (the sign is ignored).
    #[arg(long)]
    mn: f64,
    /// A finger file (`host-sim calibrate --out`'s, or a scene): its shape, k, mu (a
    /// scene's [controller] mu if set), c, gamma and half_length_m, in place of the
    /// flags --shape, --k, --mu, --c, --gamma and --length.
    #[arg(long, conflicts_with_all = ["mu", "c", "gamma", "length", "shape", "k"])]
    finger: Option<std::path::PathBuf>,
    /// Largest skew of the pressure peak, Δ/a in [0, 1); 0 is the symmetric profile (only
    /// table mode sees it).
    #[arg(long, default_value_t = 0.0)]
    skew: f64,
    /// Rate α of the skew law Δy = Δ·tanh(α d_c/a).
    #[arg(long, default_value_t = 1.1)]
    alpha: f64,
    /// Half-axis h/a of the peak's locus (Eq. 16); default Δ/2, the paper's circular path.
    #[arg(long)]
    locus: Option<f64>,
    /// The configuration (`--config FILE`, one flag per field: --mu, --c, --gamma,
    /// --length, --safety, --shape, --k, --mode, --n-min, --n-max, ...) over the rule's
    /// defaults (ControllerConfig's, with 64 force nodes). The fault force and sensor
    /// ranges are derived: --n-min, and twice the load.
    #[command(flatten)]
    config: ConfigArgs,
    /// Arithmetic of the grid and the solver.
    #[arg(long, value_enum, default_value_t = Precision::F64)]
    precision: Precision,
    /// Square root of the tick.
    #[arg(long, value_enum, default_value_t = MathArg::Libm)]
    math: MathArg,
    /// Output format.
    #[arg(long, value_enum, default_value_t = OutFormat::Table)]
    format: OutFormat,
}

/// The fields a finger file gives.
const FINGER_FIELDS: [&str; 6] = [
    "mu",
    "shape",
    "k",
    "c_m_per_n_gamma",
    "gamma",
    "half_length_m",
];

impl RequiredForceArgs {
    /// The rule's base configuration: its defaults, the finger file's finger if given, and
    /// the skew flags.
    fn base(&self) -> Result<ControllerConfig, CliError> {
        let skew = (self.skew != 0.0).then(|| SkewParams {
            delta_over_a: self.skew,
            alpha: self.alpha,
            locus_over_a: self.locus.unwrap_or(self.skew / 2.0),
        });
        let base = ControllerConfig {
            skew,
            ..ControllerConfig::rule_base()
        };
        let Some(path) = &self.finger else {
            return Ok(base);
        };
        let f = crate::finger_file::FingerFile::load(path, "--finger")?;
        let g = &f.finger;
        if !(g.c.is_finite() && g.gamma.is_finite()) {
            return Err(CliError::Usage(format!(
                "--finger: {}: [finger] needs c and gamma (the contact law softgrip \
                 believes)",
                path.display()
            )));
        }
        let cfg = ControllerConfig {
            mu: f.believed_mu(),
            shape: g.shape,
            k: g.k,
            c_m_per_n_gamma: g.c,
            gamma: g.gamma,
            half_length_m: g.half_length_m,
            ..base
        };
        // The finger's measured margins (its disc_torsion_factor acts here).
        crate::config::overlay(&cfg, &f.margins)
            .map_err(|e| CliError::Usage(format!("--finger: {}: margins.{e}", path.display())))
    }
}

/// The answer, as `--format json` prints it.
#[derive(Debug, Serialize)]
pub struct RequiredForce {
    /// `N_req(s)` as the tick asks it of this steady load (a round patch's moment carries
    /// `DISC_TORSION_SAFETY_FACTOR` on top of `s`) \[N\].
    pub normal_force: f64,
    /// `N_slip`, the force at which the contact starts to slip (`N_req(1)` on a
    /// hemicylinder) \[N\].
    pub n_slip: f64,
    /// The safety factor `s` of `normal_force` (the table output prints it; not in the
    /// JSON, whose fields are the answer's).
    #[serde(skip)]
    pub safety: f64,
    /// Contact half-width at `normal_force` \[m\].
    pub a: f64,
    /// Utilisation of the (unscaled) load at `command`: `1/s` on a hemicylinder unless the
    /// grid clamps (less on a round patch under a moment).
    pub utilisation: f64,
    /// `ok`, or `saturated` when `normal_force > n_max`.
    pub status: &'static str,
    /// What a controller with this grid would command: `normal_force` clamped into
    /// `[n_min, n_max]` \[N\].
    pub command: f64,
    /// `ellipse` or `table`.
    pub mode: &'static str,
    /// `f64` or `f32`.
    pub precision: &'static str,
    /// `libm` or `micromath`.
    pub math: &'static str,
    /// The semi-axes `(A, B)` of the ellipse the mode tests against, in `(f̃, m̃/pitch)`:
    /// ellipse mode's inscribed ellipse (`(1, 1)` would be Eq. 10's); `(1, 1)` in table mode,
    /// which applies none.
    pub ellipse_axes: [f64; 2],
    /// `N_req(s)` on the exact limit surface (docs/model.md's table reading), with no grid: a
    /// root search in `ln N` in f64 with the surface integrated at every trial force \[N\].
    pub exact_force: f64,
    /// `normal_force / exact_force − 1`: what this mode asks over the exact surface
    /// (never negative beyond rounding: the controller is conservative by construction).
    pub over_exact: f64,
}

/// A configuration error as the user should read it: naming the flag they typed (through
/// the rename table; the derived fault force and sensor ranges on `--n-min`, `--ft`,
/// `--mn`), or the finger file's key for a value from it.
///
/// - The core's `aspect` (`l/a`, derived from `--length` and the contact size) is
///   reported on `--length`.
/// - `locus` when `--locus` was not given (it defaults to `--skew`/2) is reported on
///   `--skew`.
fn explain(args: &RequiredForceArgs, cfg: &ControllerConfig, e: ConfigError) -> CliError {
    let reason = config_reason(&e);
    let field = e.field();
    match (e.param(), &args.finger) {
        ("aspect", _) => CliError::Usage(format!(
            "--length: {} m gives a contact aspect l/a whose limit surface cannot be \
             computed (l/a {reason})",
            short_num(cfg.half_length_m)
        )),
        ("locus", _) if args.locus.is_none() => CliError::Usage(format!(
            "--skew: {} with the default --locus (skew/2 = {}): {reason}",
            short_num(args.skew),
            short_num(args.skew / 2.0)
        )),
        (_, Some(path)) if FINGER_FIELDS.contains(&field) && !args.config.sets(field) => {
            CliError::Usage(format!(
                "--finger: {}: {}: {reason}",
                path.display(),
                scene_key(field, false)
            ))
        }
        ("skew" | "alpha" | "locus", _) => CliError::Usage(format!("--{}: {reason}", e.param())),
        _ => CliError::Usage(format!(
            "--{}: {reason}",
            flag(ControllerConfig::rule_input(field))
        )),
    }
}

/// A build error as the user should read it: a sensor-range overflow on the flags of the
/// factor that causes it ([`RangeOverflow`]): `--mu`/`--safety` (the more extreme first),
/// `--length`, or `--ft`/`--mn`.
fn explain_build(args: &RequiredForceArgs, cfg: &ControllerConfig, e: BuildError) -> CliError {
    let overflow = "the worst load the sensor range admits, times safety/mu, overflows the \
                    tick's precision";
    let name = match e {
        BuildError::Config(e) => return explain(args, cfg, e),
        BuildError::RangeOverflow(RangeOverflow::SafetyOverMu) => {
            let (mu, safety) = (
                format!("--mu {}", short_num(cfg.mu)),
                format!("--safety {}", short_num(cfg.safety)),
            );
            let (first, second) = if cfg.safety.ln().abs() > cfg.mu.ln().abs() {
                (safety, mu)
            } else {
                (mu, safety)
            };
            format!(
                "{first} with {second}: safety/mu = {}",
                short_num(cfg.safety / cfg.mu)
            )
        }
        BuildError::RangeOverflow(RangeOverflow::Contact) => {
            format!("--length: {} m", short_num(cfg.half_length_m))
        }
        BuildError::RangeOverflow(RangeOverflow::SensorRange) => {
            let d = ControllerConfig::default();
            if cfg.force_range_n > d.force_range_n && cfg.moment_range_nm <= d.moment_range_nm {
                format!("--ft {}", short_num(args.ft))
            } else if cfg.moment_range_nm > d.moment_range_nm
                && cfg.force_range_n <= d.force_range_n
            {
                format!("--mn {}", short_num(args.mn))
            } else {
                format!(
                    "--ft {} with --mn {}",
                    short_num(args.ft),
                    short_num(args.mn)
                )
            }
        }
    };
    CliError::Usage(format!("{name}: {overflow}"))
}

fn finite(name: &str, v: f64) -> Result<f64, CliError> {
    if v.is_finite() {
        Ok(v.abs())
    } else {
        Err(CliError::Usage(format!(
            "--{name}: must be a finite number"
        )))
    }
}

/// The controller configuration the arguments describe, checked: the rule's (the core's
/// [`ControllerConfig::for_loads`], shared with the Python package).
fn config(args: &RequiredForceArgs) -> Result<Checked, CliError> {
    let ft = finite("ft", args.ft)?;
    let mn = finite("mn", args.mn)?;
    let cfg = args.config.apply(&args.base()?)?.for_loads(ft, mn);
    cfg.check().map_err(|e| explain(args, &cfg, e))
}

fn compute<T: Real, M: TickMath<T>>(
    args: &RequiredForceArgs,
    cfg: &Checked,
    ft: f64,
    mn: f64,
) -> Result<RequiredForce, CliError> {
    let ctl =
        Controller::<T, M>::from_checked_in::<f64>(cfg).map_err(|e| explain_build(args, cfg, e))?;
    let (f, m) = (T::of(ft), T::of(mn));
    let fail = || CliError::Failed("the solver returned no answer".into());
    let req = ctl
        .tick_required_force(f, m, T::of(cfg.safety))
        .ok_or_else(fail)?
        .force_n;
    let slip = ctl.slip_force(f, m).ok_or_else(fail)?.force_n;
    let command = req.max(T::of(cfg.n_min_n)).min(T::of(cfg.n_max_n));
    let utilisation = ctl.utilisation(f, m, command).ok_or_else(fail)?;
    let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma)
        .map_err(|e| explain(args, cfg, e))?;
    let n = req.to_f64();
    let status = if n > cfg.n_max_n {
        Status::Saturated
    } else {
        Status::Ok
    };
    Ok(RequiredForce {
        normal_force: n,
        n_slip: slip.to_f64(),
        safety: cfg.safety,
        a: contact.half_width_m(n),
        utilisation: utilisation.to_f64(),
        status: status.name(),
        command: command.to_f64(),
        mode: cfg.mode.name(),
        precision: if T::SINGLE { "f32" } else { "f64" },
        math: M::NAME,
        ellipse_axes: {
            let [sf, sm] = ctl.capacity().demand_scale();
            [1.0 / sf.to_f64(), 1.0 / sm.to_f64()]
        },
        exact_force: f64::NAN,
        over_exact: f64::NAN,
    })
}

/// `N_req(s)` of the load on the exact surface of `cfg`'s finger (see
/// [`RequiredForce::exact_force`]).
fn exact_force(cfg: &ControllerConfig, ft: f64, mn: f64) -> Result<f64, CliError> {
    let finger = Finger::new(*cfg).map_err(CliError::Failed)?;
    let surface = ExactSurface::new(finger, usize::from(cfg.quadrature_order), 1e-13, 1e-12)
        .map_err(CliError::Failed)?;
    let s = cfg.safety / cfg.mu;
    let torsion = cfg.torsion_factor();
    Ok(surface
        .required_in(Rule::Exact, ft * s, mn * s * torsion, 1e-12, 1e12)
        .0)
}

/// Computes the answer for the arguments.
pub fn required_force(args: &RequiredForceArgs) -> Result<RequiredForce, CliError> {
    let cfg = config(args)?;
    let (ft, mn) = (args.ft.abs(), args.mn.abs());
    let mut r = match (args.precision, args.math) {
        (Precision::F64, MathArg::Libm) => compute::<f64, Libm>(args, &cfg, ft, mn),
        (Precision::F32, MathArg::Libm) => compute::<f32, Libm>(args, &cfg, ft, mn),
        (Precision::F32, MathArg::Micromath) => compute::<f32, Micromath>(args, &cfg, ft, mn),
        (Precision::F64, MathArg::Micromath) => Err(CliError::Usage(
            "--math: micromath is f32 only (add --precision f32)".into(),
        )),
    }?;
    r.exact_force = exact_force(&cfg, ft, mn)?;
    r.over_exact = if r.exact_force > 0.0 {
        r.normal_force / r.exact_force - 1.0
    } else {
        0.0
    };
    Ok(r)
}

/// Runs `host-sim required-force`.
pub fn run(args: &RequiredForceArgs) -> Result<(), CliError> {
    let r = required_force(args)?;
    match args.format {
        OutFormat::Json => {
            let text =
                serde_json::to_string_pretty(&r).map_err(|e| CliError::Failed(e.to_string()))?;
            println!("{text}");
        }
        OutFormat::Table => {
            println!(
                "normal_force  {:>14.6e} N   N_req(s), s = {}",
                r.normal_force, r.safety
            );
            println!("n_slip        {:>14.6e} N", r.n_slip);
            println!(
                "exact_force   {:>14.6e} N   N_req(s) on the exact surface ({:+.3} % over it)",
                r.exact_force,
                100.0 * r.over_exact
            );
            println!(
                "a             {:>14.6e} m   contact half-width at normal_force",
                r.a
            );
            println!(
                "utilisation   {:>14.6}     of the load at the command",
                r.utilisation
            );
            println!("status        {:>14}", r.status);
            println!(
                "command       {:>14.6e} N   clamped to [n_min, n_max]",
                r.command
            );
            println!(
                "mode          {:>14}     {} {}",
                r.mode, r.precision, r.math
            );
        }
    }
    Ok(())
}
