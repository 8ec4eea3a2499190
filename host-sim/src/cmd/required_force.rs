//! `host-sim required-force`: docs/model.md's slip-prevention rule for one load, computed by
//! the controller's own start-up grid and solver.

use crate::accuracy::exact::{ExactSurface, Finger, Rule};
use crate::args::{PatchArgs, Precision};
use crate::input::{config_error, short_num};
use crate::CliError;
use clap::{Args, ValueEnum};
use serde::Serialize;
use softgrip::contact::ContactSize;
use softgrip::controller::{
    Controller, ControllerConfig, Libm, Micromath, Mode, SkewParams, Status, TickMath,
};
use softgrip::{ConfigError, Real};

/// How the rule tests the load.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ModeArg {
    /// The Eq. 10 ellipse with the exact pitch at l/a(N).
    Ellipse,
    /// The exact limit surface, tabulated.
    Table,
}

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
    /// Friction coefficient μ > 0.
    #[arg(long, required_unless_present = "finger")]
    mu: Option<f64>,
    /// Contact-size coefficient c in a = c·N^γ [m/N^γ].
    #[arg(long, required_unless_present = "finger")]
    c: Option<f64>,
    /// Contact-size exponent γ in [0, 1/2].
    #[arg(long, required_unless_present = "finger")]
    gamma: Option<f64>,
    /// Shape, pressure exponent, skew (only table mode sees the skew).
    #[command(flatten)]
    patch: PatchArgs,
    /// Half-length l of the rectangular patch [m] (ignored for the disc).
    #[arg(long, default_value_t = 0.01)]
    length: f64,
    /// Safety factor s >= 1.
    #[arg(long, default_value_t = 1.3)]
    safety: f64,
    /// Ellipse or table (only table mode sees --skew).
    #[arg(long, value_enum, default_value_t = ModeArg::Ellipse)]
    mode: ModeArg,
    /// Lower end of the controller's force grid [N]; answers below it are closed-form
    /// bounds.
    #[arg(long, default_value_t = 0.2)]
    n_min: f64,
    /// Upper end of the force grid [N]: a larger answer is reported as saturated.
    #[arg(long, default_value_t = 20.0)]
    n_max: f64,
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

/// The arguments with the finger resolved: from `--finger`'s file or from the flags.
#[derive(Debug)]
struct Resolved<'a> {
    ft: f64,
    mn: f64,
    mu: f64,
    c: f64,
    gamma: f64,
    patch: PatchArgs,
    length: f64,
    safety: f64,
    mode: ModeArg,
    n_min: f64,
    n_max: f64,
    precision: Precision,
    math: MathArg,
    /// The file the finger came from, for errors.
    finger: Option<&'a std::path::Path>,
}

impl RequiredForceArgs {
    fn resolve(&self) -> Result<Resolved<'_>, CliError> {
        let base = |mu, c, gamma, patch, length| Resolved {
            ft: self.ft,
            mn: self.mn,
            mu,
            c,
            gamma,
            patch,
            length,
            safety: self.safety,
            mode: self.mode,
            n_min: self.n_min,
            n_max: self.n_max,
            precision: self.precision,
            math: self.math,
            finger: self.finger.as_deref(),
        };
        let Some(path) = &self.finger else {
            // clap requires the three flags without --finger.
            let missing = |name: &str| CliError::Usage(format!("--{name} is required"));
            return Ok(base(
                self.mu.ok_or_else(|| missing("mu"))?,
                self.c.ok_or_else(|| missing("c"))?,
                self.gamma.ok_or_else(|| missing("gamma"))?,
                self.patch,
                self.length,
            ));
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
        let patch = PatchArgs {
            shape: g.shape,
            k: g.k,
            ..self.patch
        };
        Ok(base(f.believed_mu(), g.c, g.gamma, patch, g.half_length_m))
    }
}

/// The answer, as `--format json` prints it.
#[derive(Debug, Serialize)]
pub struct RequiredForce {
    /// `N_req(s)` [N].
    pub normal_force: f64,
    /// `N_slip = N_req(1)` [N].
    pub n_slip: f64,
    /// Contact half-width at `normal_force` [m].
    pub a: f64,
    /// Utilisation of the (unscaled) load at `command`: `1/s` unless the grid clamps.
    pub utilisation: f64,
    /// `ok`, or `saturated` when `normal_force > n_max`.
    pub status: &'static str,
    /// What a controller with this grid would command: `normal_force` clamped into
    /// `[n_min, n_max]` [N].
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
    /// root search in `ln N` in f64 with the surface integrated at every trial force [N].
    pub exact_force: f64,
    /// `normal_force / exact_force − 1`: what this mode asks over the exact surface
    /// (never negative beyond rounding: the controller is conservative by construction).
    pub over_exact: f64,
}

/// The command-line flag of a configuration field.
fn flag(param: &str) -> &str {
    match param {
        "c_m_per_n_gamma" => "c",
        "half_length_m" => "length",
        "n_min_n" | "fault_force_n" => "n-min",
        "n_max_n" => "n-max",
        "force_range_n" => "ft",
        "moment_range_nm" => "mn",
        other => other,
    }
}

fn usage(e: ConfigError) -> CliError {
    CliError::Usage(config_error(flag(e.param()), &e))
}

/// Whether the controller of `cfg` builds in the precision of `args`.
fn builds(args: &Resolved, cfg: ControllerConfig) -> bool {
    match args.precision {
        Precision::F64 => Controller::<f64, Libm>::new_precomputed_in::<f64>(cfg).is_ok(),
        Precision::F32 => Controller::<f32, Libm>::new_precomputed_in::<f64>(cfg).is_ok(),
    }
}

/// A configuration error as the user should read it: naming the flags they typed.
///
/// - The core's `aspect` (`l/a`, derived from `--length` and the contact size) is
///   reported on `--length`.
/// - `locus` when `--locus` was not given (it defaults to `--skew`/2) is reported on
///   `--skew`.
/// - The sensor-range overflow (`force_range_n`, `moment_range_nm`: the worst load the
///   derived sensor range admits, times `safety/μ`, overflows the tick) is put on the
///   flag that causes it, found by retrying with that flag at an ordinary value:
///   `--mu`/`--safety` (their ratio), else `--length`, else `--ft`/`--mn`.
fn explain(args: &Resolved, cfg: ControllerConfig, e: ConfigError) -> CliError {
    let reason = config_error("", &e);
    let reason = reason.split_once(": ").map_or(reason.as_str(), |(_, r)| r);
    match e.param() {
        "aspect" => CliError::Usage(format!(
            "--length: {} m gives a contact aspect l/a whose limit surface cannot be \
             computed (l/a {reason})",
            short_num(args.length)
        )),
        "locus" if args.patch.locus.is_none() => CliError::Usage(format!(
            "--skew: {} with the default --locus (skew/2 = {}): {reason}",
            short_num(args.patch.skew),
            short_num(args.patch.skew / 2.0)
        )),
        "force_range_n" | "moment_range_nm" => {
            let overflow = "the worst load the sensor range admits, times safety/mu, \
                            overflows the tick's precision";
            let plain = ControllerConfig {
                mu: 1.0,
                safety: 1.0,
                ..cfg
            };
            if builds(args, plain) {
                // The more extreme of the two first.
                let (mu, safety) = (
                    format!("--mu {}", short_num(args.mu)),
                    format!("--safety {}", short_num(args.safety)),
                );
                let (first, second) = if args.safety.ln().abs() > args.mu.ln().abs() {
                    (safety, mu)
                } else {
                    (mu, safety)
                };
                return CliError::Usage(format!(
                    "{first} with {second}: safety/mu = {}: {overflow}",
                    short_num(args.safety / args.mu)
                ));
            }
            let plain = ControllerConfig {
                half_length_m: 0.01,
                ..cfg
            };
            if builds(args, plain) {
                return CliError::Usage(format!(
                    "--length: {} m: {overflow}",
                    short_num(args.length)
                ));
            }
            let name = if cfg.force_range_n > 100.0 {
                format!("--ft {}", short_num(args.ft))
            } else if cfg.moment_range_nm > 2.0 {
                format!("--mn {}", short_num(args.mn))
            } else {
                format!(
                    "--ft {} with --mn {}",
                    short_num(args.ft),
                    short_num(args.mn)
                )
            };
            CliError::Usage(format!("{name}: {overflow}"))
        }
        _ => usage(e),
    }
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

/// The controller configuration the arguments describe.
fn config(args: &Resolved) -> Result<ControllerConfig, CliError> {
    let ft = finite("ft", args.ft)?;
    let mn = finite("mn", args.mn)?;
    let skew = if args.patch.skew == 0.0 {
        None
    } else {
        Some(SkewParams {
            delta_over_a: args.patch.skew,
            alpha: args.patch.alpha,
            locus_over_a: args.patch.locus.unwrap_or(args.patch.skew / 2.0),
        })
    };
    Ok(ControllerConfig {
        mu: args.mu,
        shape: args.patch.shape,
        k: args.patch.k,
        skew,
        c_m_per_n_gamma: args.c,
        gamma: args.gamma,
        half_length_m: args.length,
        safety: args.safety,
        n_min_n: args.n_min,
        n_max_n: args.n_max,
        fault_force_n: args.n_min,
        // The sensor must be able to read the load.
        force_range_n: (2.0 * ft).max(100.0),
        moment_range_nm: (2.0 * mn).max(2.0),
        mode: match args.mode {
            ModeArg::Ellipse => Mode::Ellipse,
            ModeArg::Table => Mode::Table,
        },
        force_nodes: 64,
        ..ControllerConfig::default()
    })
}

fn compute<T: Real, M: TickMath<T>>(
    cfg: ControllerConfig,
    ft: f64,
    mn: f64,
) -> Result<RequiredForce, CliError> {
    let ctl = Controller::<T, M>::new_precomputed_in::<f64>(cfg).map_err(usage)?;
    let (f, m) = (T::of(ft), T::of(mn));
    let fail = || CliError::Failed("the solver returned no answer".into());
    let req = ctl
        .required_force(f, m, T::of(cfg.safety))
        .ok_or_else(fail)?
        .force_n;
    let slip = ctl.required_force(f, m, T::one()).ok_or_else(fail)?.force_n;
    let command = req.max(T::of(cfg.n_min_n)).min(T::of(cfg.n_max_n));
    let utilisation = ctl.utilisation(f, m, command).ok_or_else(fail)?;
    let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma).map_err(usage)?;
    let n = req.to_f64();
    let status = if n > cfg.n_max_n {
        Status::Saturated
    } else {
        Status::Ok
    };
    Ok(RequiredForce {
        normal_force: n,
        n_slip: slip.to_f64(),
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
    Ok(surface
        .required_in(Rule::Exact, ft * s, mn * s, 1e-12, 1e12)
        .0)
}

/// Computes the answer for the arguments.
pub fn required_force(args: &RequiredForceArgs) -> Result<RequiredForce, CliError> {
    let args = &args.resolve()?;
    let cfg = config(args)?;
    if let Err(e) = cfg.validate() {
        return Err(match args.finger {
            // A value from the file: named by its key there.
            Some(path)
                if matches!(e.param(), "mu" | "c_m_per_n_gamma" | "gamma" | "k")
                    || e.param() == "half_length_m" =>
            {
                let reason = config_error("", &e);
                let reason = reason.split_once(": ").map_or(reason.as_str(), |(_, r)| r);
                let key = crate::sim::run::scene_key(
                    e.param(),
                    &crate::sim::scene::ControllerSettings::default(),
                );
                CliError::Usage(format!("--finger: {}: {key}: {reason}", path.display()))
            }
            _ => explain(args, cfg, e),
        });
    }
    // The grid's own checks (its precision, the sensor range), named for the user; the
    // controller is built again below in the precision and math asked for.
    let built = match args.precision {
        Precision::F64 => Controller::<f64, Libm>::new_precomputed_in::<f64>(cfg).err(),
        Precision::F32 => Controller::<f32, Libm>::new_precomputed_in::<f64>(cfg).err(),
    };
    if let Some(e) = built {
        return Err(explain(args, cfg, e));
    }
    let (ft, mn) = (args.ft.abs(), args.mn.abs());
    let mut r = match (args.precision, args.math) {
        (Precision::F64, MathArg::Libm) => compute::<f64, Libm>(cfg, ft, mn),
        (Precision::F32, MathArg::Libm) => compute::<f32, Libm>(cfg, ft, mn),
        (Precision::F32, MathArg::Micromath) => compute::<f32, Micromath>(cfg, ft, mn),
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
                r.normal_force, args.safety
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
