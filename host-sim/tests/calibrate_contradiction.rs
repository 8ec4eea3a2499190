//! A fit the rows contradict is not silent (docs/calibration.md, "A fit the rows
//! contradict"), and the lab files' record of the rig is the setup unless a flag says
//! otherwise:
//!
//! - a brush hemisphere's rows, calibrated as a rectangle (the default shape, the files
//!   without their record), warn and name the likely cause; as a disc they do not;
//! - rows the fit describes do not warn: 2 % noisy `fls` rows of both shapes over 20 seeds
//!   each, and the three brush fingers of `brush_calibration.rs`, noisy and noise-free
//!   (whose misfit stays under half of `MATERIAL_RMS`);
//! - a half-length 25 % too long warns, and names the half-length;
//! - the files record the shape and the half-length, a contradicting flag is refused
//!   naming both values, and the text report gives intervals to four digits.
//!
//! Prints the figures docs/calibration.md quotes:
//! `cargo test --release -p host-sim --test calibrate_contradiction -- --nocapture`.

mod common;

use host_sim::experiment::protocol::{all, DEFAULT_RATIOS_M};
use host_sim::experiment::{FingerSpec, FlsRig, Noise, Rig};
use host_sim::sim::finger::Finger;
use serde_json::Value;
use softgrip::controller::FingerShape;
use softgrip_calibrate::lack_of_fit::{LackOfFit, MATERIAL_RMS};
use softgrip_calibrate::{calibrate, calibrate_on, grid_for, Setup};
use std::path::{Path, PathBuf};

const FORCES: [f64; 5] = [0.5, 1.0, 2.0, 4.0, 8.0];

/// A brush hemisphere: μ_s 0.9, μ_k 0.8 (the reviewer's finger).
const HEMISPHERE: &str = r#"
[finger]
model = "brush"
shape = "disc"
mu = 0.9
young_modulus_pa = 5e5
[finger.brush]
radius_m = 0.009
layer_thickness_m = 0.003
mu_kinetic = 0.8
height_m = 0.003
"#;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "softgrip-contradiction-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn host_sim(args: &[&str]) -> (i32, String, String) {
    common::host_sim(args)
}

/// `calibrate --format json` of the two files with `extra` flags: the JSON and stderr.
fn calibrate_json(ind: &Path, slip: &Path, extra: &[&str]) -> (Value, String) {
    let mut args = vec!["calibrate", "--indentation", s(ind), "--slip", s(slip)];
    args.extend_from_slice(&["--format", "json"]);
    args.extend_from_slice(extra);
    let (code, out, err) = host_sim(&args);
    assert_eq!(code, 0, "{err}");
    (serde_json::from_str(&out).unwrap(), err)
}

/// `name` without its comment lines, as `old-name`: a lab file that records no rig.
fn without_record(d: &Path, name: &str) -> PathBuf {
    let text = std::fs::read_to_string(d.join(name)).unwrap();
    let old: String = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    let path = d.join(format!("old-{name}"));
    std::fs::write(&path, old).unwrap();
    path
}

fn lof(v: &Value) -> (bool, f64) {
    let l = &v["fit"]["lack_of_fit"];
    (
        l["contradicted"].as_bool().unwrap(),
        l["rms_ln_utilisation"].as_f64().unwrap(),
    )
}

#[test]
fn a_hemisphere_calibrated_as_a_rectangle_warns_and_as_a_disc_does_not() {
    let d = dir("hemisphere");
    let finger = d.join("finger.toml");
    std::fs::write(&finger, HEMISPHERE).unwrap();
    let (code, _, err) = host_sim(&[
        "experiment",
        "all",
        "--plant",
        "brush",
        "--finger",
        s(&finger),
        "--noise",
        "0.02",
        "--seed",
        "1",
        "--out",
        s(&d),
    ]);
    assert_eq!(code, 0, "{err}");
    let (ind, slip) = (d.join("indentation.csv"), d.join("slip.csv"));
    let (old_ind, old_slip) = (
        without_record(&d, "indentation.csv"),
        without_record(&d, "slip.csv"),
    );
    let (rect, warned) = calibrate_json(&old_ind, &old_slip, &[]);
    let (disc, quiet) = calibrate_json(&ind, &slip, &[]);
    let ((rect_bad, rect_rms), (disc_bad, disc_rms)) = (lof(&rect), lof(&disc));
    println!(
        "hemisphere as rect: mu {:.3}, RMS of ln u {rect_rms:.4}, {}",
        rect["mu"]["value"], rect["fit"]["lack_of_fit"]
    );
    println!(
        "hemisphere as disc: mu {:.3}, RMS of ln u {disc_rms:.4}, {}",
        disc["mu"]["value"], disc["fit"]["lack_of_fit"]
    );
    assert_eq!(rect["shape"], "rect");
    assert!(rect_bad && rect_rms > 0.3, "{}", rect["fit"]);
    for cause in [
        "warning: the rows contradict the fit",
        "a hemisphere (shape disc)",
        "the shape (rect) and the half-length (0.01 m) are only the defaults",
    ] {
        assert!(warned.contains(cause), "{cause}: {warned}");
    }
    assert_eq!(rect["warnings"].as_array().unwrap().len(), 1);
    // The files' record makes it a disc, which the rows do not contradict.
    assert_eq!(disc["shape"], "disc");
    assert!(!disc_bad && disc_rms < MATERIAL_RMS, "{}", disc["fit"]);
    assert!(!quiet.contains("warning"), "{quiet}");
    assert_eq!(disc["warnings"], Value::Array(vec![]));
    let _ = std::fs::remove_dir_all(&d);
}

/// The largest RMS and the least p value over `fits`, for the printout.
fn worst(fits: &[LackOfFit]) -> (f64, f64) {
    fits.iter().fold((0.0f64, 1.0f64), |(r, p), l| {
        (r.max(l.rms_ln_utilisation), p.min(l.p_value.unwrap_or(1.0)))
    })
}

#[test]
fn noisy_rows_the_model_describes_do_not_warn() {
    let specs = [
        FingerSpec {
            shape: FingerShape::Rect,
            mu: 0.8,
            k: 3.0,
            c: 2.5e-3,
            gamma: 0.45,
            half_length_m: 0.01,
            skew: None,
        },
        FingerSpec {
            shape: FingerShape::Disc,
            mu: 0.6,
            k: 2.0,
            c: 3e-3,
            gamma: 1.0 / 3.0,
            half_length_m: 0.01,
            skew: None,
        },
    ];
    for spec in specs {
        let rig = FlsRig::new(spec, 0.3, 12.0).unwrap();
        let setup = Setup {
            shape: spec.shape,
            half_length_m: spec.half_length_m,
        };
        let data = |seed: u64| {
            all(
                &rig,
                &FORCES,
                2,
                &DEFAULT_RATIOS_M,
                &mut Noise::new(0.02, 0.0, 0.0, 0.0, seed),
            )
        };
        let (ind0, slip0) = data(0);
        let grid = grid_for(&setup, &ind0, &slip0).unwrap();
        let fits: Vec<LackOfFit> = (1..=20)
            .map(|seed| {
                let (ind, slip) = data(seed);
                let cal = calibrate_on(&grid, &setup, "ind", &ind, "slip", &slip).unwrap();
                assert!(cal.warnings.is_empty(), "seed {seed}: {:?}", cal.warnings);
                cal.fit.lack_of_fit
            })
            .collect();
        let (rms, p) = worst(&fits);
        println!(
            "fls {:?}, 20 seeds: largest RMS of ln u {rms:.4}, least p {p:.3}",
            spec.shape
        );
        assert!(fits.iter().all(|l| !l.contradicted));
    }
}

/// One brush finger's lab rows (`noise` relative, `repeats` per force).
fn brush_rows(
    toml: &str,
    noise: f64,
    repeats: usize,
) -> (
    Vec<softgrip_calibrate::lab_csv::Indentation>,
    Vec<softgrip_calibrate::lab_csv::SlipOnset>,
) {
    #[derive(serde::Deserialize)]
    struct File {
        finger: Finger,
    }
    let f = toml::from_str::<File>(toml).unwrap().finger;
    let brush = f.brush_finger().unwrap().unwrap();
    let rig: &dyn Rig = &brush;
    let mut noise = Noise::new(noise, 0.0, 0.0, 0.0, 11);
    all(rig, &FORCES, repeats, &DEFAULT_RATIOS_M, &mut noise)
}

/// The brush finger `i` of [`common::BRUSH_FINGERS`]: noisy (2 %, twice per force) and
/// noise-free rows at its own shape and half-length do not warn; the noise-free misfit
/// stays under half of [`MATERIAL_RMS`]. The soft hemicylinder given a half-length 25 % too long warns.
fn brush_finger(i: usize) {
    let (name, toml, l) = common::BRUSH_FINGERS[i];
    let shape = if toml.contains("\"disc\"") {
        FingerShape::Disc
    } else {
        FingerShape::Rect
    };
    let setup = Setup {
        shape,
        half_length_m: l,
    };
    let fit = |rows: &(Vec<_>, Vec<_>), setup: &Setup| {
        calibrate(setup, "ind", &rows.0, "slip", &rows.1).unwrap()
    };
    let noisy = brush_rows(toml, 0.02, 2);
    let exact = brush_rows(toml, 0.0, 1);
    let (a, b) = (fit(&noisy, &setup), fit(&exact, &setup));
    let (la, lb) = (&a.fit.lack_of_fit, &b.fit.lack_of_fit);
    println!(
        "{name}: 2 % noise RMS of ln u {:.4} (p {:.3}), noise-free {:.4}",
        la.rms_ln_utilisation,
        la.p_value.unwrap_or(1.0),
        lb.rms_ln_utilisation
    );
    assert!(a.warnings.is_empty() && b.warnings.is_empty(), "{name}");
    assert!(lb.rms_ln_utilisation < MATERIAL_RMS / 2.0, "{name}: {lb:?}");
    if i == 0 {
        let long = Setup {
            shape,
            half_length_m: 1.25 * l,
        };
        let c = fit(&noisy, &long);
        println!(
            "{name}, half-length 25 % long: RMS of ln u {:.4}, {:?}",
            c.fit.lack_of_fit.rms_ln_utilisation, c.warnings
        );
        assert_eq!(c.warnings.len(), 1, "{name}: {:?}", c.fit);
        assert!(c.warnings[0].contains("shorter than the half-length (0.0125 m)"));
    }
}

#[test]
fn brush_fingers_fitted_at_their_shape_do_not_warn() {
    std::thread::scope(|s| {
        for i in 0..common::BRUSH_FINGERS.len() {
            s.spawn(move || brush_finger(i));
        }
    });
}

/// Each `95 % [lo, hi]` of a text report has at most four significant digits.
fn four_digit_intervals(text: &str) {
    for part in text.split("95 % [").skip(1) {
        let inside = &part[..part.find(']').unwrap()];
        for n in inside.split(", ") {
            let digits: String = n
                .chars()
                .take_while(|c| *c != 'e')
                .filter(char::is_ascii_digit)
                .collect();
            let significant = digits.trim_start_matches('0');
            assert!(
                n == "inf" || significant.len() <= 4,
                "{n} in {inside}\n{text}"
            );
        }
    }
}

#[test]
fn the_files_record_the_rig_and_a_contradicting_flag_is_refused() {
    let d = dir("record");
    let (code, _, err) = host_sim(&[
        "experiment",
        "all",
        "--noise",
        "0.02",
        "--seed",
        "4",
        "--out",
        s(&d),
    ]);
    assert_eq!(code, 0, "{err}");
    let (ind, slip) = (d.join("indentation.csv"), d.join("slip.csv"));
    let text = std::fs::read_to_string(&slip).unwrap();
    assert!(
        text.starts_with(
            "normal_force_n,tangential_force_n,torsional_moment_nm\n# shape = rect\n\
             # half_length_m = 0.01\n"
        ),
        "{text}"
    );
    let run = |extra: &[&str]| {
        let mut args = vec!["calibrate", "--indentation", s(&ind), "--slip", s(&slip)];
        args.extend_from_slice(extra);
        host_sim(&args)
    };
    for (flags, want) in [
        (
            ["--shape", "disc"],
            "--shape disc contradicts {ind}, which records the rig's shape = rect",
        ),
        (
            ["--half-length", "0.02"],
            "--half-length 0.02 contradicts {ind}, which records the rig's half_length_m = 0.01",
        ),
    ] {
        let (code, _, err) = run(&flags);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains(&want.replace("{ind}", s(&ind))), "{err}");
    }
    // The recorded values, given or not, and the text report to four digits.
    let (code, text_out, err) = run(&["--shape", "rect", "--half-length", "0.01"]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("warning"), "{err}");
    four_digit_intervals(&text_out);
    assert!(text_out.contains("lack of fit: RMS of ln u"), "{text_out}");
    // Two files of different rigs are refused.
    std::fs::write(&slip, text.replace("# shape = rect", "# shape = disc")).unwrap();
    let (code, _, err) = run(&[]);
    assert_eq!(code, 2);
    assert!(err.contains("the files are of different rigs"), "{err}");
    // Without a record or a flag: a rectangle of half-length 0.01 m, the defaults.
    let (old_ind, old_slip) = (
        without_record(&d, "indentation.csv"),
        without_record(&d, "slip.csv"),
    );
    let (v, _) = calibrate_json(&old_ind, &old_slip, &[]);
    assert_eq!(v["shape"], "rect");
    assert_eq!(v["half_length_m"], 0.01);
    let _ = std::fs::remove_dir_all(&d);
}
