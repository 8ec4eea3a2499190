//! Identifying the actuator online (`controller::actuator`) and leading with it
//! (`controller::lead`), in a closed loop with a simulated first-order, slew-limited
//! actuator and a noisy normal-force sensor: the lag and slew are found from a wrong
//! prior, an untold actuator is led through a lift and a shake where the controller
//! that cannot identify it falls short, a fast shake is not over-commanded, and an ideal
//! actuator changes no command.

use softgrip::controller::{
    Controller, ControllerConfig, Measurement, Mode, SlipSignal, CYCLIC_SAFETY_FACTOR,
};

#[path = "common/noise.rs"]
mod noise;
use noise::Noise;

/// The actuator: a first-order lag `tau_s` with slew `slew` [N/s] (`tau_s = 0`: the
/// force is the last command).
struct Actuator {
    tau_s: f64,
    slew: f64,
    force_n: f64,
}

impl Actuator {
    fn step(&mut self, command_n: f64, dt: f64) {
        let d = if self.tau_s > 0.0 {
            (command_n - self.force_n) * (dt / self.tau_s).min(1.0)
        } else {
            command_n - self.force_n
        };
        self.force_n += d.clamp(-self.slew * dt, self.slew * dt);
    }
}

/// What a closed-loop run gives: the identified lag and slew at its end, the worst
/// shortfall of the actuator's force below the force the load needs with no margin
/// (`N_slip`) [N], and the mean force and mean `N_slip` [N].
struct Outcome {
    lag_s: f64,
    /// The worst shortfall after the first 0.6 s (once the first lift has shown the lag).
    late_shortfall_n: f64,
    slew: f64,
    shortfall_n: f64,
    mean_force_n: f64,
    mean_need_n: f64,
    commands: Vec<f64>,
    /// The identified lag after each tick [s].
    lags: Vec<f64>,
    /// `N_slip` and the actuator's force on each tick [N].
    needs: Vec<f64>,
    forces: Vec<f64>,
}

impl Outcome {
    /// The worst shortfall of the actuator's force below `N_slip` from `from_s` on [N]
    /// (0 when it never falls short).
    fn shortfall_from(&self, from_s: f64) -> f64 {
        let k0 = (from_s * 1e3) as usize;
        (self.needs[k0..].iter().zip(&self.forces[k0..]))
            .map(|(n, f)| n - f)
            .fold(0.0, f64::max)
    }

    /// Mean command over mean `N_slip` from `from_s` on.
    fn command_over_need_from(&self, from_s: f64) -> f64 {
        let k0 = (from_s * 1e3) as usize;
        self.commands[k0..].iter().sum::<f64>() / self.needs[k0..].iter().sum::<f64>()
    }
}

/// Runs `seconds` of `load(t)` [N, tangential] through `actuator` against a controller of
/// `cfg`, with 0.02 N of noise on every channel.
fn run(
    cfg: ControllerConfig,
    mut act: Actuator,
    seconds: f64,
    load: impl Fn(f64) -> f64,
) -> Outcome {
    let mut c = Controller::<f64>::new(cfg).unwrap();
    let mut noise = Noise(7);
    let dt = 1e-3;
    act.force_n = cfg.n_min_n;
    let (mut shortfall, mut force, mut need, mut commands) = (0.0f64, 0.0, 0.0, Vec::new());
    let mut late = 0.0f64;
    let (mut lags, mut needs, mut forces) = (Vec::new(), Vec::new(), Vec::new());
    let ticks = (seconds / dt) as usize;
    for k in 0..ticks {
        let t = k as f64 * dt;
        let ft = load(t);
        let m = Measurement {
            tangential_force_n: [0.0, ft + 0.02 * noise.normal()],
            torsional_moment_nm: 0.0,
            normal_force_n: act.force_n + 0.02 * noise.normal(),
            timestamp_us: 1000 * (k as u64 + 1),
            slip: SlipSignal::None,
        };
        let out = c.tick(&m);
        let slip = c.slip_force(ft, 0.0).unwrap().force_n;
        shortfall = shortfall.max(slip - act.force_n);
        if t >= 0.6 {
            late = late.max(slip - act.force_n);
        }
        force += act.force_n;
        need += slip;
        commands.push(out.command_n);
        lags.push(c.actuator_lag_estimate_s());
        needs.push(slip);
        forces.push(act.force_n);
        act.step(out.command_n, dt);
    }
    Outcome {
        lag_s: c.actuator_lag_estimate_s(),
        late_shortfall_n: late,
        slew: c.actuator_slew_estimate_n_per_s(),
        shortfall_n: shortfall,
        mean_force_n: force / ticks as f64,
        mean_need_n: need / ticks as f64,
        commands,
        lags,
        needs,
        forces,
    }
}

/// A lift: the load rises from 0 to 3 N over 0.15 s (smoothly), then holds.
fn lift(t: f64) -> f64 {
    let x = ((t - 0.1) / 0.15).clamp(0.0, 1.0);
    3.0 * x * x * (3.0 - 2.0 * x)
}

/// A lag told to be one tick: an ideal actuator, under the lead's floor, never led.
const IDEAL_LAG_S: f64 = 1e-3;

fn lagging(lag_s: f64, slew: f64) -> ControllerConfig {
    ControllerConfig {
        actuator_lag_s: lag_s,
        actuator_slew_n_per_s: slew,
        ..base()
    }
}

/// The settings these figures were measured at: ellipse mode, safety 1.3 (the default
/// before the bench chose table mode at 1.4); the identifier and the lead do not depend
/// on the mode.
fn base() -> ControllerConfig {
    ControllerConfig {
        mode: Mode::Ellipse,
        safety: 1.3,
        ..ControllerConfig::default()
    }
}

#[test]
fn the_lag_is_found_from_a_wrong_prior() {
    for tau in [0.01, 0.03, 0.06] {
        for prior in [0.0, 2.0 * tau] {
            let act = Actuator {
                tau_s: tau,
                slew: f64::INFINITY,
                force_n: 0.0,
            };
            // Two lifts: up, down and up again.
            let o = run(lagging(prior, f64::INFINITY), act, 2.0, |t| {
                lift(t) - lift(t - 0.8) + lift(t - 1.4)
            });
            // 200 ms after the first lift began (it starts at 0.1 s), the prior is
            // corrected already.
            let early = o.lags[300];
            eprintln!(
                "tau {tau}: prior {prior} -> {:.4} s 0.2 s into the first lift, {:.4} s at \
                 the end",
                early, o.lag_s
            );
            for lag in [early, o.lag_s] {
                assert!(
                    (lag / tau - 1.0).abs() < 0.3,
                    "tau {tau}, prior {prior}: {early} then {}",
                    o.lag_s
                );
            }
            assert!(o.slew.is_infinite());
        }
    }
}

#[test]
fn a_slew_that_binds_is_found() {
    // A 100 N/s actuator: a light lift shows its lag (the slew does not bind), then heavy,
    // fast lifts make it slew. From no slew prior, and from one twice and half the truth.
    let load = |t: f64| lift(t) + 3.0 * lift(t - 0.5) - 3.0 * lift(t - 1.0) + 3.0 * lift(t - 1.5);
    for prior in [f64::INFINITY, 200.0, 50.0] {
        let act = Actuator {
            tau_s: 0.01,
            slew: 100.0,
            force_n: 0.0,
        };
        let o = run(lagging(0.0, prior), act, 2.2, load);
        eprintln!(
            "slew 100 N/s, prior {prior} -> {:.1} N/s, lag {:.4} s",
            o.slew, o.lag_s
        );
        assert!((o.slew / 100.0 - 1.0).abs() < 0.15, "{prior}: {}", o.slew);
        assert!((o.lag_s / 0.01 - 1.0).abs() < 0.5, "{prior}: {}", o.lag_s);
    }
}

/// The same rule with no lead at all (a controller that measures its own commands back,
/// so sees an ideal actuator) driving `act` through `load`: the worst shortfall of the
/// actuator's force below `N_slip` over the run and from `from_s` on [N].
fn no_lead(mut act: Actuator, seconds: f64, from_s: f64, load: impl Fn(f64) -> f64) -> (f64, f64) {
    let mut blind = Controller::<f64>::new(lagging(IDEAL_LAG_S, f64::INFINITY)).unwrap();
    act.force_n = 0.2;
    let (mut worst, mut worst_late) = (0.0f64, 0.0f64);
    for k in 0..(seconds * 1e3) as u64 {
        let t = k as f64 * 1e-3;
        let m = Measurement {
            tangential_force_n: [0.0, load(t)],
            torsional_moment_nm: 0.0,
            normal_force_n: blind.command_n(),
            timestamp_us: 1000 * (k + 1),
            slip: SlipSignal::None,
        };
        let out = blind.tick(&m);
        let short = blind.slip_force(load(t), 0.0).unwrap().force_n - act.force_n;
        worst = worst.max(short);
        if t >= from_s {
            worst_late = worst_late.max(short);
        }
        act.step(out.command_n, 1e-3);
    }
    (worst, worst_late)
}

/// [`lift`], then from 0.6 s a shake of `amplitude_n` at `hz`.
fn lift_then_shake(amplitude_n: f64, hz: f64) -> impl Fn(f64) -> f64 + Copy {
    move |t: f64| {
        let shake = if t > 0.6 {
            amplitude_n * (std::f64::consts::TAU * hz * (t - 0.6)).sin()
        } else {
            0.0
        };
        lift(t) + shake
    }
}

/// A 25 ms actuator, not slew-limited, starting from no force.
fn untold_25ms() -> Actuator {
    Actuator {
        tau_s: 0.025,
        slew: f64::INFINITY,
        force_n: 0.0,
    }
}

#[test]
fn an_untold_actuator_is_led_through_a_lift_and_a_shake() {
    // 25 ms, not told. The first lift shows the lag; through the 8 Hz shake that follows,
    // the controller that identified it does as well as the one that was told, and over
    // the run it falls short of the load's need by under half as much as the same rule
    // with no lead at all (a controller that measures its own commands back, so sees an
    // ideal actuator).
    let load = lift_then_shake(2.0, 8.0);
    let act = untold_25ms;
    let told = run(lagging(0.025, f64::INFINITY), act(), 1.6, load);
    let untold = run(lagging(0.0, f64::INFINITY), act(), 1.6, load);
    let (worst, worst_late) = no_lead(act(), 1.6, 0.6, load);
    eprintln!(
        "shortfall [N], whole run / shake: told {:.3} / {:.3}; untold {:.3} / {:.3} (lag \
         found {:.4} s); no lead {worst:.3} / {worst_late:.3}",
        told.shortfall_n,
        told.late_shortfall_n,
        untold.shortfall_n,
        untold.late_shortfall_n,
        untold.lag_s
    );
    // Once identified, as good as told; and over the run, well under the controller
    // that cannot lead.
    assert!(
        untold.late_shortfall_n <= told.late_shortfall_n + 0.01,
        "{} {}",
        untold.late_shortfall_n,
        told.late_shortfall_n
    );
    assert!(worst > 0.0, "the test must be able to fail: {worst}");
    assert!(
        untold.shortfall_n < 0.5 * worst,
        "{} {worst}",
        untold.shortfall_n
    );
    assert!(
        (untold.lag_s / 0.025 - 1.0).abs() < 0.25,
        "{}",
        untold.lag_s
    );
    // The first lift, before its rise has shown the lag, is led from the untold prior
    // (20 ms): short by 0.074 N; starting from no lag at all it was 0.165 N.
    assert!(untold.shortfall_n < 0.1, "{}", untold.shortfall_n);
}

#[test]
fn a_fast_shake_is_not_over_commanded() {
    // 10 Hz through 40 ms: the mean force (2.25 x the mean need) stays within 1.75 x the
    // mean need times the
    // cyclic load's factor on the safety factor, which the shake earns from its second
    // trough (a lead on every rise ratchets it up to the swing's peak and a lead on top:
    // 2.1 x, before the cyclic factor, when the cap was off by a bug).
    let load = |t: f64| {
        1.0 + lift(t)
            + if t > 0.5 {
                1.5 * (std::f64::consts::TAU * 10.0 * (t - 0.5)).sin()
            } else {
                0.0
            }
    };
    let act = Actuator {
        tau_s: 0.04,
        slew: f64::INFINITY,
        force_n: 0.0,
    };
    let o = run(lagging(0.04, f64::INFINITY), act, 1.5, load);
    let ratio = o.mean_force_n / o.mean_need_n;
    eprintln!(
        "10 Hz through 40 ms: force / need = {ratio:.3}, shortfall {:.3} N",
        o.shortfall_n
    );
    assert!(ratio < 1.75 * CYCLIC_SAFETY_FACTOR, "{ratio}");
}

#[test]
fn an_untold_actuator_holds_a_five_hz_shake() {
    // 25 ms, not told: a lift (0.1 to 0.25 s), then a 5 Hz shake of ±3 N about its 3 N
    // from 0.6 s. Once the first 50 ms of the lift have shown the lag, the actuator's
    // force falls below N_slip by no more than the sensor's noise, and in the shake never;
    // the rule with no lead falls below it by tenths of a newton, in the lift and in the
    // shake.
    let load = lift_then_shake(3.0, 5.0);
    let act = untold_25ms;
    let untold = run(lagging(0.0, f64::INFINITY), act(), 1.6, load);
    let told = run(lagging(0.025, f64::INFINITY), act(), 1.6, load);
    let (blind_all, blind_after) = no_lead(act(), 1.6, 0.15, load);
    let (_, blind_shake) = no_lead(act(), 1.6, 0.6, load);
    let after = untold.shortfall_from(0.15);
    eprintln!(
        "5 Hz through an untold 25 ms actuator: shortfall below N_slip [N], whole run / from \
         0.15 s / shake: untold {:.3} / {after:.3} / {:.3} (lag found {:.4} s); told {:.3} / \
         {:.3} / {:.3}; no lead {blind_all:.3} / {blind_after:.3} / {blind_shake:.3}",
        untold.shortfall_n,
        untold.shortfall_from(0.6),
        untold.lag_s,
        told.shortfall_n,
        told.shortfall_from(0.15),
        told.shortfall_from(0.6),
    );
    assert!(
        blind_after > 0.1 && blind_shake > 0.1,
        "the test must be able to fail"
    );
    // In the lift, short by no more than the sensor's noise (0.02 N) once the lag shows;
    // in the shake, never short.
    assert!(after <= 0.02, "untold, from 0.15 s: {after}");
    assert_eq!(untold.shortfall_from(0.6), 0.0, "untold, in the shake");
    assert_eq!(told.shortfall_from(0.15), 0.0, "told, from 0.15 s");
}

#[test]
fn shakes_of_6_to_15_hz_through_20_to_60_ms_are_not_over_commanded() {
    // A 1 N load, lifted by 3 N (0.1 to 0.25 s), shaken by ±1.5 N from 0.5 s. Over the
    // shake (from 0.6 s), for told and untold actuators: the actuator's force never falls
    // below N_slip, and the mean command stays within 6 % of the safety factor (times the
    // cyclic load's factor, which the shake earns) times the shake's peak N_slip. That is
    // what holding a swing through a lag that cannot follow it needs; a lead on every
    // rise, which the swing cap stops, ratchets the command up to the peak plus a lead on
    // top. Against the mean N_slip it is under 1.9 × that factor: the safety factor's
    // 1.3 × times the swing's peak over its mean. Measured: 0.905 to 1.055 × the
    // peak-hold, 2.35 to 2.74 × the mean N_slip (1.62 to 1.89 × in units of the cyclic
    // factor, 1.45).
    let (mut worst, mut worst_over_peak) = (0.0f64, 0.0f64);
    for tau in [0.02, 0.04, 0.06] {
        for hz in [6.0, 8.0, 10.0, 12.0, 15.0] {
            let load = move |t: f64| {
                let shake = if t > 0.5 {
                    1.5 * (std::f64::consts::TAU * hz * (t - 0.5)).sin()
                } else {
                    0.0
                };
                1.0 + lift(t) + shake
            };
            for prior in [tau, 0.0] {
                let act = Actuator {
                    tau_s: tau,
                    slew: f64::INFINITY,
                    force_n: 0.0,
                };
                let o = run(lagging(prior, f64::INFINITY), act, 1.6, load);
                let ratio = o.command_over_need_from(0.6);
                let peak = o.needs[600..].iter().fold(0.0, |a: f64, &b| a.max(b));
                let mean_command = o.commands[600..].iter().sum::<f64>() / 1000.0;
                let over_peak = mean_command / (1.3 * CYCLIC_SAFETY_FACTOR * peak);
                worst = worst.max(ratio);
                worst_over_peak = worst_over_peak.max(over_peak);
                eprintln!(
                    "{hz} Hz through {tau} s (prior {prior}): mean command / mean N_slip \
                     {ratio:.3}, / (1.3 x cyclic x peak N_slip) {over_peak:.3}, shortfall {:.3} N",
                    o.shortfall_from(0.6)
                );
                let case = format!("{hz} Hz, {tau} s, prior {prior}");
                assert_eq!(o.shortfall_from(0.6), 0.0, "{case}");
                assert!(over_peak < 1.06, "{case}: {over_peak}");
                assert!(ratio < 1.9 * CYCLIC_SAFETY_FACTOR, "{case}: {ratio}");
            }
        }
    }
    eprintln!(
        "worst over the sweep: mean command / mean N_slip {worst:.3}, / (1.3 x cyclic x peak \
         N_slip) {worst_over_peak:.3}"
    );
}

#[test]
fn an_ideal_actuator_changes_no_command() {
    // The force is the last command: identified as no lag, so the commands are those of
    // a controller that cannot lead at all (fed its own commands back).
    let a = run(
        base(),
        Actuator {
            tau_s: 0.0,
            slew: f64::INFINITY,
            force_n: 0.0,
        },
        1.0,
        lift,
    );
    assert_eq!(a.lag_s, 0.0);
    let mut c = Controller::<f64>::new(base()).unwrap();
    let mut noise = Noise(7);
    let mut force = 0.2;
    for (k, want) in a.commands.iter().enumerate() {
        let t = k as f64 * 1e-3;
        let m = Measurement {
            tangential_force_n: [0.0, lift(t) + 0.02 * noise.normal()],
            torsional_moment_nm: 0.0,
            normal_force_n: force + 0.02 * noise.normal(),
            timestamp_us: 1000 * (k as u64 + 1),
            slip: SlipSignal::None,
        };
        let out = c.tick(&m);
        assert_eq!(out.command_n.to_bits(), want.to_bits(), "tick {k}");
        force = out.command_n;
    }
}

#[test]
fn hostile_normal_forces_keep_the_estimates_finite() {
    let mut c = Controller::<f64>::new(lagging(0.02, 300.0)).unwrap();
    let values = [
        f64::NAN,
        f64::INFINITY,
        -5.0,
        1e30,
        -1e30,
        0.0,
        99.0,
        -99.0,
        1e-300,
    ];
    for k in 0..5000u64 {
        let n = values[(k as usize * 7) % values.len()];
        let m = Measurement {
            tangential_force_n: [0.0, (k % 13) as f64 * 0.3],
            torsional_moment_nm: 0.0,
            normal_force_n: if k % 3 == 0 { n } else { (k % 17) as f64 },
            timestamp_us: 1000 * (k + 1),
            slip: SlipSignal::None,
        };
        let out = c.tick(&m);
        assert!(out.command_n.is_finite());
        let lag = c.actuator_lag_estimate_s();
        assert!(lag.is_finite() && lag >= 0.0, "{lag}");
        assert!(c.actuator_slew_estimate_n_per_s() > 0.0);
    }
}
