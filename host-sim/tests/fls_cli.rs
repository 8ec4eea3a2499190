//! The `fls` command line: its JSON interface and its exit codes.

mod common;

fn run(args: &[&str]) -> (i32, String, String) {
    common::host_sim(&[&["fls"], args].concat())
}

#[test]
fn json_has_pitch_ellipse_and_samples() {
    let (code, out, _) = run(&["--format", "json", "--k", "4", "--at", "0,1,2.5"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let pitch = v["pitch"].as_f64().unwrap();
    assert!((pitch - 0.7442).abs() < 5e-5);
    let e = &v["ellipse"];
    for key in [
        "f_semi_axis",
        "m_semi_axis",
        "max_radial_gap",
        "max_relative_gap",
    ] {
        assert!(e[key].as_f64().unwrap().is_finite(), "{key}");
    }
    let samples = v["samples"].as_array().unwrap();
    assert_eq!(samples.len(), 3);
    assert_eq!(samples[0]["d"].as_f64(), Some(0.0));
    assert_eq!(samples[0]["m"].as_f64(), Some(pitch));
    assert_eq!(samples[2]["d"].as_f64(), Some(2.5));
    assert!(samples[1]["f"].as_f64().unwrap() > 0.5);
}

#[test]
fn json_sweep_has_the_requested_samples_rising_in_d() {
    let (code, out, _) = run(&["--format", "json", "--samples", "40", "--shape", "disc"]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let s = v["samples"].as_array().unwrap();
    assert_eq!(s.len(), 40);
    let d: Vec<f64> = s.iter().map(|p| p["d"].as_f64().unwrap()).collect();
    assert!(d.windows(2).all(|w| w[1] > w[0]));
    assert!((v["pitch"].as_f64().unwrap() - 3.0 * std::f64::consts::PI / 16.0).abs() < 1e-11);
}

#[test]
fn table_and_csv_formats() {
    let (code, out, _) = run(&["--samples", "8"]);
    assert_eq!(code, 0);
    assert!(out.contains("d_c/a [1]") && out.contains("pitch"));
    let (code, out, _) = run(&["--format", "csv", "--samples", "8"]);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "d_over_a,f_over_mu_n,m_over_mu_n_a");
    assert_eq!(lines.len(), 9);
}

#[test]
fn bad_arguments_exit_2_with_a_first_line_naming_them() {
    for (args, name) in [
        (vec!["--k", "0.5"], "--k"),
        (vec!["--k", "NaN"], "--k"),
        (vec!["--skew", "1"], "--skew"),
        (vec!["--skew", "NaN"], "--skew"),
        (vec!["--aspect", "0"], "--aspect"),
        (vec!["--aspect", "-2"], "--aspect"),
        (vec!["--aspect", "inf"], "--aspect"),
        (vec!["--shape", "cone"], "--shape"),
        (vec!["--alpha", "nan"], "--alpha"),
        (vec!["--at", "1,-3"], "--at"),
        (vec!["--samples", "0"], "--samples"),
        (vec!["--order", "2"], "--order"),
        (
            vec!["--shape", "disc", "--skew", "0.9", "--locus", "0.95"],
            "--locus",
        ),
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty());
        // The first line names the argument; a value clap refuses is followed by clap's
        // valid values, "did you mean" and usage hints.
        let first = err.lines().next().unwrap_or("");
        assert!(first.starts_with("error: "), "{args:?}: {err}");
        assert!(first.contains(name), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
    }
}

#[test]
fn hard_values_give_finite_answers() {
    for args in [
        vec!["--k", "1e6", "--format", "json"],
        vec!["--k", "inf", "--format", "json"],
        vec!["--skew", "0.999999", "--format", "json"],
        vec!["--aspect", "1e-3", "--format", "json"],
        vec!["--aspect", "1e3", "--format", "json"],
        vec!["--at", "0,1e-12,1,1e12", "--format", "json"],
        vec!["--precision", "f32", "--format", "json"],
    ] {
        let (code, out, err) = run(&args);
        assert_eq!(code, 0, "{args:?}: {err}");
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        for s in v["samples"].as_array().unwrap() {
            assert!(s["f"].as_f64().unwrap().is_finite(), "{args:?}");
            assert!(s["m"].as_f64().unwrap().is_finite(), "{args:?}");
        }
        assert!(v["pitch"].as_f64().unwrap().is_finite());
    }
}

#[test]
fn clap_errors_are_printed_whole() {
    // A mistyped value: the valid values and clap's suggestion, not only the first line.
    let (code, _, err) = run(&["--shape", "rec"]);
    assert_eq!(code, 2);
    assert!(err.contains("possible values: rect, disc"), "{err}");
    assert!(err.contains("a similar value exists: 'rect'"), "{err}");
    // An unknown flag: the usage line.
    let (code, _, err) = run(&["--bogus"]);
    assert_eq!(code, 2);
    assert!(err.contains("Usage: host-sim fls"), "{err}");
}
