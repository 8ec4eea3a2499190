//! A configuration from arbitrary bytes (postcard, as a `Configure` request carries it),
//! then `Controller::new` in f32 (the device's precision and precomputation) and a few
//! ticks on measurements from the remaining bytes. Checks: no panic; a refusal names a
//! field; an accepted controller's command is finite and inside `[N_min, N_max]`, and its
//! other outputs are finite when the configuration's values fit f32 (beyond, only the
//! command and the utilisation are checked; a grid f32 cannot hold once ticked with NaN,
//! now fixed: see tests/no_panic.rs, `values_beyond_f32_are_accepted`).
#![no_main]

use libfuzzer_sys::fuzz_target;
use softgrip::controller::{Controller, ControllerConfig, Libm, Measurement, UTILISATION_MAX};

fn fits_f32(cfg: &ControllerConfig) -> bool {
    let fine = |x: f64| (1e-30..=1e30).contains(&x.abs());
    [
        cfg.mu,
        cfg.c_m_per_n_gamma,
        cfg.half_length_m,
        cfg.safety,
        cfg.n_min_n,
        cfg.n_max_n,
        cfg.rise_rate_n_per_s * cfg.tick_period_s,
        cfg.fall_rate_n_per_s * cfg.tick_period_s,
        cfg.fault_force_n,
        cfg.force_range_n,
        cfg.moment_range_nm,
    ]
    .into_iter()
    .all(fine)
        && cfg
            .skew
            .is_none_or(|s| s.alpha <= 1e30 && s.locus_over_a <= 1e30)
}

fuzz_target!(|data: &[u8]| {
    let Ok((cfg, rest)) = postcard::take_from_bytes::<ControllerConfig>(data) else {
        return;
    };
    // Keep each run short: the grid sizes decide the start-up cost.
    if cfg.table_samples > 128 || cfg.force_nodes > 64 || cfg.quadrature_order > 64 {
        let _ = Controller::<f32, Libm>::new(ControllerConfig {
            mode: softgrip::controller::Mode::Ellipse,
            ..cfg
        });
        return;
    }
    let mut c = match Controller::<f32, Libm>::new(cfg) {
        Ok(c) => c,
        Err(e) => {
            assert!(!e.param().is_empty());
            let _ = e.to_string();
            return;
        }
    };
    let (lo, hi) = (cfg.n_min_n as f32, cfg.n_max_n as f32);
    for (i, m) in rest.chunks(16).enumerate() {
        let word = |k: usize| {
            let mut b = [0u8; 4];
            for (j, x) in b.iter_mut().enumerate() {
                *x = m.get(4 * k + j).copied().unwrap_or(0);
            }
            f32::from_le_bytes(b)
        };
        let o = c.tick(&Measurement {
            tangential_force_n: [word(0), word(1)],
            torsional_moment_nm: word(2),
            normal_force_n: word(3),
            timestamp_us: i as u64 * 1000,
            slip: Default::default(),
        });
        assert!(
            o.command_n.is_finite() && o.command_n >= lo && o.command_n <= hi,
            "{cfg:?} {o:?}"
        );
        assert!(o.utilisation >= 0.0 && o.utilisation <= UTILISATION_MAX as f32);
        if fits_f32(&cfg) {
            assert!(
                o.required_n.is_finite() && o.n_slip_n.is_finite(),
                "{cfg:?} {o:?}"
            );
        }
    }
});
