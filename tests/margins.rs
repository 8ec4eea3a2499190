//! The margins are configuration (`ControllerConfig`'s margin fields, docs/controller.md,
//! "Margins"): each is validated by name, its default is the named constant it replaced,
//! each changes the tick as its documentation says, and every tick reports the parts of
//! its command (`margin = slip_margin · load_factor`, `lead_n ≥ 0`).

use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, Measurement, SlipSignal, TickOutput,
    CREEP_MARGIN_MAX, CYCLIC_SAFETY_FACTOR, DISC_TORSION_SAFETY_FACTOR, MARGIN_MAX,
    MARGIN_STEP_GROSS, MARGIN_STEP_INCIPIENT, MU_FLOOR_FRACTION, STEADY_RAMP_S,
    STEADY_SAFETY_FACTOR, UNTOLD_LAG_S,
};
use std::f64::consts::TAU;

const BASE: ControllerConfig = ControllerConfig::DEFAULT;

#[test]
fn the_defaults_are_the_named_constants() {
    let d = BASE;
    assert_eq!(d.disc_torsion_factor, DISC_TORSION_SAFETY_FACTOR);
    assert_eq!(d.cyclic_factor, CYCLIC_SAFETY_FACTOR);
    assert_eq!(d.steady_factor, STEADY_SAFETY_FACTOR);
    assert_eq!(d.steady_ramp_s, STEADY_RAMP_S);
    assert_eq!(d.slip_step_incipient, MARGIN_STEP_INCIPIENT);
    assert_eq!(d.slip_step_gross, MARGIN_STEP_GROSS);
    assert_eq!(d.slip_margin_max, MARGIN_MAX);
    assert_eq!(d.creep_margin_max, CREEP_MARGIN_MAX);
    assert_eq!(d.mu_floor_fraction, MU_FLOOR_FRACTION);
    assert_eq!(d.untold_lag_s, UNTOLD_LAG_S);
}

/// `BASE` with one margin field set, by name.
fn with(field: &str, v: f64) -> ControllerConfig {
    let mut c = BASE;
    match field {
        "disc_torsion_factor" => c.disc_torsion_factor = v,
        "cyclic_factor" => c.cyclic_factor = v,
        "steady_factor" => c.steady_factor = v,
        "steady_ramp_s" => c.steady_ramp_s = v,
        "slip_step_incipient" => c.slip_step_incipient = v,
        "slip_step_gross" => c.slip_step_gross = v,
        "slip_margin_max" => c.slip_margin_max = v,
        "creep_margin_max" => c.creep_margin_max = v,
        "mu_floor_fraction" => c.mu_floor_fraction = v,
        "untold_lag_s" => c.untold_lag_s = v,
        other => panic!("{other}"),
    }
    c
}

#[test]
fn every_bad_margin_is_refused_by_name_and_its_edges_are_taken() {
    let nan = f64::NAN;
    let inf = f64::INFINITY;
    let bad: [(&str, &[f64]); 10] = [
        ("disc_torsion_factor", &[0.99, 0.0, -1.0, nan, inf]),
        ("cyclic_factor", &[0.5, nan, inf]),
        ("steady_factor", &[0.0, -0.1, 1.01, nan]),
        ("steady_ramp_s", &[-1e-3, nan, inf]),
        ("slip_step_incipient", &[-0.01, nan, inf]),
        ("slip_step_gross", &[-0.01, nan]),
        ("slip_margin_max", &[0.9, nan, inf]),
        ("creep_margin_max", &[0.9, 3.5, nan]),
        ("mu_floor_fraction", &[0.0, 1.5, nan]),
        ("untold_lag_s", &[-1e-3, 1.01, nan]),
    ];
    for (field, values) in bad {
        for &v in values {
            let e = with(field, v).validate().expect_err(field);
            assert_eq!(e.param(), field, "{field} = {v}: {e}");
        }
    }
    let good: [(&str, &[f64]); 10] = [
        ("disc_torsion_factor", &[1.0, 3.0]),
        ("cyclic_factor", &[1.0, 2.0]),
        ("steady_factor", &[1.0, 0.5]),
        ("steady_ramp_s", &[0.0, 2.0]),
        ("slip_step_incipient", &[0.0]),
        ("slip_step_gross", &[0.0, 1.0]),
        ("slip_margin_max", &[1.1, 10.0]),
        ("creep_margin_max", &[1.0, 3.0]),
        ("mu_floor_fraction", &[1.0, 0.1]),
        ("untold_lag_s", &[0.0, 1.0]),
    ];
    for (field, values) in good {
        for &v in values {
            assert!(with(field, v).validate().is_ok(), "{field} = {v}");
            assert!(
                Controller::<f32>::new(with(field, v)).is_ok(),
                "{field} = {v}"
            );
        }
    }
}

/// Runs `seconds` of `load(t) = (f_t [N], m_n [N·m])` at 1 kHz, the normal force
/// following the command (an ideal actuator), with `slip(t)` as the sensor's signal.
fn run(
    cfg: ControllerConfig,
    seconds: f64,
    load: impl Fn(f64) -> (f64, f64),
    slip: impl Fn(f64) -> SlipSignal,
) -> Vec<TickOutput<f64>> {
    let mut c = Controller::<f64>::new(cfg).unwrap();
    let mut force = cfg.n_min_n;
    (0..(seconds * 1e3) as u64)
        .map(|k| {
            let t = k as f64 * 1e-3;
            let (ft, mn) = load(t);
            let o = c.tick(&Measurement {
                tangential_force_n: [0.0, ft],
                torsional_moment_nm: mn,
                normal_force_n: force,
                timestamp_us: 1000 * (k + 1),
                slip: slip(t),
            });
            force = o.command_n;
            o
        })
        .collect()
}

fn no_slip(_: f64) -> SlipSignal {
    SlipSignal::None
}

/// A 4 Hz shake of the tangential load between 0.5 and 1.5 N after a lift.
fn shake(t: f64) -> (f64, f64) {
    (1.0 + 0.5 * (TAU * 4.0 * t).sin(), 0.0)
}

fn max_load_factor(ticks: &[TickOutput<f64>]) -> f64 {
    ticks.iter().map(|o| o.load_factor).fold(0.0, f64::max)
}

#[test]
fn the_cyclic_factor_is_what_a_shake_gets() {
    let default = run(BASE, 3.0, shake, no_slip);
    assert_eq!(max_load_factor(&default), CYCLIC_SAFETY_FACTOR);
    for factor in [1.0, 1.2, 2.0] {
        let ticks = run(with("cyclic_factor", factor), 3.0, shake, no_slip);
        assert_eq!(max_load_factor(&ticks), factor, "cyclic_factor {factor}");
    }
}

#[test]
fn the_steady_factor_and_ramp_are_what_a_hold_gets() {
    let hold = |_t: f64| (1.0, 0.0);
    let least = |ticks: &[TickOutput<f64>]| ticks.iter().map(|o| o.load_factor).fold(9.0, f64::min);
    assert_eq!(least(&run(BASE, 2.0, hold, no_slip)), STEADY_SAFETY_FACTOR);
    assert_eq!(
        least(&run(with("steady_factor", 1.0), 2.0, hold, no_slip)),
        1.0
    );
    assert_eq!(
        least(&run(with("steady_factor", 0.9), 2.0, hold, no_slip)),
        0.9
    );
    // The ramp: at 0.3 s + 0.25 s the default (0.5 s) is half-way; a 0.1 s ramp is done.
    let at = |ticks: &[TickOutput<f64>], t_s: f64| ticks[(t_s * 1e3) as usize].load_factor;
    let half = at(&run(BASE, 1.0, hold, no_slip), 0.56);
    assert!(half > STEADY_SAFETY_FACTOR && half < 1.0, "{half}");
    let quick = at(&run(with("steady_ramp_s", 0.1), 1.0, hold, no_slip), 0.56);
    assert_eq!(quick, STEADY_SAFETY_FACTOR);
}

#[test]
fn the_disc_torsion_factor_scales_only_a_round_patchs_moment() {
    let disc = |factor: f64| ControllerConfig {
        shape: FingerShape::Disc,
        disc_torsion_factor: factor,
        ..BASE
    };
    let (f, m) = (1.0, 0.004);
    for factor in [1.0, 1.5, 2.0] {
        let c = Controller::<f64>::new(disc(factor)).unwrap();
        let tick = c.tick_required_force(f, m, 1.35).unwrap().force_n;
        let model = c.required_force(f, factor * m, 1.35).unwrap().force_n;
        assert_eq!(tick, model, "factor {factor}");
    }
    let plain = Controller::<f64>::new(disc(1.0)).unwrap();
    assert_eq!(
        plain.tick_required_force(f, m, 1.35).unwrap().force_n,
        plain.required_force(f, m, 1.35).unwrap().force_n
    );
    // A hemicylinder's moment carries no factor, whatever the field says.
    let rect = Controller::<f64>::new(with("disc_torsion_factor", 3.0)).unwrap();
    assert_eq!(
        rect.tick_required_force(f, m, 1.35).unwrap().force_n,
        rect.required_force(f, m, 1.35).unwrap().force_n
    );
}

/// A lift: the tangential load rises from 0 to 2 N over 0.1 s from t = 0.2 s.
fn lift(t: f64) -> (f64, f64) {
    (2.0 * ((t - 0.2) / 0.1).clamp(0.0, 1.0), 0.0)
}

#[test]
fn an_untold_actuator_is_led_by_untold_lag_s() {
    let most_lead = |cfg| {
        run(cfg, 0.6, lift, no_slip)
            .iter()
            .map(|o| o.lead_n)
            .fold(0.0, f64::max)
    };
    let default = most_lead(BASE);
    let none = most_lead(with("untold_lag_s", 0.0));
    let longer = most_lead(with("untold_lag_s", 0.08));
    assert!(default > 0.0, "{default}");
    assert_eq!(none, 0.0);
    assert!(longer > default, "{longer} vs {default}");
}

#[test]
fn the_slip_steps_caps_and_mu_floor_are_the_configured_ones() {
    let hold = |_t: f64| (1.0, 0.0);
    // Gross slips every 50 ms from 0.1 s: each adds the step until the cap.
    let gross = |t: f64| {
        if t > 0.1 && ((t * 1e3) as u64).is_multiple_of(50) {
            SlipSignal::Gross
        } else {
            SlipSignal::None
        }
    };
    let first = |cfg| {
        let ticks = run(cfg, 0.2, hold, gross);
        ticks.iter().map(|o| o.slip_margin).fold(0.0, f64::max)
    };
    assert_eq!(first(with("slip_step_gross", 0.5)), 1.5);
    let most = |cfg| {
        run(cfg, 2.0, hold, gross)
            .iter()
            .map(|o| o.slip_margin)
            .fold(0.0, f64::max)
    };
    assert_eq!(most(BASE), MARGIN_MAX);
    assert_eq!(most(with("slip_margin_max", 1.6)), 1.6);
    let least_mu = |cfg: ControllerConfig| {
        run(cfg, 2.0, hold, gross)
            .iter()
            .map(|o| o.mu_estimate / cfg.mu)
            .fold(9.0, f64::min)
    };
    assert!(least_mu(BASE) >= MU_FLOOR_FRACTION - 1e-12);
    assert!(least_mu(with("mu_floor_fraction", 0.9)) >= 0.9 - 1e-12);
}

#[test]
fn every_tick_reports_the_parts_of_its_command() {
    let gross = |t: f64| {
        if (1.0..1.01).contains(&t) {
            SlipSignal::Gross
        } else {
            SlipSignal::None
        }
    };
    let load = |t: f64| if t < 1.5 { lift(t) } else { shake(t) };
    for cfg in [BASE, with("cyclic_factor", 1.0), with("untold_lag_s", 0.0)] {
        for o in run(cfg, 3.0, load, gross) {
            assert_eq!(o.margin, o.slip_margin * o.load_factor);
            assert!(o.lead_n >= 0.0 && o.lead_n.is_finite(), "{o:?}");
            assert!(o.slip_margin >= 1.0 && o.slip_margin <= cfg.slip_margin_max);
            assert!(o.load_factor >= cfg.steady_factor && o.load_factor <= cfg.cyclic_factor);
            assert!(o.required_n >= o.n_slip_n, "{o:?}");
        }
    }
}
