//! Cost of the controller: one tick in each mode, precision and math backend, and the
//! start-up precomputation.
//!
//! Run with `cargo bench --bench tick`. The `tick_{mode}_*` benchmarks cycle through 256
//! unrelated measurements (loads from pure translation to pure torsion, answers spread
//! over `[N_min, N_max]` and beyond): every tick starts its search afresh, the cost of a
//! load that jumps. The `tick_smooth_*` benchmarks follow a load that turns once a second
//! at 1 kHz, as in a grip loop, where the previous tick's grid interval is a good hint.

mod common;

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use softgrip::controller::{
    Controller, ControllerConfig, Libm, Measurement, Micromath, Mode, TickMath,
};
use softgrip::Real;

fn loads<T: Real>() -> Vec<Measurement<T>> {
    (0..256)
        .map(|i| {
            let phase = i as f64 * 0.173;
            let scale = 0.05 + 4.0 * ((i * 37 % 256) as f64 / 256.0);
            Measurement {
                tangential_force_n: [T::of(scale * phase.cos()), T::of(0.3 * scale * phase.sin())],
                torsional_moment_nm: T::of(0.01 * scale * (1.0 + (1.7 * phase).sin())),
                normal_force_n: T::of(2.0 + scale),
                timestamp_us: 0,
                slip: Default::default(),
            }
        })
        .collect()
}

fn bench_tick<T: Real, M: TickMath<T>>(c: &mut Criterion, name: &str, mode: Mode) {
    let cfg = ControllerConfig {
        mode,
        ..ControllerConfig::default()
    };
    let mut ctl = Controller::<T, M>::new_precomputed_in::<f64>(cfg).expect("valid");
    let mut meas = loads::<T>();
    let mut t = 0u64;
    let mut i = 0usize;
    c.bench_function(common::id(name), |b| {
        b.iter(|| {
            i = (i + 1) % meas.len();
            t += 1000;
            let m = &mut meas[i];
            m.timestamp_us = t;
            black_box(ctl.tick(black_box(m)))
        })
    });
}

/// A grasp at 1 kHz: the load turns slowly (one cycle a second), as in a control loop,
/// so consecutive ticks fall in the same grid interval.
fn bench_smooth_tick(c: &mut Criterion, name: &str, mode: Mode) {
    let cfg = ControllerConfig {
        mode,
        ..ControllerConfig::default()
    };
    let mut ctl = Controller::<f32, Libm>::new_precomputed_in::<f64>(cfg).expect("valid");
    let cycle: Vec<Measurement<f32>> = (0..1000)
        .map(|k| {
            let phase = k as f32 * (std::f32::consts::TAU / 1000.0);
            Measurement {
                tangential_force_n: [2.0 + 1.5 * phase.sin(), 0.5 * phase.cos()],
                torsional_moment_nm: 0.01 * (1.0 + phase.cos()),
                normal_force_n: 4.0,
                timestamp_us: 0,
                slip: Default::default(),
            }
        })
        .collect();
    let mut k = 0u64;
    c.bench_function(common::id(name), |b| {
        b.iter(|| {
            k += 1;
            let mut m = cycle[(k % 1000) as usize];
            m.timestamp_us = k * 1000;
            black_box(ctl.tick(black_box(&m)))
        })
    });
}

fn ticks(c: &mut Criterion) {
    bench_smooth_tick(c, "tick_smooth_ellipse_f32_libm", Mode::Ellipse);
    bench_smooth_tick(c, "tick_smooth_table_f32_libm", Mode::Table);
    for mode in [Mode::Ellipse, Mode::Table] {
        let n = mode.name();
        bench_tick::<f32, Libm>(c, &format!("tick_{n}_f32_libm"), mode);
        bench_tick::<f32, Micromath>(c, &format!("tick_{n}_f32_micromath"), mode);
        bench_tick::<f64, Libm>(c, &format!("tick_{n}_f64_libm"), mode);
    }
}

fn startup(c: &mut Criterion) {
    for mode in [Mode::Ellipse, Mode::Table] {
        let cfg = ControllerConfig {
            mode,
            ..ControllerConfig::default()
        };
        let n = mode.name();
        c.bench_function(common::id(&format!("startup_{n}_f32")), |b| {
            b.iter(|| black_box(Controller::<f32>::new(black_box(cfg)).expect("valid")))
        });
        c.bench_function(common::id(&format!("startup_{n}_f64")), |b| {
            b.iter(|| black_box(Controller::<f64>::new(black_box(cfg)).expect("valid")))
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = ticks, startup
}
criterion_main!(benches);
