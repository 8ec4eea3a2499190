//! The brush plant's numbers, bit for bit: a digest of every report and pose the plant
//! gives over a fixed input sequence (a squeeze, a lift with a wobble, an unloaded spell, a
//! non-finite input, a twist that slips), and of the lab functions (slip onsets, full-slip
//! limits, indentation), on five fingers: the shipped scene's, a soft stiffening
//! hemicylinder (E 0.12 MPa, n 1.8), a bench-like stiff hemisphere, a light object on a
//! small hemicylinder (several sub-steps a tick) and a friction gradient. The digests are
//! the ones the plant gave at 0eb85c7, before its step was made faster
//! (docs/brush-finger.md, "Cost"): a change that only makes the plant faster keeps
//! them; one that moves its numbers, on purpose, updates them and says why. The plant
//! takes `powf` and `hypot` from the system's libm, so on another libm the digests, like
//! the bench's own numbers, may differ.

use host_sim::brush::{BrushFinger, BrushParams, BrushSettings, BrushShape};

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// FNV-1a over 64-bit words.
fn fold(h: &mut u64, words: &[u64]) {
    for w in words {
        for b in w.to_le_bytes() {
            *h = (*h ^ u64::from(b)).wrapping_mul(FNV_PRIME);
        }
    }
}

/// A finger and the object it holds.
struct Finger {
    name: &'static str,
    shape: BrushShape,
    /// `(μ, half-length [m], E [Pa])`.
    shared: (f64, f64, f64),
    settings: BrushSettings,
    /// `(mass [kg], inertia [kg·m²])`.
    object: (f64, f64),
}

/// The fingers.
fn fingers() -> Vec<Finger> {
    let shipped = BrushSettings {
        mu_kinetic: Some(0.7),
        height_m: Some(0.003),
        ..BrushSettings::default()
    };
    let soft = BrushSettings {
        stiffening_exponent: 1.8,
        ..shipped.clone()
    };
    let disc = BrushSettings {
        radius_m: 0.0147,
        layer_thickness_m: 0.0037,
        stiffening_exponent: 1.63,
        mu_kinetic: Some(0.53),
        height_m: Some(0.011),
        elements: 16,
        ..BrushSettings::default()
    };
    let twist = BrushSettings {
        radius_m: 0.008,
        layer_thickness_m: 0.0024,
        stiffening_exponent: 1.24,
        mu_kinetic: Some(0.8),
        height_m: Some(0.004),
        elements: 16,
        ..BrushSettings::default()
    };
    let gradient = BrushSettings {
        stiffening_exponent: 1.4,
        mu_gradient_per_m: 60.0,
        elements: 15,
        ..shipped.clone()
    };
    use BrushShape::{Hemicylinder as Rect, Hemisphere as Disc};
    let f = |name, shape, shared, settings, object| Finger {
        name,
        shape,
        shared,
        settings,
        object,
    };
    vec![
        f("shipped", Rect, (0.8, 0.01, 3e5), shipped, (0.2, 1e-4)),
        f("soft", Rect, (0.8, 0.01, 1.2e5), soft, (0.2, 1e-4)),
        f("disc", Disc, (0.62, 0.01, 1.74e6), disc, (0.3, 2.7e-4)),
        f("twist", Rect, (0.95, 0.012, 7.4e5), twist, (0.05, 4.5e-5)),
        f("gradient", Rect, (0.8, 0.01, 3e5), gradient, (0.2, 1e-4)),
    ]
}

/// Tick `k`'s input `(normal [N], grasp force [N], grasp moment [N·m], dt [s])`: a
/// squeeze, a lift with a wobble, an unloaded spell, a bad input and a twist that slips.
fn input(k: usize, mass_kg: f64, moment_scale_nm: f64) -> (f64, [f64; 2], f64, f64) {
    let t = k as f64 * 1e-3;
    let wiggle = (0.37 * k as f64).sin();
    let normal = match k {
        900..=919 => 0.0,
        1000 => f64::NAN,
        _ => (t / 0.2).min(1.0) * (3.0 + 0.8 * (2.0 * t).sin()) + 0.02 * wiggle,
    };
    let accel = if (0.3..0.6).contains(&t) { 3.0 } else { 0.0 };
    let force = [0.05 * (3.0 * t).sin(), mass_kg * (9.81 + accel)];
    let twist = ((t - 1.1) / 0.3).clamp(0.0, 1.0);
    let moment = moment_scale_nm * (0.2 + 2.5 * twist) * (1.0 + 0.1 * wiggle);
    (normal, force, moment, 1e-3)
}

/// A finger's digests: `(run, lab)`.
fn digests(finger: &Finger) -> (u64, u64) {
    let (mu, half_length_m, young_pa) = finger.shared;
    let (mass_kg, inertia_kg_m2) = finger.object;
    let s = &finger.settings;
    let p = BrushParams::from_settings(finger.shape, mu, half_length_m, young_pa, 0.45, s);
    let f = BrushFinger::new(p).unwrap();
    let mut run = FNV_OFFSET;
    let mut plant = f.plant(mass_kg, inertia_kg_m2);
    for k in 0..1500 {
        let (n, force, moment, dt) = input(k, mass_kg, 0.01);
        let r = plant.step(n, force, moment, dt);
        let (q, c) = (plant.pose(), plant.contact());
        let words = [
            r.f_t_n[0],
            r.f_t_n[1],
            r.m_n_nm,
            r.normal_n,
            r.half_width_m,
            r.pressure_centre_y_m,
            r.stuck_fraction,
            r.slip_distance_m,
            r.slip_rotation_rad,
            q.ux_m,
            q.uy_m,
            q.theta_rad,
            c.stuck_fraction(),
        ];
        fold(&mut run, &words.map(f64::to_bits));
        fold(&mut run, &[u64::from(r.gross_slip), r.substeps as u64]);
        fold(&mut run, &[c.slip_pose().theta_rad.to_bits()]);
    }
    let mut lab = FNV_OFFSET;
    for n in [0.5, 2.0, 8.0] {
        let onset = f.slip_onset(n, 1.0, 0.0).map_or(0.0, |o| o.0);
        let twist = f.slip_onset(n, 0.0, 1e-3).map_or(0.0, |o| o.1);
        let both = f.slip_onset(n, 1.0, 0.01).map_or(0.0, |o| o.0);
        let (fl, ml) = f.full_slip_limits(n);
        let words = [
            onset,
            twist,
            both,
            fl,
            ml,
            f.indentation_half_width_m(n),
            f.indentation_m(n),
        ];
        fold(&mut lab, &words.map(f64::to_bits));
    }
    (run, lab)
}

/// Each finger's digests as the plant gave them at 0eb85c7.
const EXPECTED: [(&str, u64, u64); 5] = [
    ("shipped", 0x4fc1_60c8_4148_b331, 0x8645_0dba_5b4d_31f0),
    ("soft", 0xbec8_4b11_91c3_f76c, 0xc705_0da0_936e_914e),
    ("disc", 0xafd8_68a7_fc6d_a9f2, 0x901b_633f_1543_75ef),
    ("twist", 0x709b_155e_01b8_8d48, 0x70f3_4c39_9fa8_2074),
    ("gradient", 0x2f37_30a9_d727_70b3, 0xbd8a_69c1_6b0d_8fc9),
];

#[test]
fn the_plant_gives_the_same_bits_as_before_its_speed_up() {
    let mut wrong = Vec::new();
    for (finger, (name, run, lab)) in fingers().iter().zip(EXPECTED) {
        assert_eq!(finger.name, name);
        let got = digests(finger);
        eprintln!("{name}: run {:#018x}, lab {:#018x}", got.0, got.1);
        if got != (run, lab) {
            wrong.push(name);
        }
    }
    assert!(wrong.is_empty(), "the plant's numbers moved on {wrong:?}");
}
