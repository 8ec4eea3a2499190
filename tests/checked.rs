//! `ControllerConfig::check` and `Controller::from_checked`: a configuration validated once
//! builds the same controller as `Controller::new`; errors carry their parameter, field and
//! reason; a refused sensor range says which factor overflows.

use softgrip::controller::{Controller, ControllerConfig, Mode};
use softgrip::{BuildError, ConfigError, RangeOverflow};

#[test]
fn check_refuses_what_validate_refuses() {
    let bad = ControllerConfig {
        gamma: 0.7,
        ..ControllerConfig::default()
    };
    assert_eq!(bad.check().unwrap_err(), bad.validate().unwrap_err());
    let good = ControllerConfig::default().check().unwrap();
    assert_eq!(*good.config(), ControllerConfig::default());
    assert_eq!(good.mu, 0.8);
    assert_eq!(good.with_mode(Mode::Table).mode, Mode::Table);
}

#[test]
fn from_checked_builds_what_new_builds() {
    for mode in [Mode::Ellipse, Mode::Table] {
        let cfg = ControllerConfig {
            mode,
            ..ControllerConfig::default()
        };
        let a = Controller::<f32>::new(cfg).unwrap();
        let b = Controller::<f32>::from_checked(&cfg.check().unwrap()).unwrap();
        assert_eq!(a.capacity().tables(), b.capacity().tables());
        let c = Controller::<f32>::new_precomputed_in::<f64>(cfg).unwrap();
        let d = Controller::<f32>::from_checked_in::<f64>(&cfg.check().unwrap()).unwrap();
        assert_eq!(c.capacity().tables(), d.capacity().tables());
    }
}

#[test]
fn an_error_has_its_parameter_field_and_reason() {
    let e = ConfigError::OutOfRange {
        param: "c",
        value: -1.0,
        expected: "c > 0",
    };
    assert_eq!(e.param(), "c");
    assert_eq!(e.field(), "c_m_per_n_gamma");
    assert_eq!(e.reason().to_string(), "-1 is out of range, expected c > 0");
    assert_eq!(e.to_string(), format!("c: {}", e.reason()));
    assert_eq!(softgrip::error::field_of("order"), "quadrature_order");
    assert_eq!(softgrip::error::field_of("safety"), "safety");
}

fn overflow(cfg: ControllerConfig) -> BuildError {
    Controller::<f32>::from_checked(&cfg.check().unwrap()).unwrap_err()
}

#[test]
fn a_range_overflow_names_its_factor() {
    let d = ControllerConfig::default();
    let tiny_mu = ControllerConfig { mu: 1e-300, ..d };
    assert_eq!(
        overflow(tiny_mu),
        BuildError::RangeOverflow(RangeOverflow::SafetyOverMu)
    );
    let long = ControllerConfig {
        half_length_m: 1e300,
        ..d
    };
    // (In f64: in f32 the aspect itself is out of reach first.)
    assert_eq!(
        Controller::<f64>::from_checked(&long.check().unwrap()).unwrap_err(),
        BuildError::RangeOverflow(RangeOverflow::Contact)
    );
    // A contact of 1e-17 m: the default moment range fits the tick's f32, 100 N·m not.
    let small = ControllerConfig {
        c_m_per_n_gamma: 1e-17,
        half_length_m: 1e-17,
        ..d
    };
    assert!(Controller::<f32>::from_checked(&small.check().unwrap()).is_ok());
    let wide = ControllerConfig {
        moment_range_nm: 200.0,
        ..small
    };
    assert_eq!(
        overflow(wide),
        BuildError::RangeOverflow(RangeOverflow::SensorRange)
    );
    assert_eq!(overflow(wide).field(), "force_range_n");
}
