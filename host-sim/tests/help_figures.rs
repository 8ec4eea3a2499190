//! The figures the command line's help states are the ones the code uses: `experiment`'s
//! `[default: X]` finger values are its defaults (a run without the flags writes what a
//! run with them set to X writes), and `bench --hard`'s ranges are the ranges its shakes
//! and `mu-mismatch` trials are drawn from.

use host_sim::bench::families::{self, Ranges};
use host_sim::bench::trial_finger::{BenchPlant, FingerSource};
use std::path::PathBuf;
use std::process::Command;

fn host_sim(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(args)
        .output()
        .expect("host-sim runs");
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The `[default: X]` of flag `--name` in `help`.
fn stated_default(help: &str, name: &str) -> String {
    let flag = format!("--{name} <");
    let at = help
        .find(&flag)
        .unwrap_or_else(|| panic!("no {flag} in the help"));
    let rest = &help[at..];
    let open = rest.find("[default: ").expect("a stated default") + "[default: ".len();
    let close = rest[open..].find(']').unwrap();
    rest[open..open + close].to_string()
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-help-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn experiments_stated_finger_defaults_are_its_defaults() {
    let help = host_sim(&["experiment", "--help"]);
    let mut flags = Vec::new();
    for name in ["k", "mu", "c", "gamma", "half-length", "alpha"] {
        let value = stated_default(&help, name);
        value
            .parse::<f64>()
            .unwrap_or_else(|e| panic!("--{name}: {value}: {e}"));
        flags.push((format!("--{name}"), value));
    }
    let (plain, set) = (temp("plain"), temp("set"));
    let base = [
        "experiment",
        "slip",
        "--forces",
        "1,2",
        "--repeats",
        "1",
        "--out",
    ];
    let mut with_flags: Vec<&str> = base.to_vec();
    with_flags.push(set.to_str().unwrap());
    // A skew, so that --alpha takes part.
    with_flags.extend(["--skew", "0.3"]);
    for (f, v) in &flags {
        with_flags.extend([f.as_str(), v.as_str()]);
    }
    let mut without: Vec<&str> = base.to_vec();
    without.push(plain.to_str().unwrap());
    without.extend(["--skew", "0.3"]);
    host_sim(&without);
    host_sim(&with_flags);
    let read = |d: &PathBuf| std::fs::read_to_string(d.join("slip.csv")).expect("slip.csv");
    let (a, b) = (read(&plain), read(&set));
    std::fs::remove_dir_all(&plain).ok();
    std::fs::remove_dir_all(&set).ok();
    assert!(a.lines().count() > 2, "{a}");
    assert_eq!(a, b, "the stated defaults {flags:?} are not the defaults");
}

/// `key = value` of a trial's scene text, as a number.
fn value(text: &str, key: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.starts_with(&format!("{key} = ")))
        .unwrap_or_else(|| panic!("no {key}"));
    line.split(" = ").nth(1).unwrap().parse().unwrap()
}

#[test]
fn the_hard_ranges_are_the_ones_bench_help_states() {
    let help = host_sim(&["bench", "--help"]);
    assert!(
        help.contains("6-15 Hz through 20-60 ms actuators")
            && help.contains("a true mu 0.5-1.0 x the measured one"),
        "{help}"
    );
    let source = FingerSource::Drawn(BenchPlant::Fls);
    let hard = Ranges {
        hard: true,
        ..Ranges::default()
    };
    let (mut freq, mut tau, mut ratio) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..40 {
        let t = families::trial_on(&source, &hard, "shake", 5, i).unwrap();
        freq.push(value(&t.text, "frequency_hz"));
        tau.push(value(&t.text, "time_constant_s"));
        let t = families::trial_on(&source, &hard, "mu-mismatch", 5, i).unwrap();
        ratio.push(t.mu_ratio);
    }
    let within = |v: &[f64], lo: f64, hi: f64| v.iter().all(|x| (lo..=hi).contains(x));
    let spread = |v: &[f64], lo: f64, hi: f64| {
        let (min, max) = v
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(*x), b.max(*x)));
        min < lo + 0.25 * (hi - lo) && max > hi - 0.25 * (hi - lo)
    };
    for (v, lo, hi, what) in [
        (&freq, 6.0, 15.0, "shake frequency [Hz]"),
        (&tau, 0.02, 0.06, "actuator time constant [s]"),
        (&ratio, 0.5, 1.0, "true mu over measured"),
    ] {
        assert!(within(v, lo, hi) && spread(v, lo, hi), "{what}: {v:?}");
    }
}
