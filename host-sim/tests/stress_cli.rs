//! Hostile and extreme input at the command line and in scene files.
//!
//! - `fls` and `required-force` at the corners of the domain (the hard cases of
//!   `tests/stress.rs`): every run gives finite numbers (checked field by field in the JSON,
//!   where a NaN or an infinity would print as `null`) and, where a reference exists, the
//!   right ones; or it exits with code 2 and a first line naming the argument (clap's
//!   hints follow a value clap itself refuses). `fls_cli.rs` and
//!   `required_force_cli.rs` hold the basic cases; these are the ones they do not.
//! - The scene parser (`Scene::parse`, then everything `simulate` builds from a scene before
//!   it touches the link: the effect pipeline, the controller configuration, the ground
//!   truth) on thousands of mutated scene files and on random text: never a panic; every
//!   error is one line.

mod common;

use host_sim::sim::run::controller_config;
use host_sim::sim::scene::Scene;
use host_sim::sim::truth::Truth;

/// The default safety factor, which these runs take.
const SAFETY: f64 = softgrip::controller::ControllerConfig::DEFAULT.safety;

fn run(cmd: &str, args: &[&str]) -> (i32, String, String) {
    common::host_sim(&[&[cmd], args].concat())
}

/// A finite number at `v[key]`, or a failure naming the case.
fn finite(v: &serde_json::Value, key: &str, case: &str) -> f64 {
    let x = v[key].as_f64();
    assert!(
        x.is_some_and(f64::is_finite),
        "{case}: {key} = {} (null is how serde_json prints NaN and ±∞)",
        v[key]
    );
    x.unwrap()
}

/// Runs `fls --format json` and checks every number in the output is finite and
/// `f̃ ≤ 1 + 2e-6` (f32's documented accuracy); returns `None` for exit code 2 (after
/// checking the one-line reason), the JSON otherwise.
fn fls(args: &[&str]) -> Option<serde_json::Value> {
    fls_within(args, 2e-6)
}

/// A refusal with code 2: a first line `error: ...` (clap's hints may follow it), no panic.
fn assert_usage_error(err: &str, case: &str) {
    assert!(err.starts_with("error: "), "{case}: {err}");
    assert!(!err.contains("panicked"), "{case}: {err}");
}

/// [`fls`] with `f̃ ≤ 1 + f_excess` (a low `--order` is less accurate).
fn fls_within(args: &[&str], f_excess: f64) -> Option<serde_json::Value> {
    let mut all = args.to_vec();
    all.extend(["--format", "json"]);
    let case = args.join(" ");
    let (code, out, err) = run("fls", &all);
    if code == 2 {
        assert!(out.is_empty(), "{case}");
        assert_usage_error(&err, &case);
        return None;
    }
    assert_eq!(code, 0, "{case}: exit {code}: {err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let pitch = finite(&v, "pitch", &case);
    assert!(pitch > 0.0, "{case}");
    let e = &v["ellipse"];
    for key in [
        "f_semi_axis",
        "m_semi_axis",
        "rms_residual",
        "max_radial_gap",
        "max_relative_gap",
        "max_outside",
    ] {
        finite(e, key, &case);
    }
    for key in ["d", "f", "m"] {
        finite(&e["max_gap_at"], key, &case);
    }
    let samples = v["samples"].as_array().unwrap();
    assert!(!samples.is_empty(), "{case}");
    for s in samples {
        let (f, m) = (finite(s, "f", &case), finite(s, "m", &case));
        finite(s, "d", &case);
        // f̃ ≤ 1 up to the documented accuracy (2e-6 in f32).
        assert!(
            (0.0..=1.0 + f_excess).contains(&f) && m >= 0.0,
            "{case}: {s}"
        );
    }
    Some(v)
}

fn samples(v: &serde_json::Value) -> Vec<(f64, f64, f64)> {
    v["samples"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            (
                s["d"].as_f64().unwrap(),
                s["f"].as_f64().unwrap(),
                s["m"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// The corners of `fls`'s domain, each crossed with f32, the disc, a skew and the hard
/// centres of rotation: all finite, with the closed forms where they exist.
#[test]
fn fls_at_the_corners_of_the_domain_gives_finite_answers() {
    // The disc's closed-form pitch at k = 1 and uniform (docs/model.md: 2/3), and the edge and
    // far-field points of the extreme aspects.
    // k = 1: B(3, 2)/B(2, 2) = (1/12)/(1/6) = 1/2.
    let v = fls(&["--shape", "disc", "--k", "1", "--at", "0,1,1e12"]).unwrap();
    assert!((v["pitch"].as_f64().unwrap() - 0.5).abs() < 1e-10);
    let s = samples(&v);
    assert!(
        (s[2].1 - 1.0).abs() <= 1e-15,
        "f̃(1e12) is 1 to an ulp: {s:?}"
    );
    let v = fls(&["--shape", "disc", "--k", "inf"]).unwrap();
    assert!((v["pitch"].as_f64().unwrap() - 2.0 / 3.0).abs() < 1e-10);

    for precision in ["f64", "f32"] {
        let tol = if precision == "f64" { 1e-9 } else { 2e-6 };
        for (aspect, edge) in [("1e-3", "1e-3"), ("1", "1"), ("1e3", "1e3")] {
            for k in ["1", "1.000001", "2", "1e6", "inf"] {
                for skew in ["0", "0.999999"] {
                    let args = [
                        "--aspect",
                        aspect,
                        "--k",
                        k,
                        "--skew",
                        skew,
                        "--precision",
                        precision,
                        "--samples",
                        "16",
                    ];
                    fls(&args).unwrap();
                    let mut at = args.to_vec();
                    let points = format!("0,1e-12,{edge},1e12");
                    at.extend(["--at", &points]);
                    let v = fls(&at).unwrap();
                    let s = samples(&v);
                    let pitch = v["pitch"].as_f64().unwrap();
                    assert_eq!(s[0].1, 0.0, "{at:?}");
                    assert!((s[0].2 - pitch).abs() <= tol * pitch, "{at:?}");
                    assert!((s[1].2 - pitch).abs() <= tol * pitch, "{at:?}: {s:?}");
                    assert!(s[2].1 > 0.0 && s[2].1 < 1.0, "{at:?}: {s:?}");
                    assert!(
                        (s[3].1 - 1.0).abs() <= tol && s[3].2 < 1e-9,
                        "{at:?}: {s:?}"
                    );
                }
            }
        }
        // The disc at its edge, skewed along y (locus 0) and along the paper's circular
        // path, at the largest skew.
        for locus in ["0", "0.4999995"] {
            fls(&[
                "--shape",
                "disc",
                "--skew",
                "0.999999",
                "--locus",
                locus,
                "--precision",
                precision,
                "--samples",
                "8",
                "--at",
                "0,1e-12,1,1e12",
            ])
            .unwrap();
        }
    }
}

/// Numbers at the edge of what a float holds: accepted and finite, or refused with code 2.
#[test]
fn fls_at_the_limits_of_the_floats() {
    for args in [
        vec!["--k", "1e300"],
        vec!["--k", "1.0000000000000002"],
        vec!["--skew", "5e-324"],
        vec!["--skew", "1e-300", "--at", "1e-300,1,1e300"],
        vec![
            "--skew",
            "0.9",
            "--at",
            "0,5e-324,1e-300,1.7976931348623157e308",
        ],
        vec!["--skew", "0.5", "--alpha", "1e-300"],
        vec!["--skew", "0.5", "--alpha", "1e300"],
        vec!["--skew", "0.5", "--locus", "1e300"],
        vec!["--aspect", "1e-300"],
        vec!["--aspect", "1e76"],
        vec!["--precision", "f32", "--aspect", "1e9"],
        vec!["--precision", "f32", "--aspect", "1e-30"],
        vec![
            "--precision",
            "f32",
            "--skew",
            "1e-45",
            "--at",
            "1e-45,3e38",
        ],
        vec!["--precision", "f32", "--k", "1e300"],
        vec!["--order", "128", "--samples", "2"],
        vec!["--samples", "4096", "--k", "1"],
    ] {
        fls(&args);
    }
    // The lowest order is least accurate: f̃ reached 1.0022 here, which no load can; such
    // an answer is refused naming --order (order 28: within 1e-9 of the converged value, tests/fls_accuracy.rs).
    assert!(fls_within(
        &["--order", "4", "--k", "1", "--skew", "0.999999", "--alpha", "1e3"],
        5e-3,
    )
    .is_none());
    // Refused with code 2 and a first line naming the argument.
    for (args, name) in [
        (vec!["--k", "inf", "--skew", "-0.1"], "--skew"),
        (vec!["--skew", "0.5", "--alpha", "0"], "--alpha"),
        (vec!["--skew", "0.5", "--locus", "-1"], "--locus"),
        (vec!["--locus", "nan"], "--locus"),
        (vec!["--k=-inf"], "--k"),
        (vec!["--at", "nan"], "--at"),
        (vec!["--at", "inf"], "--at"),
        (vec!["--samples", "4097"], "--samples"),
        (vec!["--order", "129"], "--order"),
        (vec!["--aspect", "5e-324x"], "--aspect"),
        (
            vec!["--shape", "disc", "--skew", "0.5", "--locus", "3"],
            "--locus",
        ),
    ] {
        assert!(fls(&args).is_none(), "{args:?} accepted");
        let (_, _, err) = run("fls", &args);
        assert!(err.contains(name), "{args:?}: {err}");
    }
}

/// Found by this suite (see the report): aspect ratios whose `m̃⁴` overflows the
/// least-squares ellipse fit make `fls` exit with code 1 ("the sweep does not determine
/// an ellipse") instead of answering or exiting with code 2. Fixed; this test keeps each
/// of them answering or exiting with code 2.
#[test]
fn fls_at_unsupported_aspects_exits_2() {
    for args in [
        vec!["--aspect", "1e77"],
        vec!["--aspect", "1e200"],
        vec!["--precision", "f32", "--aspect", "1e10"],
        vec!["--precision", "f32", "--aspect", "1e-40"],
    ] {
        fls(&args);
    }
}

fn required(args: &[&str]) -> Option<serde_json::Value> {
    let mut all = args.to_vec();
    all.extend(["--format", "json"]);
    let case = args.join(" ");
    let (code, out, err) = run("required-force", &all);
    if code == 2 {
        assert!(out.is_empty(), "{case}");
        assert_usage_error(&err, &case);
        return None;
    }
    assert_eq!(code, 0, "{case}: exit {code}: {err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in ["normal_force", "n_slip", "a", "utilisation", "command"] {
        let x = finite(&v, key, &case);
        assert!(x >= 0.0, "{case}: {key} = {x}");
    }
    Some(v)
}

fn num(v: &serde_json::Value, key: &str) -> f64 {
    v[key].as_f64().unwrap()
}

/// One case of `required_force_at_the_corners_of_the_domain`'s grid.
#[derive(Debug, Clone, Copy)]
struct Corner<'a> {
    shape: &'a str,
    gamma: &'a str,
    mode: &'a str,
    precision: &'a str,
    math: &'a str,
    k: &'a str,
    ft: &'a str,
    mn: &'a str,
}

/// The loads of the grid, `(--ft, --mn)`: zero loads and loads from 1e-9 to 1e6 N.
const CORNER_LOADS: [(&str, &str); 7] = [
    ("0", "0"),
    ("1e-9", "0"),
    ("2", "0"),
    ("0", "1e-12"),
    ("1", "0.004"),
    ("3e5", "10"),
    ("0", "500"),
];

impl Corner<'_> {
    fn args(&self) -> [&str; 24] {
        [
            "--ft",
            self.ft,
            "--mn",
            self.mn,
            "--mu",
            "0.8",
            "--c",
            "2.5e-3",
            "--gamma",
            self.gamma,
            "--shape",
            self.shape,
            "--mode",
            self.mode,
            "--k",
            self.k,
            "--precision",
            self.precision,
            "--math",
            self.math,
            "--n-min",
            "1e-9",
            "--n-max",
            "1e6",
        ]
    }

    /// A round patch's moment carries its own factor β on top of s.
    fn beta(&self) -> f64 {
        if self.shape == "disc" {
            softgrip::controller::DISC_TORSION_SAFETY_FACTOR
        } else {
            1.0
        }
    }
}

/// Runs one corner and checks it (see `required_force_at_the_corners_of_the_domain`).
fn check_corner(c: &Corner) {
    let args = c.args();
    let case = args.join(" ");
    let v = required(&args).unwrap_or_else(|| panic!("{case} refused"));
    let (n, slip, cmd) = (
        num(&v, "normal_force"),
        num(&v, "n_slip"),
        num(&v, "command"),
    );
    // (N_min is 1e-9 rounded to f32 in f32.)
    let floor = if c.precision == "f64" {
        1e-9
    } else {
        1e-9 * (1.0 - 1e-7)
    };
    assert!((floor..=1e6).contains(&cmd), "{case}: {v}");
    assert_eq!(v["status"] == "saturated", n > 1e6, "{case}: {v}");
    // micromath's sqrt errs by up to 6 % either way, differently
    // for N_slip and N_req. An f32 solve stopped by its iteration
    // cap (on this grid, 5.6 times coarser than the default) returns
    // its bracket's upper end, at most 1 % high (tests/controller.rs,
    // `the_f32_iteration_cap_...`): N_req may then exceed s·N_slip
    // (by 0.27 % at `--ft 1e-9 --mn 0`, disc, ellipse, k = 1, s = 1.6).
    let (rel, rel_up) = match (c.precision, c.math) {
        ("f64", _) => (1e-12, 1e-12),
        (_, "libm") => (1e-6, 1e-2),
        _ => (0.07, 0.07),
    };
    let beta = c.beta();
    assert!(
        n >= slip * (1.0 - rel) && n <= SAFETY * beta * slip * (1.0 + rel_up),
        "{case}: {v}"
    );
    let ft: f64 = c.ft.parse().unwrap();
    let mn: f64 = c.mn.parse().unwrap();
    let ax_f = check_ellipse_axes(c, &case, &v);
    // Conservative by construction: never below the exact
    // surface's `N_req(s)` (f32 loads round by 6e-8).
    if c.math == "libm" && (ft > 0.0 || mn > 0.0) {
        let over = num(&v, "over_exact");
        assert!(over >= -1e-6, "{case}: {v}");
    }
    if mn == 0.0 && c.mode == "ellipse" && c.math == "libm" {
        check_translation(c, &case, n, ft, ax_f);
    }
    if n > 1e-9 && n < 1e6 && (ft > 0.0 || mn > 0.0) {
        check_utilisation(c, &case, &v, n, mn);
    }
}

/// The ellipse's semi-axes: `[1, 1]` in table mode (no ellipse), inscribed in the exact
/// surface in ellipse mode; returns the force semi-axis.
fn check_ellipse_axes(c: &Corner, case: &str, v: &serde_json::Value) -> f64 {
    let axes = [v["ellipse_axes"][0].as_f64(), v["ellipse_axes"][1].as_f64()];
    let [Some(ax_f), Some(ax_m)] = axes else {
        panic!("{case}: ellipse_axes: {v}");
    };
    if c.mode == "table" {
        assert_eq!((ax_f, ax_m), (1.0, 1.0), "{case}: {v}");
    } else {
        // Inscribed in the exact surface, which crosses the axes at 1.
        for ax in [ax_f, ax_m] {
            assert!(ax > 0.0 && ax <= 1.0 + 1e-6, "{case}: {v}");
        }
    }
    ax_f
}

/// A pure translation in ellipse mode with libm: `N_req = s·f_t/(μ·A)`.
fn check_translation(c: &Corner, case: &str, n: f64, ft: f64, ax_f: f64) {
    let want = SAFETY * ft / (0.8 * ax_f);
    // f32 loses accuracy below ~1e-8 N on the disc, where
    // φ = R²(N² − F²) − M² reaches f32's subnormals: up to
    // 5.6e-3 at 1.6e-9 N, always high (tests/stress.rs); and
    // an f32 solve stopped by its iteration cap is up to
    // 0.14 % high (6.7e-6 at 2 N and safety 1.75). Never low:
    // the first assertion below.
    let tol = match c.precision {
        "f64" => 1e-12,
        _ if want < 5e-9 => 1e-2,
        _ => 2e-3,
    };
    assert!(n >= want * (1.0 - 1e-6), "{case}: {n} vs {want}");
    assert!((n - want).abs() <= tol * want, "{case}: {n} vs {want}");
}

/// Inside the grid, the utilisation at the command: `1/s`, or on a round patch under a
/// moment between `1/(s·β)` and `1/s`.
fn check_utilisation(c: &Corner, case: &str, v: &serde_json::Value, n: f64, mn: f64) {
    let u = num(v, "utilisation");
    // An f32 solve stopped by its iteration cap is up to
    // 0.14 % high (above), its utilisation as much low.
    let tol = match (c.precision, c.math) {
        (_, "micromath") => 0.07,
        ("f32", _) if n < 5e-9 => 1e-2,
        ("f32", _) => 2e-3,
        _ => 1e-5,
    };
    let beta = c.beta();
    if beta == 1.0 || mn == 0.0 {
        assert!((u * SAFETY - 1.0).abs() < tol, "{case}: {v}");
    } else {
        // The command holds (s·f, s·β·m) at utilisation 1, so
        // the plain load's is within [1/(s·β), 1/s] (the gauge
        // of a surface symmetric about both axes is monotone in
        // each load's size).
        assert!(
            u * SAFETY < 1.0 + tol && u * SAFETY * beta > 1.0 - tol,
            "{case}: {v}"
        );
    }
}

/// The rule at the corners: `k` 1 to ∞, `γ` 0 and 1/2, both shapes and modes, f32 and
/// micromath, a grid from 1e-9 to 1e6 N and zero loads (`CORNER_LOADS`). Checked: finite;
/// the command inside `[N_min, N_max]`; `saturated` exactly when `N_req > N_max`;
/// `N_slip ≤ N_req ≤ s·β·N_slip` (β below); a pure translation needs `s·f_t/(μ·A)` in
/// ellipse mode whatever the contact, with `A` the force semi-axis of the ellipse
/// inscribed in the exact surface (`ellipse_axes`, at most 1; the solver's 8 ulp: 1e-12 in
/// f64, 1e-6 in f32; with libm), and table mode applies no ellipse
/// (`ellipse_axes = [1, 1]`); with libm, both modes ask at least `exact_force`, the exact
/// surface's `N_req(s)` (`over_exact ≥ −1e-6`); inside the grid the utilisation at the
/// command is `1/s` (1e-5; micromath's sqrt errs by up to 6 %, so 7 % there), and on a
/// round patch under a moment, whose moment carries `DISC_TORSION_SAFETY_FACTOR` β too,
/// between `1/(s·β)` and `1/s`, with `N_req` up to `s·β·N_slip`. The largest skew and
/// loads no force up to `N_max` holds:
/// `required_force_at_the_largest_skew_and_beyond_the_default_grid`.
#[test]
fn required_force_at_the_corners_of_the_domain() {
    let mut count = 0;
    for shape in ["rect", "disc"] {
        for gamma in ["0", "0.5"] {
            for mode in ["ellipse", "table"] {
                for (precision, math) in [("f64", "libm"), ("f32", "libm"), ("f32", "micromath")] {
                    for k in ["1", "1e6", "inf"] {
                        for (ft, mn) in CORNER_LOADS {
                            check_corner(&Corner {
                                shape,
                                gamma,
                                mode,
                                precision,
                                math,
                                k,
                                ft,
                                mn,
                            });
                            count += 1;
                        }
                    }
                }
            }
        }
    }
    assert_eq!(count, 2 * 2 * 2 * 3 * 3 * 7);
}

/// The largest skew in table mode (rectangle; the disc along y) answers `ok`, and loads
/// beyond anything the default grid can hold are `saturated` at the default `N_max`
/// (20 N).
#[test]
fn required_force_at_the_largest_skew_and_beyond_the_default_grid() {
    for extra in [
        vec!["--skew", "0.999999", "--mode", "table"],
        vec![
            "--skew", "0.999999", "--locus", "0", "--shape", "disc", "--mode", "table",
        ],
        vec!["--skew", "0.999999", "--alpha", "1e3", "--mode", "table"],
        // A vanishing skew: before the fix in src/fls/rect.rs the sweep's subnormal peak
        // gave NaN tables and a refusal naming --locus.
        vec!["--skew", "1e-300", "--mode", "table"],
    ] {
        let mut args = vec![
            "--ft", "1", "--mn", "0.004", "--mu", "0.8", "--c", "2.5e-3", "--gamma", "0.5",
        ];
        args.extend(extra);
        let v = required(&args).unwrap();
        assert_eq!(v["status"], "ok", "{args:?}");
    }
    for (ft, mn) in [("1e6", "0"), ("0", "1e6"), ("4e8", "4e8")] {
        let args = [
            "--ft", ft, "--mn", mn, "--mu", "0.8", "--c", "2.5e-3", "--gamma", "0.5",
        ];
        let v = required(&args).unwrap();
        assert_eq!(v["status"], "saturated", "{args:?}");
        assert_eq!(num(&v, "command"), 20.0);
        assert!(num(&v, "utilisation") > 1.0 && num(&v, "utilisation") <= 1e6);
    }
}

/// Bad values: code 2 and a first line naming the argument (for an extreme `--safety`,
/// `--mu` or `--length` whose worst load would overflow the tick, that argument).
#[test]
fn required_force_refuses_bad_values_with_one_line() {
    let base = [
        "--ft", "1", "--mn", "0.004", "--mu", "0.8", "--c", "2.5e-3", "--gamma", "0.5",
    ];
    for (flag, value, named) in [
        ("--n-min", "0", "--n-min"),
        ("--n-min", "-1", "--n-min"),
        ("--n-max", "0.1", "--n-max"),
        ("--n-max", "inf", "--n-max"),
        ("--length", "0", "--length"),
        ("--length", "nan", "--length"),
        ("--skew", "1", "--skew"),
        ("--skew", "-0.5", "--skew"),
        ("--c", "inf", "--c"),
        ("--c", "0", "--c"),
        ("--gamma", "-0.1", "--gamma"),
        ("--gamma", "nan", "--gamma"),
        ("--safety", "inf", "--safety"),
        ("--safety", "nan", "--safety"),
        ("--k", "0.999999", "--k"),
        ("--mn", "1e300", "--mn"),
        ("--ft", "-1e400", "--ft"),
        ("--math", "micromath", "--math"),
        ("--mode", "cone", "--mode"),
        ("--precision", "f16", "--precision"),
    ] {
        let mut args = base.to_vec();
        match args.iter().position(|a| *a == flag) {
            Some(i) => args[i + 1] = value,
            None => args.extend([flag, value]),
        }
        assert!(required(&args).is_none(), "{args:?} accepted");
        let (_, _, err) = run("required-force", &args);
        assert!(err.contains(named), "{flag} {value}: {err}");
    }
    for (flag, value, named) in [("--alpha", "0", "--alpha"), ("--locus", "-1", "--locus")] {
        let mut args = base.to_vec();
        args.extend(["--skew", "0.5", flag, value]);
        assert!(required(&args).is_none(), "{args:?} accepted");
        let (_, _, err) = run("required-force", &args);
        assert!(err.contains(named), "{flag} {value}: {err}");
    }
    // Disc with a sideways locus in table mode: not star-shaped, refused naming --locus.
    let mut args = base.to_vec();
    args.extend([
        "--shape", "disc", "--skew", "0.9", "--locus", "0.45", "--mode", "table",
    ]);
    if let Some(v) = required(&args) {
        // Whether the 48-sample sweep sees the bend depends on the skew; accepted is fine.
        assert_eq!(v["status"], "ok");
    }
    for (flag, value) in [
        ("--safety", "1e300"),
        ("--mu", "1e-300"),
        ("--length", "1e300"),
    ] {
        let mut args = base.to_vec();
        match args.iter().position(|a| *a == flag) {
            Some(i) => args[i + 1] = value,
            None => args.extend([flag, value]),
        }
        for precision in ["f64", "f32"] {
            let mut a = args.clone();
            a.extend(["--precision", precision]);
            assert!(required(&a).is_none(), "{a:?} accepted");
        }
    }
}

/// SplitMix64: reproducible randomness without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<'a>(&mut self, xs: &[&'a str]) -> &'a str {
        xs[self.below(xs.len())]
    }
}

const HOSTILE_VALUES: [&str; 24] = [
    "nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "-1",
    "1e308",
    "1.7976931348623157e308",
    "5e-324",
    "1e-300",
    "0.5",
    "1",
    "2",
    "1e9",
    "9223372036854775807",
    "-9223372036854775808",
    "\"rect\"",
    "\"disc\"",
    "\"\"",
    "true",
    "[]",
    "[\"gravity\", \"gravity\"]",
    "{}",
    "1979-05-27T07:32:00Z",
];

/// One random edit of a scene file: a value replaced by a hostile one, a line dropped or
/// duplicated, a byte changed, a table header or an effect added.
fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    if lines.is_empty() {
        return text.to_string();
    }
    let i = rng.below(lines.len());
    match rng.below(8) {
        0..=2 => {
            if let Some((k, _)) = lines[i].split_once('=') {
                lines[i] = format!("{k}= {}", rng.pick(&HOSTILE_VALUES));
            }
        }
        3 => {
            lines.remove(i);
        }
        4 => {
            let l = lines[i].clone();
            lines.insert(i, l);
        }
        5 => {
            let mut bytes = lines[i].clone().into_bytes();
            if !bytes.is_empty() {
                let j = rng.below(bytes.len());
                let pool = b" =[]\"#.\n\\x";
                bytes[j] = pool[rng.below(pool.len())];
            }
            lines[i] = String::from_utf8_lossy(&bytes).into_owned();
        }
        6 => {
            let effect = rng.pick(host_sim::sim::effects::NAMES);
            lines.push(format!("[effect.{effect}]"));
            let key = rng.pick(&[
                "drop_prob",
                "delay_ticks",
                "force_sd_n",
                "rate_hz",
                "lag_s",
                "tau_s",
                "delta_over_a",
                "alpha",
                "nan_prob",
                "unknown",
            ]);
            lines.push(format!("{key} = {}", rng.pick(&HOSTILE_VALUES)));
        }
        _ => {
            let at = rng.below(lines.len());
            lines.insert(
                at,
                format!(
                    "effects = [\"{}\"]",
                    rng.pick(&["gravity", "link_faults", "actuator", "creep", "nope"])
                ),
            );
        }
    }
    lines.join("\n")
}

/// Everything `simulate` builds from a scene before it opens the link. Returns the first
/// error's text; panics propagate (and fail the test).
fn build_all(text: &str) -> Result<(), String> {
    let scene = Scene::parse(text).map_err(|e| e.to_string())?;
    let pipeline = scene.pipeline().map_err(|e| e.to_string())?;
    let cfg = controller_config(&scene).map_err(|e| e.to_string())?;
    // The ground truth over the force range `run` uses (its own quadrature and tables).
    if scene.duration_s * scene.tick_hz < 1e6 {
        Truth::build(
            &scene,
            pipeline.true_skew(),
            cfg.n_min_n * 0.05,
            cfg.n_max_n * 1.5,
        )
        .map_err(|e| e.to_string())?;
    }
    Ok(())
}

/// Mutated scene files (the seven shipped scenes, 300 edits each, up to three edits
/// stacked) and random text: no panic anywhere in parsing and building, and every
/// error is a single line (docs/simulate.md: "one line naming the key and its line").
#[test]
fn mutated_and_random_scene_files_never_panic_and_errors_are_one_line() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut texts: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| std::fs::read_to_string(e.unwrap().path()).unwrap())
        .collect();
    texts.sort();
    assert!(texts.len() >= 7);
    let mut rng = Rng(0x5eed);
    let (mut ok, mut refused) = (0, 0);
    for base in &texts {
        build_all(base).unwrap();
        for _ in 0..300 {
            let mut text = base.clone();
            for _ in 0..1 + rng.below(3) {
                text = mutate(&text, &mut rng);
            }
            match std::panic::catch_unwind(|| build_all(&text)) {
                Ok(Ok(())) => ok += 1,
                Ok(Err(e)) => {
                    refused += 1;
                    assert!(!e.contains('\n'), "multi-line error {e:?} for\n{text}");
                    assert!(!e.is_empty());
                }
                Err(_) => panic!("panic on this scene:\n{text}"),
            }
        }
    }
    // Random printable text and random bytes (lossily decoded).
    for n in 0..2000 {
        let len = rng.below(200);
        let bytes: Vec<u8> = (0..len)
            .map(|_| {
                if n % 2 == 0 {
                    {
                        let pool = b" =[]\"#.\nabcdefk_0123456789eE+-{}";
                        pool[rng.below(pool.len())]
                    }
                } else {
                    rng.next() as u8
                }
            })
            .collect();
        let text = String::from_utf8_lossy(&bytes).into_owned();
        match std::panic::catch_unwind(|| build_all(&text)) {
            Ok(Ok(())) => ok += 1,
            Ok(Err(e)) => {
                refused += 1;
                assert!(!e.contains('\n'), "multi-line error {e:?} for {text:?}");
            }
            Err(_) => panic!("panic on {text:?}"),
        }
    }
    eprintln!("scene files: {ok} built, {refused} refused");
    assert!(ok > 100 && refused > 1000, "{ok} {refused}");
}

/// Found by this suite (see the report): `simulate` checks a scene's effect settings and
/// controller settings only once the run starts, and reports them as a run failure, exit
/// code 1, though docs/simulate.md promises code 2 for a bad scene file (the message itself is
/// the promised one line naming the key and its line). Fixed; this test keeps it so.
#[test]
fn simulate_refuses_bad_settings_with_code_2() {
    let base = "duration_s = 0.01\neffects = [\"gravity\", \"link_faults\"]\n\
                [finger]\nmu = 0.8\nc = 2.5e-3\ngamma = 0.5\n[object]\nmass_kg = 0.2\n";
    let dir = std::env::temp_dir().join(format!("softgrip-stress-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, extra, key) in [
        (
            "effect",
            "[effect.link_faults]\ndrop_prob = 2.0\n",
            "drop_prob",
        ),
        ("controller", "[controller]\nn_min_n = -1.0\n", "n_min_n"),
    ] {
        let path = dir.join(format!("{name}.toml"));
        std::fs::write(&path, format!("{base}{extra}")).unwrap();
        let out = dir.join(name);
        let (code, _, err) = run(
            "simulate",
            &[
                path.to_str().unwrap(),
                "--controller",
                "softgrip",
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(key), "{err}");
        assert_eq!(code, 2, "{name}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
