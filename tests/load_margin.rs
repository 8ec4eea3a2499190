//! The load's margins (`controller::lead`, "Cyclic loads" and "Steady loads").
//!
//! A shake multiplies the safety factor by `CYCLIC_SAFETY_FACTOR` from its second trough
//! until twice `SWING_WINDOW_S` after its last, while a steady noisy hold, one lift, one
//! twist, a slow sway and a ripple within sensor noise never do. A load that stays within
//! a swing's depth for `STEADY_HOLD_S` multiplies it by a factor that falls linearly from
//! 1 to `STEADY_SAFETY_FACTOR` over `STEADY_RAMP_S`, until it falls past that depth or
//! rises by more than `STEADY_RISE_N`, and the force asked never falls below `N_slip`.

use softgrip::controller::lead::{CYCLE_DEPTH, STEADY_HOLD_S, STEADY_RISE_N, SWING_WINDOW_S};
use softgrip::controller::{
    Controller, ControllerConfig, Measurement, Mode, SlipSignal, CYCLIC_SAFETY_FACTOR,
    STEADY_RAMP_S, STEADY_SAFETY_FACTOR,
};
use std::f64::consts::TAU;

#[path = "common/noise.rs"]
mod noise;
use noise::Noise;

/// One tick's record: the time [s], the margin the tick reported, its `N_req` over
/// `N_req` of the true load at the configured safety factor, at that times
/// `CYCLIC_SAFETY_FACTOR` and at that times `STEADY_SAFETY_FACTOR` (floored at 1), and
/// its `N_req` over its `N_slip`.
struct Tick {
    t_s: f64,
    margin: f64,
    req_over_plain: f64,
    req_over_cyclic: f64,
    req_over_steady: f64,
    req_over_slip: f64,
}

/// The moment's noise [N·m]: the simulator's `sensor_noise` default.
const MOMENT_NOISE_NM: f64 = 2e-4;

/// Runs `seconds` of the load `load(t) = (f_t [N], m_n [N·m])` at 1 kHz, with `noise_n`
/// of noise on the force channels (and [`MOMENT_NOISE_NM`] on the moment), the
/// normal force following the command (an ideal actuator, measured).
fn run(
    cfg: ControllerConfig,
    seconds: f64,
    noise_n: f64,
    load: impl Fn(f64) -> (f64, f64),
) -> Vec<Tick> {
    let mut c = Controller::<f64>::new(cfg).unwrap();
    let mut noise = Noise(11);
    let mut force = cfg.n_min_n;
    let mut out = Vec::new();
    for k in 0..(seconds * 1e3) as u64 {
        let t = k as f64 * 1e-3;
        let (ft, mn) = load(t);
        let m = Measurement {
            tangential_force_n: [0.0, ft + noise_n * noise.normal()],
            torsional_moment_nm: mn + MOMENT_NOISE_NM * noise.normal(),
            normal_force_n: force + noise_n * noise.normal(),
            timestamp_us: 1000 * (k + 1),
            slip: SlipSignal::None,
        };
        let o = c.tick(&m);
        force = o.command_n;
        let plain = c.required_force(ft, mn, cfg.safety).unwrap().force_n;
        let cyclic = c
            .required_force(ft, mn, cfg.safety * CYCLIC_SAFETY_FACTOR)
            .unwrap()
            .force_n;
        let steady = c
            .required_force(ft, mn, (cfg.safety * STEADY_SAFETY_FACTOR).max(1.0))
            .unwrap()
            .force_n;
        out.push(Tick {
            t_s: t,
            margin: o.margin,
            req_over_plain: o.required_n / plain,
            req_over_cyclic: o.required_n / cyclic,
            req_over_steady: o.required_n / steady,
            req_over_slip: o.required_n / o.n_slip_n,
        });
    }
    out
}

/// The configurations tried: both modes, the actuator untold (led as a 20 ms lag) and
/// told ideal.
fn configs() -> Vec<ControllerConfig> {
    let mut v = Vec::new();
    for mode in [Mode::Ellipse, Mode::Table] {
        for lag in [0.0, 1e-3] {
            v.push(ControllerConfig {
                mode,
                actuator_lag_s: lag,
                ..ControllerConfig::default()
            });
        }
    }
    v
}

/// The largest margin of a run.
fn most_margin(ticks: &[Tick]) -> f64 {
    ticks.iter().map(|k| k.margin).fold(0.0, f64::max)
}

/// A weight of `w` N lifted with a peak acceleration of `a_over_g` g: the load rises as
/// the lift accelerates, falls below the weight as it decelerates (0.3 to 0.7 s), then
/// holds the weight.
fn lift(w: f64, a_over_g: f64, t: f64) -> f64 {
    let x = ((t - 0.3) / 0.4).clamp(0.0, 1.0);
    w * (1.0 + a_over_g * (TAU * x).sin())
}

#[test]
fn a_steady_noisy_hold_never_cycles() {
    for cfg in configs() {
        for (w, noise) in [(0.3, 0.05), (1.0, 0.02), (3.0, 0.05)] {
            let ticks = run(cfg, 3.0, noise, |_| (w, 0.002 * w));
            assert_eq!(most_margin(&ticks), 1.0, "{cfg:?}, {w} N, noise {noise} N");
        }
    }
}

#[test]
fn one_lift_never_cycles() {
    for cfg in configs() {
        for (w, a) in [(0.5, 0.1), (1.5, 0.3), (2.5, 0.5)] {
            let ticks = run(cfg, 2.5, 0.02, |t| (lift(w, a, t), 0.01 * lift(w, a, t)));
            assert_eq!(most_margin(&ticks), 1.0, "{cfg:?}, {w} N at {a} g");
        }
    }
}

#[test]
fn one_twist_never_cycles() {
    // A turn that accelerates, then decelerates: |m_n| rises, falls to 0 and rises again
    // once (one bottom), as the bench's twist family does.
    for cfg in configs() {
        for peak_nm in [0.005, 0.02] {
            let ticks = run(cfg, 2.0, 0.02, |t| {
                let x = ((t - 0.2) / 1.0).clamp(0.0, 1.0);
                (0.3, peak_nm * (TAU * x).sin())
            });
            assert_eq!(most_margin(&ticks), 1.0, "{cfg:?}, {peak_nm} N·m");
        }
    }
}

#[test]
fn a_slow_sway_and_a_ripple_within_noise_do_not_cycle() {
    for cfg in configs() {
        // 0.5 Hz: a second between a top and the next bottom, a sequence of steady loads.
        let sway = run(cfg, 6.0, 0.02, |t| (2.0 + 1.0 * (TAU * 0.5 * t).sin(), 0.0));
        assert_eq!(most_margin(&sway), 1.0, "{cfg:?}: sway");
        // 5 Hz at 0.02 N: as much as the noise.
        let ripple = run(cfg, 3.0, 0.02, |t| {
            (2.0 + 0.02 * (TAU * 5.0 * t).sin(), 0.0)
        });
        assert_eq!(most_margin(&ripple), 1.0, "{cfg:?}: ripple");
    }
}

#[test]
fn a_shake_cycles_from_its_second_trough_until_a_window_after_it() {
    let factor = CYCLIC_SAFETY_FACTOR;
    for cfg in configs() {
        for hz in [2.0, 4.0, 8.0, 15.0] {
            // A held weight of 1.5 N shaken by ±40 % from 0.5 s to 2.5 s.
            let ticks = run(cfg, 5.0, 0.02, |t| {
                let shaking = (0.5..2.5).contains(&t);
                let swing = if shaking {
                    0.4 * (TAU * hz * (t - 0.5)).sin()
                } else {
                    0.0
                };
                (1.5 * (1.0 + swing), 0.0)
            });
            let what = format!("{:?} lag {}, {hz} Hz", cfg.mode, cfg.actuator_lag_s);
            let first = ticks
                .iter()
                .find(|k| k.margin > 1.0)
                .unwrap_or_else(|| panic!("{what}: never cycled"));
            // The second trough is at 0.5 s + 1.75 periods; the filter and the turn's
            // depth delay it by under a quarter period more.
            let second_trough_s = 0.5 + 1.75 / hz;
            assert!(
                first.t_s > 0.5 + 0.75 / hz && first.t_s < second_trough_s + 0.25 / hz + 0.02,
                "{what}: first cycled at {} s, the second trough is at {second_trough_s} s",
                first.t_s
            );
            assert_eq!(first.margin, factor, "{what}");
            // From then until the shake ends it cycles on every tick, and asks the
            // factor's force: N_req of the load at safety × factor.
            for k in ticks
                .iter()
                .filter(|k| k.t_s >= first.t_s + 0.1 && k.t_s < 2.5)
            {
                assert_eq!(k.margin, factor, "{what}: at {} s", k.t_s);
                assert!(
                    (k.req_over_cyclic - 1.0).abs() < 0.1 && k.req_over_plain > 1.2,
                    "{what}: at {} s, N_req is {} x the cyclic one, {} x the plain one",
                    k.t_s,
                    k.req_over_cyclic,
                    k.req_over_plain
                );
            }
            // The shake's last trough lies within one period of its end; two windows after
            // that (and the filter's few milliseconds) the cyclic factor has ended. The
            // load has been steady since the shake ended, so the steady factor follows.
            let back = 2.5 + 1.0 / hz + 2.0 * SWING_WINDOW_S + 0.03;
            assert!(ticks.iter().filter(|k| k.t_s > back).count() > 500);
            for k in ticks.iter().filter(|k| k.t_s > back) {
                assert_eq!(k.margin, STEADY_SAFETY_FACTOR, "{what}: at {} s", k.t_s);
                assert!((k.req_over_steady - 1.0).abs() < 0.05, "{what}: {}", k.t_s);
            }
        }
    }
}

/// A weight of 1.5 N (and 0.015 N·m) held from the start, stepped at 1.5 s to
/// `1.5 · step` N over `ramp_s`.
fn stepped_hold(step: f64, ramp_s: f64, t: f64) -> (f64, f64) {
    let x = ((t - 1.5) / ramp_s).clamp(0.0, 1.0);
    let w = 1.5 * (1.0 + (step - 1.0) * x);
    (w, 0.01 * w)
}

#[test]
fn a_steady_hold_ramps_in_the_steady_factor_after_the_hold_time() {
    // The ramp: from the hold's end the factor falls by `(1 − STEADY_SAFETY_FACTOR)` over
    // `STEADY_RAMP_S` of 1 ms ticks, the same step on every tick.
    let step = (1.0 - STEADY_SAFETY_FACTOR) * 1e-3 / STEADY_RAMP_S;
    for cfg in configs() {
        let what = format!("{:?} lag {}", cfg.mode, cfg.actuator_lag_s);
        let ticks = run(cfg, 1.4, 0.02, |t| stepped_hold(1.0, 0.1, t));
        // The load settles within the filter's few milliseconds of the start.
        for k in &ticks {
            if k.t_s < STEADY_HOLD_S - 0.002 {
                assert_eq!(k.margin, 1.0, "{what}: at {} s", k.t_s);
                assert!((k.req_over_plain - 1.0).abs() < 0.05, "{what}: {}", k.t_s);
            } else if k.t_s > STEADY_HOLD_S + STEADY_RAMP_S + 0.03 {
                assert_eq!(k.margin, STEADY_SAFETY_FACTOR, "{what}: at {} s", k.t_s);
                assert!((k.req_over_steady - 1.0).abs() < 0.05, "{what}: {}", k.t_s);
                assert!(k.req_over_plain < 0.9, "{what}: {}", k.t_s);
            }
        }
        // Never rising, and linear in between: every tick of the ramp is one step down.
        let ramp: Vec<_> = ticks
            .windows(2)
            .filter(|w| w[1].margin < w[0].margin)
            .collect();
        assert_eq!(ramp.len() as f64, (STEADY_RAMP_S * 1e3).ceil(), "{what}");
        for w in ticks.windows(2) {
            assert!(w[1].margin <= w[0].margin, "{what}: at {} s", w[1].t_s);
        }
        for w in &ramp {
            assert!(
                (w[0].margin - w[1].margin - step).abs() < 1e-9,
                "{what}: at {} s, a step of {}",
                w[1].t_s,
                w[0].margin - w[1].margin
            );
        }
        // Halfway down the ramp the force asked is halfway between the plain and the
        // steady one (`N_req` is linear in the safety factor once above `N_slip`).
        let mid = &ramp[ramp.len() / 2][1];
        assert!(
            (mid.margin - (1.0 + STEADY_SAFETY_FACTOR) / 2.0).abs() < 2.0 * step,
            "{what}"
        );
        assert!(
            mid.req_over_plain < 1.0 && mid.req_over_steady > 1.0,
            "{what}: {} x the plain, {} x the steady",
            mid.req_over_plain,
            mid.req_over_steady
        );
    }
}

#[test]
fn a_load_that_moves_past_a_swing_depth_ends_the_steady_factor() {
    // Up by 30 %, up by 3 × (a second lift), down to 60 % (a release), each over 50 ms
    // at 1.5 s; the steady factor is back a hold's time after the load settles again.
    for cfg in configs() {
        for step in [1.3, 3.0, 0.6] {
            let what = format!("{:?} lag {}, × {step}", cfg.mode, cfg.actuator_lag_s);
            let ticks = run(cfg, 3.0, 0.02, |t| stepped_hold(step, 0.05, t));
            let before = ticks.iter().find(|k| k.t_s > 1.49).unwrap();
            assert_eq!(before.margin, STEADY_SAFETY_FACTOR, "{what}");
            // The filtered load passes the depth (10 % and the noise floor) within the
            // ramp and the filter's delay.
            let depth = CYCLE_DEPTH + 0.1 / 1.5;
            let crossed_s = 1.5 + 0.05 * depth / (step - 1.0).abs() + 0.02;
            let ended = ticks
                .iter()
                .find(|k| k.t_s > 1.5 && k.margin == 1.0)
                .unwrap_or_else(|| panic!("{what}: never ended"));
            assert!(ended.t_s < crossed_s, "{what}: ended at {} s", ended.t_s);
            // Then the configured factor holds for at least a hold time (the load may settle
            // within a depth of where it passed it, before the ramp's end), and the steady
            // factor is back, ramped in, within two hold times and a steady ramp of the
            // load's ramp's end.
            for k in ticks
                .iter()
                .filter(|k| k.t_s >= ended.t_s && k.t_s < ended.t_s + STEADY_HOLD_S - 0.002)
            {
                assert_eq!(k.margin, 1.0, "{what}: at {} s", k.t_s);
            }
            // (A settled load within the sensor noise of a depth from where it passed it
            // may start the hold once more.)
            for k in ticks
                .iter()
                .filter(|k| k.t_s > 1.55 + 2.0 * STEADY_HOLD_S + STEADY_RAMP_S + 0.05)
            {
                assert_eq!(k.margin, STEADY_SAFETY_FACTOR, "{what}: at {} s", k.t_s);
            }
        }
    }
}

#[test]
fn a_small_rise_ends_the_steady_factor_and_a_small_fall_does_not() {
    // A rise of 5 % of 1.5 N (0.075 N of load, more than `STEADY_RISE_N` but less than a
    // swing's depth) ends the steady factor within the ramp and the filter's delay: a
    // rising load gets its whole margin back before it climbs further. The same fall
    // keeps it.
    const { assert!(0.075 > STEADY_RISE_N && 0.075 < CYCLE_DEPTH * 1.5 + 0.1) };
    for cfg in configs() {
        for step in [1.05, 0.95] {
            let what = format!("{:?} lag {}, × {step}", cfg.mode, cfg.actuator_lag_s);
            let ticks = run(cfg, 2.2, 0.02, |t| stepped_hold(step, 0.05, t));
            let before = ticks.iter().find(|k| k.t_s > 1.49).unwrap();
            assert_eq!(before.margin, STEADY_SAFETY_FACTOR, "{what}");
            let ended = ticks.iter().find(|k| k.t_s > 1.5 && k.margin == 1.0);
            if step > 1.0 {
                let ended = ended.unwrap_or_else(|| panic!("{what}: never ended"));
                assert!(
                    ended.t_s < 1.5 + 0.05 + 0.02,
                    "{what}: ended at {} s",
                    ended.t_s
                );
            } else {
                assert!(ended.is_none(), "{what}: ended at {} s", ended.unwrap().t_s);
            }
        }
    }
}

#[test]
fn the_steady_factor_never_asks_less_than_n_slip() {
    // At safety factors where `s × STEADY_SAFETY_FACTOR` < 1 the force asked is `N_slip`;
    // above, `N_req` at the product.
    for cfg in configs() {
        for safety in [1.0, 1.2, 1.0 / STEADY_SAFETY_FACTOR + 0.05, 2.0] {
            let cfg = ControllerConfig { safety, ..cfg };
            let what = format!("{:?} lag {}, s {safety}", cfg.mode, cfg.actuator_lag_s);
            let ticks = run(cfg, 1.5, 0.02, |t| stepped_hold(1.0, 0.1, t));
            let steady: Vec<_> = ticks.iter().filter(|k| k.t_s > 1.0).collect();
            for k in &steady {
                assert_eq!(k.margin, STEADY_SAFETY_FACTOR, "{what}");
                assert!(k.req_over_slip >= 1.0 - 1e-9, "{what}: {}", k.req_over_slip);
                assert!((k.req_over_steady - 1.0).abs() < 0.05, "{what}");
                if safety * STEADY_SAFETY_FACTOR <= 1.0 {
                    assert!(
                        (k.req_over_slip - 1.0).abs() < 1e-6,
                        "{what}: {}",
                        k.req_over_slip
                    );
                } else {
                    assert!(k.req_over_slip > 1.0 + 1e-3, "{what}: {}", k.req_over_slip);
                }
            }
        }
    }
}
