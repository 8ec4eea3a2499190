//! The margin protocols (`host-sim experiment cyclic`, `hold`) and their fit
//! (`softgrip_calibrate::margins`): the `fls` plant, softgrip's own limit surface, neither
//! ratchets nor creeps, so its shares are 1 within their intervals and every factor 1;
//! the brush fingers of docs/calibration.md are measured, their table there is what this
//! test measures, and each one's cyclic share is below 1 (a measured property: the brush
//! ratchets under cycles its static onset holds); the rows are the same for a seed;
//! calibrate without the margin files says what was not measured.
//!
//! `cargo test --release -p host-sim --test margin_protocols -- --nocapture` prints the
//! brush fingers' shares and the protocols' wall times.

mod common;

use host_sim::experiment::cyclic::{self, CyclicPlan};
use host_sim::experiment::hold::{self, HoldPlan};
use host_sim::experiment::timed::{Frame, TimedRig};
use host_sim::experiment::{FingerSpec, FlsRig, Noise};
use host_sim::sim::finger::Finger;
use softgrip::controller::FingerShape;
use softgrip_calibrate::estimate::Estimate;
use softgrip_calibrate::margin_csv::{parse_cyclic, parse_hold, write_cyclic, write_hold};
use softgrip_calibrate::margins::{fit_cyclic, fit_hold, CyclicMargins, HoldMargins, Measured};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// The protocols' defaults, as `host-sim experiment` runs them: 2 N, two onsets per axis.
fn plans() -> (CyclicPlan, HoldPlan) {
    let fractions = cyclic::DEFAULT_FRACTIONS.to_vec();
    (
        CyclicPlan {
            frame: Frame {
                normal_n: 2.0,
                fractions: fractions.clone(),
                onsets: 2,
            },
            cycles: cyclic::DEFAULT_CYCLES,
            frequency_hz: cyclic::DEFAULT_FREQUENCY_HZ,
        },
        HoldPlan {
            frame: Frame {
                normal_n: 2.0,
                fractions,
                onsets: 2,
            },
            ramp_s: hold::DEFAULT_RAMP_S,
            hold_s: hold::DEFAULT_HOLD_S,
        },
    )
}

/// What one finger measures: its margins and each protocol's wall time.
struct Measured2 {
    cyclic: CyclicMargins,
    hold: HoldMargins,
    wall: (Duration, Duration),
}

/// Runs both protocols on `rig` with 2 % relative noise seeded by `seed`, through the
/// files (written and read back), and fits them.
fn measure(rig: &dyn TimedRig, shape: FingerShape, seed: u64) -> Measured2 {
    let (cp, hp) = plans();
    let t = Instant::now();
    let rows = cyclic::cyclic(rig, &cp, &mut Noise::new(0.02, 0.0, 0.0, 0.0, seed));
    let cyclic_wall = t.elapsed();
    let rows = parse_cyclic("cyclic.csv", &write_cyclic(&rows)).unwrap();
    let cyclic = match fit_cyclic("cyclic.csv", &rows).unwrap() {
        Measured::Fitted(c) => c,
        Measured::Not { reason, .. } => panic!("{reason}"),
    };
    let t = Instant::now();
    let rows = hold::hold(rig, &hp, &mut Noise::new(0.02, 0.0, 0.0, 0.0, seed));
    let hold_wall = t.elapsed();
    let rows = parse_hold("hold.csv", &write_hold(&rows)).unwrap();
    let hold = match fit_hold("hold.csv", &rows, shape).unwrap() {
        Measured::Fitted(h) => h,
        Measured::Not { reason, .. } => panic!("{reason}"),
    };
    Measured2 {
        cyclic,
        hold,
        wall: (cyclic_wall, hold_wall),
    }
}

fn ci(e: &Estimate) -> [f64; 2] {
    e.ci95.unwrap_or_else(|| panic!("no interval: {e:?}"))
}

fn contains(e: &Estimate, x: f64) -> bool {
    let [lo, hi] = ci(e);
    lo <= x && x <= hi
}

fn fls(shape: FingerShape) -> FlsRig {
    let spec = FingerSpec {
        shape,
        mu: 0.8,
        k: 2.0,
        c: 2.5e-3,
        gamma: 0.5,
        half_length_m: 0.01,
        skew: None,
    };
    FlsRig::new(spec, 2.0, 2.0).unwrap()
}

#[test]
fn the_fls_plant_neither_ratchets_nor_creeps() {
    for shape in [FingerShape::Rect, FingerShape::Disc] {
        let rig = fls(shape);
        // Without noise the shares are exactly 1: every fraction up to the onset holds.
        let (cp, hp) = plans();
        let rows = cyclic::cyclic(&rig, &cp, &mut Noise::none());
        let Measured::Fitted(c) = fit_cyclic("c", &rows).unwrap() else {
            panic!("not fitted")
        };
        assert_eq!((c.share.value, ci(&c.share)), (1.0, [1.0, 1.0]));
        assert_eq!(c.cyclic_factor.value, 1.0);
        let rows = hold::hold(&rig, &hp, &mut Noise::none());
        let Measured::Fitted(h) = fit_hold("h", &rows, shape).unwrap() else {
            panic!("not fitted")
        };
        assert_eq!((h.force_share.value, h.torsion_share.value), (1.0, 1.0));
        assert_eq!(h.least_safety_steady.value, 1.0);
        // With 2 % noise the fractions are of a measured onset, so the largest may slide:
        // 1 stays within every interval.
        for seed in 1..=10 {
            let m = measure(&rig, shape, seed);
            for (name, e, one) in [
                ("cyclic force share", &m.cyclic.force_share, 1.0),
                ("cyclic torsion share", &m.cyclic.torsion_share, 1.0),
                ("cyclic_factor", &m.cyclic.cyclic_factor, 1.0),
                ("hold force share", &m.hold.force_share, 1.0),
                ("hold torsion share", &m.hold.torsion_share, 1.0),
                ("least safety·steady", &m.hold.least_safety_steady, 1.0),
            ] {
                assert!(contains(e, one), "{shape:?} seed {seed}: {name} {e:?}");
            }
            if shape == FingerShape::Disc {
                let d = &m.hold.disc_torsion_factor;
                assert!(contains(d, 1.0), "seed {seed}: disc_torsion_factor {d:?}");
            }
        }
    }
}

/// A brush finger of docs/calibration.md: its name, `[finger]` TOML and shape.
struct BrushCase {
    name: &'static str,
    toml: String,
    shape: FingerShape,
}

fn brush_cases() -> Vec<BrushCase> {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/brush_lift_hold.toml");
    vec![
        BrushCase {
            name: "soft hemicylinder (brush_lift_hold.toml)",
            toml: std::fs::read_to_string(scene).unwrap(),
            shape: FingerShape::Rect,
        },
        BrushCase {
            name: "stiff hemicylinder",
            toml: "[finger]\nmodel = \"brush\"\nshape = \"rect\"\nmu = 0.6\n\
                   half_length_m = 0.008\nyoung_modulus_pa = 2e6\n[finger.brush]\n\
                   radius_m = 0.008\nlayer_thickness_m = 0.002\nstiffening_exponent = 1.5\n\
                   mu_kinetic = 0.55\nheight_m = 0.002\n"
                .into(),
            shape: FingerShape::Rect,
        },
        BrushCase {
            name: "hemisphere",
            toml: "[finger]\nmodel = \"brush\"\nshape = \"disc\"\nmu = 1.0\n\
                   young_modulus_pa = 5e5\n[finger.brush]\nradius_m = 0.009\n\
                   layer_thickness_m = 0.003\nmu_kinetic = 0.9\nheight_m = 0.003\n"
                .into(),
            shape: FingerShape::Disc,
        },
    ]
}

fn brush(toml_text: &str) -> host_sim::brush::BrushFinger {
    #[derive(serde::Deserialize)]
    struct File {
        finger: Finger,
    }
    let f: File = toml::from_str(toml_text).unwrap();
    f.finger.brush_finger().unwrap().unwrap()
}

/// `v [lo, hi]` to 2 decimals.
fn cell(e: &Estimate) -> String {
    if !e.identified {
        return "–".into();
    }
    let [lo, hi] = ci(e);
    format!("{:.2} [{lo:.2}, {hi:.2}]", e.value)
}

fn render(rows: &[(&str, &Measured2)]) -> String {
    let mut t = String::from(
        "<!-- margins:begin (generated by host-sim/tests/margin_protocols.rs; \
         SOFTGRIP_WRITE_DOCS=1 rewrites it) -->\n",
    );
    t += "| finger | cyclic share `r`: force, torsion | `cyclic_factor` | hold share \
          `h_t`, `h_m` | `disc_torsion_factor` | least `safety·steady_factor` |\n";
    t += "| --- | --- | --- | --- | --- | --- |\n";
    for (name, m) in rows {
        t += &format!(
            "| {name} | {}; {} | {} | {}; {} | {} | {} |\n",
            cell(&m.cyclic.force_share),
            cell(&m.cyclic.torsion_share),
            cell(&m.cyclic.cyclic_factor),
            cell(&m.hold.force_share),
            cell(&m.hold.torsion_share),
            cell(&m.hold.disc_torsion_factor),
            cell(&m.hold.least_safety_steady),
        );
    }
    t + "<!-- margins:end -->"
}

#[test]
fn on_the_brush_fingers_the_cyclic_share_is_below_one() {
    let cases = brush_cases();
    let measured: Vec<Measured2> = std::thread::scope(|s| {
        let runs: Vec<_> = cases
            .iter()
            .map(|c| s.spawn(|| measure(&brush(&c.toml), c.shape, 1)))
            .collect();
        runs.into_iter().map(|r| r.join().unwrap()).collect()
    });
    for (c, m) in cases.iter().zip(&measured) {
        println!(
            "{}: cyclic {:?} (wall {:.2?}), hold {:?} (wall {:.2?})",
            c.name, m.cyclic, m.wall.0, m.hold, m.wall.1
        );
        // It ratchets below its static onset: the share's whole interval is below 1.
        let [_, hi] = ci(&m.cyclic.share);
        assert!(hi < 1.0, "{}: cyclic share {:?}", c.name, m.cyclic.share);
        assert!(m.cyclic.cyclic_factor.value > 1.0, "{}", c.name);
    }
    // The hemisphere's rim turns under a sustained moment that its tangential force holds
    // at a larger share: its moment needs more than 1.
    let sphere = &measured[2].hold.disc_torsion_factor;
    assert!(ci(sphere)[0] > 1.0, "hemisphere: {sphere:?}");
    let rows: Vec<(&str, &Measured2)> = cases.iter().map(|c| c.name).zip(&measured).collect();
    let table = render(&rows);
    println!("{table}");
    common::check_block(
        "docs/calibration.md",
        ("<!-- margins:begin", "<!-- margins:end -->"),
        &table,
        "host-sim/tests/margin_protocols.rs",
    )
    .unwrap();
}

#[test]
fn the_rows_are_the_same_for_a_seed() {
    let (mut cp, mut hp) = plans();
    cp.frame.fractions = vec![0.8, 0.9];
    cp.cycles = 3;
    hp.frame.fractions = vec![0.9, 1.0];
    let cases = brush_cases();
    let finger = brush(&cases[0].toml);
    let rigs: [&dyn TimedRig; 2] = [&fls(FingerShape::Rect), &finger];
    for rig in rigs {
        let run = |seed| {
            let noise = || Noise::new(0.02, 0.01, 1e-5, 0.0, seed);
            (
                write_cyclic(&cyclic::cyclic(rig, &cp, &mut noise())),
                write_hold(&hold::hold(rig, &hp, &mut noise())),
            )
        };
        assert_eq!(run(4), run(4));
        assert_ne!(run(4), run(5));
    }
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-margins-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str]) -> String {
    let (code, out, err) = common::host_sim(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    out
}

#[test]
fn calibrate_without_the_margin_files_says_not_measured() {
    // `all` writes what it wrote before the margin protocols, and no margin file.
    let all = dir("all");
    run(&["experiment", "all", "--out", all.to_str().unwrap()]);
    let mut files: Vec<String> = std::fs::read_dir(&all)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(
        files,
        ["indentation.csv", "indentation.svg", "slip.csv", "slip.svg"]
    );
    let d = dir("cli");
    let out = d.to_str().unwrap();
    let base = ["--noise", "0.02", "--seed", "2", "--out", out];
    for kind in ["all", "cyclic", "hold"] {
        run(&[&["experiment", kind][..], &base].concat());
    }
    let (ind, slip) = (d.join("indentation.csv"), d.join("slip.csv"));
    let lab = [
        "calibrate",
        "--indentation",
        ind.to_str().unwrap(),
        "--slip",
    ];
    let lab = [&lab[..], &[slip.to_str().unwrap()]].concat();
    let toml = d.join("finger.toml");
    let text = run(&[&lab[..], &["--out", toml.to_str().unwrap()]].concat());
    for kind in ["cyclic", "hold"] {
        let said = format!("not measured: run `host-sim experiment {kind}`");
        assert!(text.contains(&said), "{text}");
        let file = std::fs::read_to_string(&toml).unwrap();
        assert!(file.contains(&said), "{file}");
        assert!(!file.contains("[margins]\n"), "{file}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&run(&[&lab[..], &["--format", "json"]].concat())).unwrap();
    assert_eq!(json["margins"]["cyclic"]["measured"], false, "{json}");
    assert_eq!(json["margins"]["hold"]["measured"], false, "{json}");
    // With them the TOML has a [margins] table the commands and the scene format read.
    let (cy, ho) = (d.join("cyclic.csv"), d.join("hold.csv"));
    let margins = [
        "--cyclic",
        cy.to_str().unwrap(),
        "--hold",
        ho.to_str().unwrap(),
    ];
    let out = [&lab[..], &margins, &["--out", toml.to_str().unwrap()]].concat();
    let text = run(&out);
    assert!(!text.contains("not measured"), "{text}");
    let file = std::fs::read_to_string(&toml).unwrap();
    assert!(file.contains("\n[margins]\ncyclic_factor = "), "{file}");
    let scene = format!("duration_s = 1.0\n{file}\n[object]\nmass_kg = 0.1\n");
    let scene = host_sim::sim::scene::Scene::parse(&scene).unwrap();
    assert!(scene.controller.config.contains_key("cyclic_factor"));
    run(&[
        "required-force",
        "--finger",
        toml.to_str().unwrap(),
        "--ft",
        "1",
        "--mn",
        "0",
    ]);
}
