//! The `required-force` command line: its JSON, the disc's closed form, and its errors.

mod common;

fn run(args: &[&str]) -> (i32, String, String) {
    common::host_sim(&[&["required-force"], args].concat())
}

fn json(args: &[&str]) -> serde_json::Value {
    let mut all = args.to_vec();
    all.extend(["--format", "json"]);
    let (code, out, err) = run(&all);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

const BASE: [&str; 10] = [
    "--ft", "1.0", "--mn", "0.004", "--mu", "0.8", "--c", "0.008", "--gamma", "0",
];

#[test]
fn json_has_the_issue_keys_and_the_disc_closed_form_at_gamma_zero() {
    let mut args = BASE.to_vec();
    args.extend(["--shape", "disc", "--safety", "1.5", "--mode", "ellipse"]);
    for precision in ["f64", "f32"] {
        let mut a = args.clone();
        a.extend(["--precision", precision]);
        let v = json(&a);
        for key in ["normal_force", "n_slip", "a", "utilisation", "status"] {
            assert!(!v[key].is_null(), "{key}");
        }
        // docs/model.md's closed form with the inscribed ellipse (A, B) for Eq. 10's unit circle,
        // the round patch's moment carrying its own factor β in the tick's requirement:
        // N_req(s) = s·sqrt((f/(μA))² + (β·m/(μ a pitch B))²), pitch = 3π/16; N_slip has
        // neither s nor β.
        let pitch = 3.0 * std::f64::consts::PI / 16.0;
        let ax = v["ellipse_axes"][0].as_f64().unwrap();
        let bx = v["ellipse_axes"][1].as_f64().unwrap();
        assert!(ax > 0.9 && ax < 1.0 && bx > 0.9 && bx < 1.0, "{ax} {bx}");
        let beta = softgrip::controller::DISC_TORSION_SAFETY_FACTOR;
        let closed = |b: f64| {
            ((1.0f64 / (0.8 * ax)).powi(2) + (b * 0.004 / (0.8 * 0.008 * pitch * bx)).powi(2))
                .sqrt()
        };
        let (want, slip) = (1.5 * closed(beta), closed(1.0));
        let got = v["normal_force"].as_f64().unwrap();
        let tol = if precision == "f64" { 1e-12 } else { 1e-6 };
        assert!(
            (got / want - 1.0).abs() < tol,
            "{precision}: {got} vs {want}"
        );
        assert!((v["n_slip"].as_f64().unwrap() / slip - 1.0).abs() < tol);
        assert_eq!(v["a"].as_f64(), Some(0.008));
        // At γ = 0 the capacity is linear in N: the unscaled load's utilisation is N_slip/N.
        let u = v["utilisation"].as_f64().unwrap();
        assert!((u / (slip / want) - 1.0).abs() < tol, "{u}");
        assert_eq!(v["status"], "ok");
        // Conservative: never below the exact surface's answer.
        let exact = v["exact_force"].as_f64().unwrap();
        assert!(
            got >= exact * (1.0 - 1e-6) && got < exact * 1.08,
            "{got} {exact}"
        );
    }
}

#[test]
fn growing_contacts_need_less_than_s_times_n_slip_and_both_modes_at_least_the_exact_force() {
    let args = [
        "--ft", "1.0", "--mn", "0.006", "--mu", "0.8", "--c", "0.0025", "--gamma", "0.5",
        "--safety", "1.3",
    ];
    let mut e = args.to_vec();
    e.extend(["--mode", "ellipse"]);
    let e = json(&e);
    let mut t = args.to_vec();
    t.extend(["--mode", "table"]);
    let t = json(&t);
    let (n, slip) = (
        e["normal_force"].as_f64().unwrap(),
        e["n_slip"].as_f64().unwrap(),
    );
    assert!(n < 1.3 * slip && n > slip, "{n} {slip}");
    // Both modes are conservative against the exact surface: table mode within its raised
    // rows (0.5 %), ellipse mode within what the inscribed ellipse costs (at most 15.2 %
    // for the default finger).
    let exact = e["exact_force"].as_f64().unwrap();
    assert_eq!(t["exact_force"].as_f64().unwrap(), exact);
    let tn = t["normal_force"].as_f64().unwrap();
    assert!(tn >= exact && tn < exact * 1.005, "{tn} {exact}");
    assert!(n >= exact && n < exact * 1.16, "{n} {exact}");
    assert!((e["over_exact"].as_f64().unwrap() - (n / exact - 1.0)).abs() < 1e-12);
}

#[test]
fn a_load_beyond_n_max_is_saturated_and_the_command_clamped() {
    let mut args = BASE.to_vec();
    args[1] = "100";
    let v = json(&args);
    assert_eq!(v["status"], "saturated");
    assert_eq!(v["command"].as_f64(), Some(20.0));
    assert!(v["normal_force"].as_f64().unwrap() > 20.0);
    assert!(v["utilisation"].as_f64().unwrap() > 1.0);
}

#[test]
fn zero_and_tiny_loads_give_finite_answers() {
    for (ft, mn) in [("0", "0"), ("1e-12", "0"), ("0", "1e-15"), ("-2", "-0.01")] {
        let mut args = BASE.to_vec();
        args[1] = ft;
        args[3] = mn;
        let v = json(&args);
        let n = v["normal_force"].as_f64().unwrap();
        assert!(n.is_finite() && n >= 0.0, "{ft} {mn}: {n}");
        assert!(v["command"].as_f64().unwrap() >= 0.2);
    }
}

#[test]
fn bad_arguments_give_one_line_naming_them_and_exit_code_2() {
    let cases: [(&str, &str, &str); 10] = [
        ("--mu", "0", "--mu"),
        ("--mu", "NaN", "--mu"),
        ("--c", "-1", "--c"),
        ("--gamma", "0.7", "--gamma"),
        ("--ft", "inf", "--ft"),
        ("--mn", "nan", "--mn"),
        ("--ft", "1e30", "--ft"),
        ("--safety", "0.5", "--safety"),
        ("--k", "0.2", "--k"),
        ("--ft", "abc", "--ft"),
    ];
    for (flag, value, named) in cases {
        let mut args = BASE.to_vec();
        match args.iter().position(|a| *a == flag) {
            Some(i) => args[i + 1] = value,
            None => args.extend([flag, value]),
        }
        let (code, out, err) = run(&args);
        assert_eq!(code, 2, "{flag} {value}: {err}");
        assert!(out.is_empty());
        // The first line names the flag (a value clap refuses is followed by its hints).
        let first = err.lines().next().unwrap_or("");
        assert!(first.starts_with("error: "), "{flag} {value}: {err}");
        assert!(first.contains(named), "{flag} {value}: {err}");
    }
    // Missing arguments: clap's whole error, naming them, with the usage line.
    let (code, _, err) = run(&["--ft", "1"]);
    assert_eq!(code, 2);
    assert!(err.starts_with("error: "), "{err}");
    assert!(err.contains("--mn"), "{err}");
    assert!(err.contains("Usage: host-sim required-force"), "{err}");
}
