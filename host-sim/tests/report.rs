//! The report writers of `host-sim simulate`: CSV, SVG plots, JSON summary and tables.

mod common;

use common::parts;
use host_sim::sim::record::{CommandParts, LinkSummary, RunSummary, Sample};
use host_sim::sim::report::*;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// A fresh, empty directory under the system's temp dir, removed on drop unless
/// `SOFTGRIP_KEEP_TEST_OUTPUT` is set (to look at the plots).
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!(
            "softgrip-report-test-{}-{name}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }
    fn join(&self, file: &str) -> PathBuf {
        self.0.join(file)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        if std::env::var_os("SOFTGRIP_KEEP_TEST_OUTPUT").is_some() {
            eprintln!("kept {}", self.0.display());
            return;
        }
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const PITCH: f64 = 0.8;

/// A circle-ish trajectory in the normalised load plane whose radius grows past 1 (there
/// the contact slips), with NaN and infinite values sprinkled in.
fn samples(n: usize, phase: f64) -> Vec<Sample> {
    (0..n)
        .map(|i| {
            let t = i as f64 * 1e-3;
            let th = std::f64::consts::FRAC_PI_2 * (i as f64 / n as f64);
            let r = 0.4 + 0.9 * (i as f64 / n as f64) + 0.05 * (phase + t * 40.0).sin();
            let slipping = r > 1.0;
            let mut s = Sample {
                t_s: t,
                ft_n: 2.0 * r * th.cos() + 0.1 / 3.0,
                mn_nm: 1e-3 * r * th.sin(),
                ft_meas_n: if i % 7 == 0 {
                    f64::NAN
                } else {
                    2.0 * r * th.cos()
                },
                mn_meas_nm: 1e-3 * r * th.sin(),
                n_cmd_n: 3.0 + r + phase,
                n_true_n: 2.9 + r + phase,
                a_true_m: 4e-3,
                f_norm: r * th.cos(),
                m_norm: r * th.sin() * PITCH,
                pitch: PITCH,
                utilisation: r,
                slipping,
                slip_distance_m: if slipping { 1e-4 * i as f64 } else { 0.0 },
                slip_rotation_rad: 0.0,
                status: if i % 2 == 0 { "ok" } else { "saturated" },
                ..unexplained()
            };
            match i % 50 {
                11 => s.f_norm = f64::INFINITY,
                23 => s.pitch = f64::NAN,
                31 => s.m_norm = f64::NEG_INFINITY,
                37 => s.n_true_n = f64::NAN,
                41 => s.ft_n = f64::INFINITY,
                _ => {}
            }
            s
        })
        .collect()
}

/// A baseline's sample: no command parts (all NaN), the rest zero.
fn unexplained() -> Sample {
    Sample {
        t_s: 0.0,
        ft_n: 0.0,
        mn_nm: 0.0,
        ft_meas_n: 0.0,
        mn_meas_nm: 0.0,
        n_cmd_n: 0.0,
        n_true_n: 0.0,
        a_true_m: 0.0,
        f_norm: 0.0,
        m_norm: 0.0,
        pitch: 1.0,
        utilisation: 0.0,
        slipping: false,
        slip_distance_m: 0.0,
        slip_rotation_rad: 0.0,
        status: "none",
        parts: CommandParts::NONE,
    }
}

/// `samples(n, phase)` with softgrip's command parts: `N_slip` of 2 N, the safety factor's
/// level 2.7 N, a load factor of 0.85 for the first third (a steady hold), 1 for the
/// second, 1.45 for the last (a shake, with a slip margin of 1.2 and `μ̂` lowered), and a
/// lead of 0.1 N.
fn explained(n: usize, phase: f64) -> Vec<Sample> {
    let mut v = samples(n, phase);
    for (i, s) in v.iter_mut().enumerate() {
        let (load_factor, slip_margin, mu_hat) = match 3 * i / n {
            0 => (0.85, 1.0, 0.8),
            1 => (1.0, 1.0, 0.8),
            _ => (1.45, 1.2, 0.7),
        };
        s.parts.n_slip_mu_n = 2.0;
        s.parts.n_slip_n = 2.0 * 0.8 / mu_hat;
        s.parts.n_safety_n = 2.7;
        s.parts.n_load_n = 2.7 * load_factor;
        s.parts.required_n = 2.7 * load_factor * slip_margin * 0.8 / mu_hat;
        s.parts.load_factor = load_factor;
        s.parts.slip_margin = slip_margin;
        s.parts.margin = load_factor * slip_margin;
        s.parts.mu_hat = mu_hat;
        s.parts.lead_n = 0.1;
    }
    v
}

fn run(scene: &str, controller: &str, events: u64, mean: f64, expected_slip: bool) -> RunSummary {
    RunSummary {
        scene: scene.to_string(),
        controller: controller.to_string(),
        dropped: false,
        slip_events: events,
        slip_distance_m: 1e-3 * events as f64,
        slip_rotation_rad: 2e-3 * events as f64,
        mean_normal_force_n: mean,
        peak_normal_force_n: 2.0 * mean,
        expected_slip,
        max_utilisation: if events > 0 { 1.3 } else { 0.8 },
        ticks: 1000,
        duration_s: 1.0,
        wall_s: 0.01,
        real_time_factor: 100.0,
        link: LinkSummary {
            frames_sent: 1000,
            frames_received: 998,
            frames_corrupt: 1,
            frames_lost: 1,
            commands_missing: 2,
        },
        step_cost_share: BTreeMap::from([("core".to_string(), 1.0)]),
        effects: vec!["hysteresis".to_string()],
        metrics: BTreeMap::from([("plant_step_s".to_string(), 0.004)]),
    }
}

/// softgrip's command parts, the CSV's last columns.
const PARTS: [&str; 10] = [
    "n_slip_n",
    "required_n",
    "mu_hat",
    "margin",
    "slip_margin",
    "load_factor",
    "lead_n",
    "n_slip_mu_n",
    "n_safety_n",
    "n_load_n",
];

/// The numeric cells of a CSV row as read back.
fn same(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan())
}

#[test]
fn csv_has_header_and_every_sample_round_trips() {
    let dir = TempDir::new("csv");
    let path = dir.join("run.csv");
    let mut data = explained(500, 0.0);
    data[3].t_s = 0.1 + 0.2; // not exactly representable in few digits
    data[4].a_true_m = 1.0 / 3.0;
    data[5].parts.required_n = 1.0 / 3.0;
    data[6] = Sample {
        t_s: 6e-3,
        ..unexplained()
    };
    write_csv(&path, &data).unwrap();

    let mut rd = csv::Reader::from_path(&path).unwrap();
    let header: Vec<String> = rd.headers().unwrap().iter().map(str::to_string).collect();
    assert_eq!(header, SAMPLE_CSV_FIELDS);
    // softgrip's command parts follow the status, units in their names.
    assert_eq!(header[header.len() - PARTS.len()..], PARTS);
    let rows: Vec<csv::StringRecord> = rd.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), data.len());

    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    for (row, s) in rows.iter().zip(&data) {
        assert_eq!(row.len(), SAMPLE_CSV_FIELDS.len());
        let f = |name: &str| -> f64 { row[col(name)].parse().unwrap() };
        let expect = [
            ("t_s", s.t_s),
            ("ft_n", s.ft_n),
            ("mn_nm", s.mn_nm),
            ("ft_meas_n", s.ft_meas_n),
            ("mn_meas_nm", s.mn_meas_nm),
            ("n_cmd_n", s.n_cmd_n),
            ("n_true_n", s.n_true_n),
            ("a_true_m", s.a_true_m),
            ("f_norm", s.f_norm),
            ("m_norm", s.m_norm),
            ("pitch", s.pitch),
            ("utilisation", s.utilisation),
            ("slip_distance_m", s.slip_distance_m),
            ("slip_rotation_rad", s.slip_rotation_rad),
        ];
        for (name, v) in expect {
            assert!(same(f(name), v), "{name}: {} read back as {}", v, f(name));
        }
        for (name, v) in PARTS.into_iter().zip(parts(s)) {
            let back: f32 = row[col(name)].parse().unwrap();
            assert!(
                back.to_bits() == v.to_bits() || (back.is_nan() && v.is_nan()),
                "{name}: {v} read back as {back}"
            );
        }
        let slipping: bool = row[col("slipping")].parse().unwrap();
        assert_eq!(slipping, s.slipping);
        assert_eq!(&row[col("status")], s.status);
    }

    // NaN is spelled `NaN`, infinities `inf`/`-inf`.
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains(",NaN,"));
    assert!(text.contains(",inf,"));
    assert!(text.contains(",-inf,"));
    assert!(text.contains("0.30000000000000004"));
}

#[test]
fn csv_of_no_samples_has_the_same_header() {
    let dir = TempDir::new("csv-empty");
    write_csv(&dir.join("a.csv"), &samples(1, 0.0)).unwrap();
    write_csv(&dir.join("b.csv"), &[]).unwrap();
    let a = std::fs::read_to_string(dir.join("a.csv")).unwrap();
    let b = std::fs::read_to_string(dir.join("b.csv")).unwrap();
    assert_eq!(a.lines().next(), b.lines().next());
    assert_eq!(b.lines().count(), 1);
    assert_eq!(b.trim_end(), SAMPLE_CSV_FIELDS.join(","));
}

fn assert_clean_svg(svg: &str) {
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("<text"));
    // Non-finite samples are skipped, never drawn at NaN/inf coordinates.
    assert!(!svg.contains("NaN"));
    assert!(!svg.contains("inf\""));
}

#[test]
fn surface_plot_has_curves_runs_legend_and_slip_marks() {
    let dir = TempDir::new("surface");
    let a = samples(2000, 0.0);
    let b = samples(1500, 1.0);
    let surface: Vec<(f64, f64)> = (0..=50)
        .map(|i| {
            let th = std::f64::consts::FRAC_PI_2 * f64::from(i) / 50.0;
            (th.cos(), 0.9 * th.sin())
        })
        .chain([(f64::NAN, 0.5)])
        .collect();
    let path = dir.join("surface.svg");
    plot_surface(
        &path,
        "scene twist: load vs limit surface",
        &[("softgrip", &a), ("coulomb", &b)],
        &surface,
    )
    .unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert_clean_svg(&svg);
    for label in [
        "scene twist: load vs limit surface",
        "Eq. 10 ellipse",
        "limit surface",
        "softgrip",
        "coulomb",
        "slipping",
    ] {
        assert!(svg.contains(label), "missing {label:?}");
    }
    // Slip crosses in red, and the two runs in the first two run colours.
    assert!(svg.matches("#D62728").count() > 20, "too few slip marks");
    assert!(svg.contains("#1F77B4"));
    assert!(svg.contains("#FF7F0E"));
    // The dashed ellipse (many short black dashes) and the solid surface.
    assert!(svg.matches("stroke=\"#000000\" stroke-width=\"2\"").count() > 30);
}

#[test]
fn surface_plot_survives_degenerate_data() {
    let dir = TempDir::new("surface-degenerate");
    let mut nan_only = samples(100, 0.0);
    for s in &mut nan_only {
        s.f_norm = f64::NAN;
    }
    let mut huge = samples(100, 0.0);
    for s in &mut huge {
        s.f_norm = 1e308;
        s.m_norm = -1e308;
        s.pitch = 1e-300;
    }
    let path = dir.join("s.svg");
    plot_surface(
        &path,
        "degenerate",
        &[("all-nan", &nan_only), ("huge", &huge), ("empty", &[])],
        &[],
    )
    .unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert_clean_svg(&svg);
    for label in ["all-nan", "huge", "empty", "Eq. 10 ellipse"] {
        assert!(svg.contains(label), "missing {label:?}");
    }

    plot_force(&dir.join("f.svg"), "no runs", &[]).unwrap();
    assert_clean_svg(&std::fs::read_to_string(dir.join("f.svg")).unwrap());
}

#[test]
fn force_plot_has_lines_load_and_slip_shading() {
    let dir = TempDir::new("force");
    let a = samples(3000, 0.0);
    let mut b = samples(3000, 0.5);
    for s in &mut b {
        s.slipping = false;
    }
    let path = dir.join("force.svg");
    plot_force(
        &path,
        "scene twist: normal force",
        &[("softgrip", &a), ("fixed-3N", &b)],
    )
    .unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert_clean_svg(&svg);
    for label in [
        "scene twist: normal force",
        "tangential load (per contact)",
        "softgrip",
        "fixed-3N",
        "time [s]",
        "force [N]",
        "slipping",
    ] {
        assert!(svg.contains(label), "missing {label:?}");
    }
    // The shading of the first run's slip intervals: translucent rectangles in its colour.
    assert!(svg.contains("<rect"));
    assert!(svg.contains("fill=\"#1F77B4\""));
    // The second run never slips: nothing shaded in its colour.
    assert!(!svg.contains("fill=\"#FF7F0E\""));
}

#[test]
fn force_plot_stacks_what_each_part_of_softgrips_command_asks() {
    let dir = TempDir::new("force-bands");
    let a = explained(3000, 0.0);
    let b = explained(3000, 0.5);
    let c = samples(3000, 1.0);
    let path = dir.join("force.svg");
    plot_force(
        &path,
        "shake: normal force",
        &[("constant", &c), ("softgrip", &a), ("softgrip-table", &b)],
    )
    .unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert_clean_svg(&svg);
    // The first run with parts gets the bands, each in the legend; the second does not.
    for label in [
        "softgrip: N_slip at μ (the model)",
        "softgrip: × safety factor (and the disc factor β on torsion)",
        "softgrip: × load factor (up to 1.45)",
        "softgrip: × load factor (down to 0.85): given back",
        "softgrip: × slip margin (up to 1.20), μ/μ̂",
        "softgrip: + lead for the actuator",
    ] {
        assert!(svg.contains(label), "missing {label:?}");
    }
    assert!(!svg.contains("softgrip-table: "));
    // Each band is one filled polygon per stretch of finite samples, in its pale colour.
    for fill in [
        "#C6DBEF", "#98DF8A", "#FFBB78", "#D4D4D4", "#FF9896", "#C5B0D5",
    ] {
        assert!(
            svg.contains(&format!("fill=\"{fill}\"")),
            "no band in {fill}"
        );
    }

    // A band that asks nothing stays out of the legend; baselines alone get no bands.
    let steady: Vec<Sample> = explained(300, 0.0).into_iter().take(100).collect();
    plot_force(&path, "hold", &[("softgrip", &steady)]).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.contains("given back"));
    assert!(!svg.contains("up to") && !svg.contains("slip margin"));
    plot_force(&path, "baselines", &[("constant", &c), ("box", &c)]).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(!svg.contains("N_slip") && !svg.contains("#C6DBEF"));
}

#[test]
fn surface_axes_follow_the_99th_percentile_and_stay_finite() {
    let quiet = samples(1000, 0.0);
    // The synthetic loads stay below 1.35: the floor of 1.2 or a little above.
    let l = surface_axis_limit(&[("a", &quiet)], &[]);
    assert!((1.2..1.5).contains(&l), "{l}");

    // Tangential loads spread evenly up to 3 (no torsion): the axes reach about 3.
    let mut big = samples(1000, 0.0);
    for (i, s) in big.iter_mut().enumerate() {
        s.f_norm = 3.0 * i as f64 / 999.0;
        s.m_norm = 0.0;
        s.pitch = PITCH;
    }
    let l = surface_axis_limit(&[("a", &big)], &[]);
    assert!((2.9..3.2).contains(&l), "{l}");

    // Pure torsion: y is |m_norm| / pitch, so m_norm = 1.5 at pitch 0.5 is y = 3.
    let mut twist = samples(100, 0.0);
    for s in &mut twist {
        s.f_norm = 0.0;
        s.m_norm = -1.5;
        s.pitch = 0.5;
    }
    let l = surface_axis_limit(&[("a", &twist)], &[]);
    assert!((l - 3.15).abs() < 1e-9, "{l}");

    // Five wild outliers among 1000 samples (< 1 %) do not stretch the axes.
    let mut wild = samples(1000, 0.0);
    for s in wild.iter_mut().step_by(200) {
        s.f_norm = 1e12;
    }
    let l = surface_axis_limit(&[("a", &wild)], &[]);
    assert!(l < 1.5, "{l}");

    // Nothing finite, or everything huge: still finite.
    let mut nan = samples(10, 0.0);
    for s in &mut nan {
        s.pitch = f64::NAN;
    }
    assert_eq!(surface_axis_limit(&[("a", &nan)], &[]), 1.2);
    let mut huge = samples(10, 0.0);
    for s in &mut huge {
        s.f_norm = f64::MAX;
    }
    let l = surface_axis_limit(&[("a", &huge)], &[(f64::INFINITY, 0.0)]);
    assert!(l.is_finite() && l >= 1.2, "{l}");
    assert_eq!(surface_axis_limit(&[], &[(2.0, 0.5)]), 2.1);
}

#[test]
fn plot_into_a_missing_directory_is_an_io_error() {
    let path = std::env::temp_dir().join("softgrip-report-no-such-dir/x/surface.svg");
    let err = plot_surface(&path, "t", &[], &[]).unwrap_err();
    assert!(matches!(err, ReportError::Io(_)), "{err:?}");
    assert!(!err.to_string().is_empty());
    assert!(std::error::Error::source(&err).is_some());
    assert!(write_csv(&path, &[]).is_err());
    assert!(write_summary_json(&path, &[]).is_err());
}

#[test]
fn summary_json_has_every_run() {
    let dir = TempDir::new("json");
    let runs = [
        run("twist", "softgrip", 0, 1.4, false),
        run("twist", "coulomb", 3, f64::NAN, false),
    ];
    let path = dir.join("summary.json");
    write_summary_json(&path, &runs).unwrap();
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let arr = v["runs"].as_array().unwrap();
    assert_eq!(arr.len(), 2);
    assert_eq!(arr[0]["slip_events"], 0);
    assert_eq!(arr[1]["slip_events"], 3);
    assert_eq!(arr[1]["controller"], "coulomb");
    assert_eq!(arr[0]["mean_normal_force_n"], 1.4);
    assert!(arr[1]["mean_normal_force_n"].is_null());
    assert_eq!(arr[0]["link"]["frames_corrupt"], 1);
    assert_eq!(arr[0]["step_cost_share"]["core"], 1.0);
    assert_eq!(arr[0]["effects"][0], "hysteresis");
}

#[test]
fn summary_table_has_every_run_and_the_right_verdict() {
    let runs = [
        run("twist", "softgrip", 0, 1.4, false),
        run("twist", "fixed-3N", 2, 3.0, false),
        run("overload", "softgrip", 5, 4.0, true),
        run("overload", "coulomb", 0, 9.0, true),
    ];
    let table = summary_table(&runs);
    let lines: Vec<&str> = table.lines().collect();
    assert_eq!(lines.len(), 2 + runs.len(), "{table}");
    for h in [
        "scene",
        "controller",
        "slip events",
        "slip distance [mm]",
        "slip rotation [mrad]",
        "mean N [N]",
        "peak N [N]",
        "max utilisation",
        "expected slip",
        "verdict",
    ] {
        assert!(lines[0].contains(h), "missing header {h:?}");
    }
    let expected = [
        ("twist", "softgrip", "no", "held"),
        ("twist", "fixed-3N", "no", "SLIPPED"),
        (
            "overload",
            "softgrip",
            "yes",
            "overload (slipped as expected)",
        ),
        ("overload", "coulomb", "yes", "held (unexpected)"),
    ];
    let verdict_col = lines[0].find("verdict").unwrap();
    for (line, (scene, ctrl, exp, verdict)) in lines[2..].iter().zip(expected) {
        let cells: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(cells[0], scene, "{line}");
        assert_eq!(cells[1], ctrl, "{line}");
        assert_eq!(&line[verdict_col..], verdict, "{line}");
        assert!(line.contains(&format!(" {exp} ")), "{line}");
    }
    // Units: 2 events → 2 mm and 4 mrad in the synthetic runs.
    assert!(
        lines[3].contains("2.000") && lines[3].contains("4.000"),
        "{}",
        lines[3]
    );
    // Every row is aligned with the header.
    assert!(lines[2..]
        .iter()
        .all(|l| l.chars().count() >= verdict_col + 4));
}

#[test]
fn comparison_table_flags_a_baseline_that_does_as_well() {
    let runs = [
        // Scene a: the baseline holds with less force than softgrip.
        run("a", "softgrip", 0, 1.40, false),
        run("a", "coulomb", 0, 1.23, false),
        run("a", "fixed-3N", 1, 3.0, false),
        // Scene b: softgrip holds with less force.
        run("b", "softgrip", 0, 1.0, false),
        run("b", "coulomb", 0, 2.0, false),
        run("b", "fixed-3N", 0, 3.0, false),
        // Scene c: softgrip slips where a baseline holds.
        run("c", "softgrip", 2, 1.0, false),
        run("c", "coulomb", 1, 2.0, false),
        run("c", "fixed-3N", 0, 3.0, false),
        // Scene d: an overload.
        run("d", "softgrip", 4, 5.0, true),
        run("d", "coulomb", 4, 5.01, true),
        run("d", "fixed-3N", 4, 3.0, true),
    ];
    let table = comparison_table(&runs);
    let lines: Vec<&str> = table.lines().collect();

    // One row per controller, in input order.
    let row = |c: &str| -> Vec<&str> {
        lines
            .iter()
            .find(|l| l.starts_with(c))
            .unwrap_or_else(|| panic!("no row for {c}:\n{table}"))
            .split_whitespace()
            .collect()
    };
    assert!(lines[2].starts_with("softgrip"));
    assert!(lines[3].starts_with("coulomb"));
    assert!(lines[4].starts_with("fixed-3N"));
    assert_eq!(
        row("softgrip")[1..],
        ["2/3", "6", "6.000", "2.100", "10.000"]
    );
    assert_eq!(
        row("coulomb")[1..],
        ["2/3", "5", "5.000", "2.560", "10.020"]
    );
    assert_eq!(
        row("fixed-3N")[1..],
        ["2/3", "5", "5.000", "3.000", "6.000"]
    );

    assert!(
        table.contains(
            "scene a: baseline \"coulomb\" held with 1.230 N mean, softgrip 1.400 N \
             — the baseline does as well here"
        ),
        "{table}"
    );
    assert!(table.contains("scene a: held by softgrip, coulomb; least mean force: coulomb"));
    assert!(table.contains(
        "scene b: held by softgrip, coulomb, fixed-3N; least mean force: softgrip (1.000 N)"
    ));
    assert!(
        !table.contains("scene b: baseline"),
        "softgrip did better in b:\n{table}"
    );
    assert!(table.contains(
        "scene c: baseline \"fixed-3N\" held with 3.000 N mean, softgrip slipped (2 events) \
         — the baseline does better here"
    ));
    assert!(!table.contains("scene c: baseline \"coulomb\""));
    assert!(table.contains("scene d (overload): every controller slipped, as expected"));
    assert!(!table.contains("scene d: baseline"));
}

#[test]
fn comparison_table_is_quiet_when_softgrip_wins_everywhere() {
    let runs = [
        run("a", "softgrip", 0, 1.0, false),
        run("a", "coulomb", 0, 1.5, false),
        run("b", "softgrip-link", 0, 1.0, false),
        run("b", "coulomb", 0, 1.0 + 1e-9, false),
        run("b", "softgrip", 0, 0.9, false),
    ];
    let table = comparison_table(&runs);
    assert!(!table.contains("baseline"), "{table}");
    assert!(table.contains(
        "scene b: held by softgrip-link, coulomb, softgrip; least mean force: softgrip (0.900 N)"
    ));
    // Equal force counts as "as well".
    let tie = [
        run("a", "softgrip", 0, 1.0, false),
        run("a", "coulomb", 0, 1.0, false),
    ];
    assert!(comparison_table(&tie).contains("the baseline does as well here"));
}

/// A run that lost its object without a slip event (the brush finger's creep can turn it
/// out of the grasp while its centre still sticks) did not hold it: the comparison counts
/// it as the verdict does.
#[test]
fn comparison_table_does_not_count_a_drop_without_slip_events_as_held() {
    let dropped = RunSummary {
        dropped: true,
        ..run("brush", "coulomb", 0, 1.0, false)
    };
    let runs = [run("brush", "softgrip", 0, 2.0, false), dropped];
    let table = comparison_table(&runs);
    assert!(
        table.contains("scene brush: held by softgrip; least mean force: softgrip (2.000 N)"),
        "{table}"
    );
    assert!(!table.contains("baseline"), "{table}");
    let row = table.lines().find(|l| l.starts_with("coulomb")).unwrap();
    assert_eq!(row.split_whitespace().nth(1), Some("0/1"), "{table}");
}
