//! The fits against closed forms: exact data (onsets on the core's exact surface,
//! indentations on the exact law) give the exact parameters; and the identifiability
//! rules and row minimums.

use softgrip::controller::FingerShape;
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};
use softgrip_calibrate::lab_csv::{Indentation, SlipOnset};
use softgrip_calibrate::{calibrate, CalibError, Calibration, Setup};

struct Truth {
    mu: f64,
    k: f64,
    c: f64,
    gamma: f64,
    l: f64,
    skew: Option<(f64, f64, f64)>,
}

const FORCES: [f64; 5] = [0.5, 1.0, 2.0, 4.0, 8.0];

fn indentations(t: &Truth) -> Vec<Indentation> {
    FORCES
        .iter()
        .map(|&n| Indentation {
            normal_force_n: n,
            half_width_m: t.c * n.powf(t.gamma),
        })
        .collect()
}

/// Onsets on the exact surface: pure force, pure torsion, and mixed at `d_c/a` in `ds`.
fn onsets(t: &Truth, shape: FingerShape, ds: &[f64]) -> Vec<SlipOnset> {
    let mut out = Vec::new();
    for &n in &FORCES {
        let a = t.c * n.powf(t.gamma);
        let model = FlsModel::<f64>::new(FlsConfig {
            shape: match shape {
                FingerShape::Rect => Shape::Rect { aspect: t.l / a },
                FingerShape::Disc => Shape::Disc,
            },
            k: t.k,
            skew: t.skew,
            order: QuadratureOrder::DEFAULT,
        })
        .unwrap();
        let onset = |f: f64, m: f64| SlipOnset {
            normal_force_n: n,
            tangential_force_n: t.mu * n * f,
            torsional_moment_nm: t.mu * n * a * m,
        };
        out.push(onset(1.0, 0.0));
        out.push(onset(0.0, model.pitch()));
        for &d in ds {
            let p = model.point(d);
            out.push(onset(p.f, p.m));
        }
    }
    out
}

const TRUTH: Truth = Truth {
    mu: 0.8,
    k: 3.0,
    c: 2.5e-3,
    gamma: 0.45,
    l: 0.01,
    skew: None,
};

fn setup(shape: FingerShape) -> Setup {
    Setup {
        shape,
        half_length_m: 0.01,
    }
}

/// The calibration of `TRUTH`'s exact indentations and `slip`.
fn fit_truth(shape: FingerShape, slip: &[SlipOnset]) -> Calibration {
    calibrate(
        &setup(shape),
        "ind.csv",
        &indentations(&TRUTH),
        "slip.csv",
        slip,
    )
    .unwrap()
}

#[test]
fn exact_data_give_the_exact_parameters() {
    for shape in FingerShape::ALL {
        let cal = fit_truth(shape, &onsets(&TRUTH, shape, &[0.3, 1.0]));
        let rel = |v: f64, t: f64| (v / t - 1.0).abs();
        assert!(
            rel(cal.c.value, TRUTH.c) < 1e-8,
            "{shape:?} c {}",
            cal.c.value
        );
        assert!(
            (cal.gamma.value - TRUTH.gamma).abs() < 1e-8,
            "{shape:?} {}",
            cal.gamma.value
        );
        assert!(
            rel(cal.mu.value, TRUTH.mu) < 2e-4,
            "{shape:?} mu {}",
            cal.mu.value
        );
        assert!(
            rel(cal.k.value, TRUTH.k) < 0.02,
            "{shape:?} k {}",
            cal.k.value
        );
        assert!(cal.mu.identified && cal.k.identified && cal.gamma.identified);
        // The exact surface has no skew: the fit finds none.
        assert!(
            cal.skewed_pressure.delta_over_a.value < 0.2,
            "{:?}",
            cal.skewed_pressure
        );
    }
}

#[test]
fn a_strong_skew_is_identified_from_exact_onsets() {
    let truth = Truth {
        k: 1.25,
        skew: Some((0.9, 1.1, 0.45)),
        ..TRUTH
    };
    let ds = [0.2, 0.4, 0.7, 1.0, 1.5];
    let cal = calibrate(
        &setup(FingerShape::Rect),
        "ind.csv",
        &indentations(&truth),
        "slip.csv",
        &onsets(&truth, FingerShape::Rect, &ds),
    )
    .unwrap();
    let d = &cal.skewed_pressure.delta_over_a;
    assert!(d.identified && (d.value - 0.9).abs() < 0.05, "{d:?}");
    assert!((cal.k.value / 1.25 - 1.0).abs() < 0.03, "{:?}", cal.k);
}

#[test]
fn what_the_data_cannot_identify_is_held_conservatively() {
    // No moment: k held at 2. One force: gamma held at 0.
    let slip: Vec<SlipOnset> = onsets(&TRUTH, FingerShape::Rect, &[])
        .into_iter()
        .filter(|o| o.torsional_moment_nm == 0.0)
        .collect();
    let one_force: Vec<Indentation> = vec![indentations(&TRUTH)[2]; 4];
    let cal = calibrate(&setup(FingerShape::Rect), "i", &one_force, "s", &slip).unwrap();
    assert!(!cal.k.identified && cal.k.value == 2.0, "{:?}", cal.k);
    assert!(cal
        .k
        .reason
        .as_deref()
        .unwrap()
        .contains("kept at 2 (conservative"));
    assert!(!cal.gamma.identified && cal.gamma.value == 0.0);
    assert!(!cal.skewed_pressure.delta_over_a.identified);
    assert_eq!(cal.skewed_pressure.delta_over_a.value, 0.0);
    assert!((cal.mu.value / 0.8 - 1.0).abs() < 1e-9);
}

#[test]
fn too_few_rows_are_refused_with_the_minimum() {
    let ind = indentations(&TRUTH);
    let slip = onsets(&TRUTH, FingerShape::Rect, &[]);
    let e = calibrate(
        &setup(FingerShape::Rect),
        "ind.csv",
        &ind[..2],
        "slip.csv",
        &slip,
    );
    let msg = e.unwrap_err().to_string();
    assert!(
        msg.starts_with("ind.csv: indentation needs at least 3 rows"),
        "{msg}"
    );
    let torsion: Vec<SlipOnset> = slip
        .iter()
        .copied()
        .filter(|o| o.tangential_force_n == 0.0)
        .collect();
    let e = calibrate(
        &setup(FingerShape::Rect),
        "ind.csv",
        &ind,
        "slip.csv",
        &torsion,
    );
    assert!(matches!(e, Err(CalibError::TooFew { .. })));
    assert!(e
        .unwrap_err()
        .to_string()
        .contains("at least 3 onsets with a tangential force"));
}

/// On exact data of a finger the model describes, the friction contact changes nothing
/// the data pin: `μ` is the pure-force onsets' (exact), the refit moves `c` (not the
/// half-length) and finds the indentation's within the tabulated surface's
/// interpolation; `k`, `γ` stay; its conservative values are the joint fit's.
#[test]
fn on_exact_data_the_friction_contact_is_the_joint_fit() {
    use softgrip_calibrate::friction_contact::Refit;
    for shape in FingerShape::ALL {
        let slip = onsets(&TRUTH, shape, &[0.3, 1.0]);
        let joint = fit_truth(shape, &slip);
        let fc = joint.with_friction_contact("slip.csv", &slip).unwrap();
        let note = fc.friction_contact.as_ref().unwrap();
        assert_eq!(note.refit, Refit::Scale, "{shape:?}");
        let rel = |v: f64, t: f64| (v / t - 1.0).abs();
        assert!(
            rel(fc.mu.value, TRUTH.mu) < 1e-12,
            "{shape:?} mu {}",
            fc.mu.value
        );
        assert!(
            rel(fc.c.value, TRUTH.c) < 0.01,
            "{shape:?} c {}",
            fc.c.value
        );
        assert_eq!(fc.half_length_m, 0.01);
        assert_eq!(
            (fc.k.value, fc.gamma.value),
            (joint.k.value, joint.gamma.value)
        );
        assert_eq!(note.joint_mu.value, joint.mu.value);
        assert_eq!(fc.conservative(), joint.conservative());
        assert_eq!(fc.joint(), joint);
        // Refitting again starts from the joint fit: the same values.
        assert_eq!(fc.with_friction_contact("slip.csv", &slip).unwrap(), fc);
        // Conservative values are not refitted.
        assert!(joint
            .conservative()
            .with_friction_contact("s", &slip)
            .is_err());
    }
}

/// Without two pure-force onsets there is no slip-test `μ`: refused, naming the file
/// and the minimum.
#[test]
fn the_friction_contact_needs_two_pure_force_onsets() {
    let slip: Vec<SlipOnset> = onsets(&TRUTH, FingerShape::Rect, &[0.3, 1.0])
        .into_iter()
        .filter(|o| !(o.torsional_moment_nm == 0.0))
        .collect();
    let joint = fit_truth(FingerShape::Rect, &slip);
    let e = joint.with_friction_contact("slip.csv", &slip).unwrap_err();
    let msg = e.to_string();
    assert!(
        msg.starts_with("slip.csv:") && msg.contains("at least 2 pure-force"),
        "{msg}"
    );
}
