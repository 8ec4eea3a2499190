//! A tactile sensor that fires on creep (`controller::slip`, "Creep is not slip"): a
//! persistent incipient report at a moderate load raises the margin a little and never
//! moves μ̂, while a report at a load near the limit, or a gross slip, still gets the
//! full response.

use softgrip::controller::slip::CREEP_UTILISATION;
use softgrip::controller::{
    Controller, ControllerConfig, Measurement, Mode, SlipSignal, CREEP_MARGIN_MAX,
    MARGIN_STEP_GROSS,
};

fn frame(k: u64, f: f64, n: f64, slip: SlipSignal) -> Measurement<f64> {
    Measurement {
        tangential_force_n: [0.0, f],
        torsional_moment_nm: 0.0,
        normal_force_n: n,
        timestamp_us: 1000 * (k + 1),
        slip,
    }
}

/// Table mode: the exact surface, on which a pure force `f` at grip `N` has utilisation
/// `f/(μN)`.
fn config() -> ControllerConfig {
    ControllerConfig {
        mode: Mode::Table,
        ..ControllerConfig::default()
    }
}

/// Holds a load of utilisation `u` (under the configured μ, at 5 N of grip) for
/// `seconds` with the sensor reporting `slip` throughout; returns the last output.
fn hold(u: f64, seconds: f64, slip: SlipSignal) -> softgrip::controller::TickOutput<f64> {
    let cfg = config();
    let mut c = Controller::<f64>::new(cfg).unwrap();
    let f = u * cfg.mu * 5.0;
    let got = c.utilisation(f, 0.0, 5.0).unwrap();
    assert!((got / u - 1.0).abs() < 3e-3, "{got} {u}");
    let mut out = c.tick(&frame(0, f, 5.0, SlipSignal::None));
    for k in 1..(seconds * 1000.0) as u64 {
        out = c.tick(&frame(k, f, 5.0, slip));
        assert!(out.margin <= softgrip::controller::MARGIN_MAX);
    }
    out
}

#[test]
fn creep_at_a_moderate_load_raises_the_margin_a_little_and_leaves_mu() {
    for u in [0.3, 0.5, 0.65] {
        assert!(u < CREEP_UTILISATION);
        let out = hold(u, 2.0, SlipSignal::Incipient);
        let cfg = config();
        eprintln!(
            "creep at utilisation {u}: margin {:.3}, mu {:.3}",
            out.margin, out.mu_estimate
        );
        assert!(
            out.margin > 1.0 && out.margin <= CREEP_MARGIN_MAX,
            "{out:?}"
        );
        assert_eq!(out.mu_estimate, cfg.mu);
        // The command: the load's need at the safety factor x the creep margin at most (table
        // mode's interpolation is good to a few per mille).
        let need = cfg.safety * CREEP_MARGIN_MAX * u * 5.0;
        assert!(out.command_n <= need * 1.005, "{} > {need}", out.command_n);
    }
}

#[test]
fn a_report_near_the_limit_or_a_gross_slip_still_teaches_mu() {
    let cfg = config();
    // Incipient at 0.9: the margin climbs past the creep cap and μ̂ falls.
    let out = hold(0.9, 0.5, SlipSignal::Incipient);
    assert!(out.margin > CREEP_MARGIN_MAX, "{out:?}");
    assert!(out.mu_estimate < cfg.mu, "{out:?}");
    // A gross slip at 0.95: one gross step at once and μ̂ at what the load implies.
    let mut c = Controller::<f64>::new(cfg).unwrap();
    let f = 0.95 * cfg.mu * 5.0;
    c.tick(&frame(0, f, 5.0, SlipSignal::None));
    let out = c.tick(&frame(1, f, 5.0, SlipSignal::Gross));
    assert_eq!(out.margin, 1.0 + MARGIN_STEP_GROSS);
    assert!(
        (out.mu_estimate / (0.95 * cfg.mu) - 1.0).abs() < 3e-3,
        "{out:?}"
    );
}

#[test]
fn creep_after_a_real_slip_lets_its_margin_relax_and_keeps_its_mu() {
    // A gross slip at utilisation 0.95 raises the margin to 1.3 and lowers μ̂ to 0.95 μ.
    // The load then settles at utilisation 0.5 under that belief, and the sensor reports
    // creep for 3 s. Creep is no slip: the margin relaxes to the creep cap (it used to stay
    // at 1.3 for as long as the creep did), and μ̂ keeps what the slip taught.
    let cfg = config();
    let mut c = Controller::<f64>::new(cfg).unwrap();
    let f = 0.95 * cfg.mu * 5.0;
    c.tick(&frame(0, f, 5.0, SlipSignal::None));
    let out = c.tick(&frame(1, f, 5.0, SlipSignal::Gross));
    assert_eq!(out.margin, 1.0 + MARGIN_STEP_GROSS);
    let mu_hat = out.mu_estimate;
    assert!(mu_hat < cfg.mu);
    let f = 0.5 * mu_hat * 5.0;
    let mut out = out;
    for k in 2..3002 {
        out = c.tick(&frame(k, f, 5.0, SlipSignal::Incipient));
        assert!(out.margin <= 1.0 + MARGIN_STEP_GROSS, "{out:?}");
        assert_eq!(out.mu_estimate, mu_hat, "tick {k}");
    }
    eprintln!(
        "creep for 3 s after a gross slip: margin {:.4}, mu {:.4}",
        out.margin, out.mu_estimate
    );
    assert!(
        out.margin <= CREEP_MARGIN_MAX + 1e-3 && out.margin >= 1.0,
        "{out:?}"
    );
    // The command: the load's need at the safety factor x the creep margin, under μ̂.
    let need = cfg.safety * CREEP_MARGIN_MAX * f / mu_hat;
    assert!(out.command_n <= need * 1.005, "{} > {need}", out.command_n);
}
