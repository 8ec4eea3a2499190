//! Exported tables: a controller built from them ticks exactly like the one they came
//! from, and a blob that is corrupt, of another version or for another configuration is
//! refused with the right error.

use softgrip::controller::blob::{encode, Blob, BlobError, BLOB_MAX_LEN};
use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, FromTablesError, Libm, Measurement, Mode, TableError,
};
use softgrip::protocol::CRC;

fn configs() -> Vec<ControllerConfig> {
    let d = ControllerConfig::default();
    vec![
        d,
        ControllerConfig {
            mode: Mode::Table,
            ..d
        },
        ControllerConfig {
            shape: FingerShape::Disc,
            gamma: 1.0 / 3.0,
            c_m_per_n_gamma: 4e-3,
            mode: Mode::Table,
            ..d
        },
        ControllerConfig {
            gamma: 0.0,
            c_m_per_n_gamma: 5e-3,
            mode: Mode::Table,
            force_nodes: 16,
            ..d
        },
    ]
}

fn same_ticks(a: &mut Controller<f32>, b: &mut Controller<f32>) {
    for i in 0..500u64 {
        let p = i as f32 * 0.03;
        let m = Measurement {
            tangential_force_n: [4.0 * p.sin().abs(), 0.3 * p.cos()],
            torsional_moment_nm: 0.02 * (1.3 * p).sin(),
            normal_force_n: 2.0 + p.cos(),
            timestamp_us: 1000 * i + 1,
            slip: Default::default(),
        };
        let (x, y) = (a.tick(&m), b.tick(&m));
        assert_eq!(x.command_n.to_bits(), y.command_n.to_bits(), "tick {i}");
        assert_eq!(x.required_n.to_bits(), y.required_n.to_bits(), "tick {i}");
        assert_eq!(x.n_slip_n.to_bits(), y.n_slip_n.to_bits(), "tick {i}");
        assert_eq!(x.utilisation.to_bits(), y.utilisation.to_bits(), "tick {i}");
    }
}

#[test]
fn tables_and_blobs_give_bit_identical_controllers() {
    for cfg in configs() {
        let computed = Controller::<f32>::new(cfg).unwrap();
        let tables = computed.capacity().tables();
        let mut imported = Controller::<f32>::from_tables(cfg, &tables).unwrap();
        let mut buf = [0u8; BLOB_MAX_LEN];
        let len = encode(&cfg, &tables, &mut buf).unwrap();
        let blob = Blob::parse(&buf[..len]).unwrap();
        assert_eq!(blob.config(), cfg);
        let mut from_blob = blob.controller::<Libm>().unwrap();
        let mut fresh = Controller::<f32>::new(cfg).unwrap();
        same_ticks(&mut fresh, &mut imported);
        let mut fresh = Controller::<f32>::new(cfg).unwrap();
        same_ticks(&mut fresh, &mut from_blob);
        // f64 precomputation exports too, and still ticks like its source.
        let mut fine = Controller::<f32>::new_precomputed_in::<f64>(cfg).unwrap();
        let mut copy = Controller::<f32>::from_tables(cfg, &fine.capacity().tables()).unwrap();
        same_ticks(&mut fine, &mut copy);
    }
}

fn blob_for(cfg: ControllerConfig) -> Vec<u8> {
    let c = Controller::<f32>::new(cfg).unwrap();
    let mut buf = [0u8; BLOB_MAX_LEN];
    let len = encode(&cfg, &c.capacity().tables(), &mut buf).unwrap();
    buf[..len].to_vec()
}

fn reseal(mut b: Vec<u8>) -> Vec<u8> {
    let end = b.len() - 4;
    let crc = CRC.checksum(&b[..end]);
    b[end..].copy_from_slice(&crc.to_le_bytes());
    b
}

#[test]
fn every_single_bit_flip_and_truncation_is_refused() {
    let good = blob_for(ControllerConfig {
        mode: Mode::Table,
        ..ControllerConfig::default()
    });
    for i in 0..good.len() {
        for bit in 0..8 {
            let mut b = good.clone();
            b[i] ^= 1 << bit;
            let e = Blob::parse(&b).unwrap_err();
            assert!(
                matches!(
                    e,
                    BlobError::Crc { .. }
                        | BlobError::BadMagic
                        | BlobError::Version { .. }
                        | BlobError::Length { .. }
                ),
                "byte {i} bit {bit}: {e}"
            );
        }
    }
    for n in [0, 3, 13, good.len() / 2, good.len() - 1] {
        let e = Blob::parse(&good[..n]).unwrap_err();
        assert!(
            matches!(e, BlobError::TooShort { .. } | BlobError::Length { .. }),
            "{n}: {e}"
        );
    }
}

#[test]
fn wrong_versions_configurations_and_values_are_named() {
    let good = blob_for(ControllerConfig::default());
    let mut b = good.clone();
    b[4] = 9;
    assert_eq!(
        Blob::parse(&reseal(b)).unwrap_err(),
        BlobError::Version { found: 9 }
    );
    let mut b = good.clone();
    b[0] = b'X';
    assert_eq!(Blob::parse(&b).unwrap_err(), BlobError::BadMagic);

    // Tables that do not fit the configuration they claim (ellipse mode's, which have no
    // table-mode radii).
    let cfg = ControllerConfig {
        mode: Mode::Ellipse,
        ..ControllerConfig::default()
    };
    let c = Controller::<f32>::new(cfg).unwrap();
    let t = c.capacity().tables();
    let other = ControllerConfig {
        n_min_n: 0.3,
        ..cfg
    };
    assert_eq!(
        Controller::<f32>::from_tables(other, &t).unwrap_err(),
        FromTablesError::Tables(TableError::Mismatch { param: "n_min_n" })
    );
    let fewer = ControllerConfig {
        force_nodes: 40,
        ..cfg
    };
    assert!(matches!(
        Controller::<f32>::from_tables(fewer, &t).unwrap_err(),
        FromTablesError::Tables(TableError::Size {
            what: "force_n",
            ..
        })
    ));
    let table_mode = ControllerConfig {
        mode: Mode::Table,
        ..cfg
    };
    assert!(matches!(
        Controller::<f32>::from_tables(table_mode, &t).unwrap_err(),
        FromTablesError::Tables(TableError::Size {
            what: "inv_radius",
            ..
        })
    ));
    let mut arms = t.arm_m.to_vec();
    arms[7] = f32::NAN;
    let bad = softgrip::controller::Tables { arm_m: &arms, ..t };
    assert_eq!(
        Controller::<f32>::from_tables(cfg, &bad).unwrap_err(),
        FromTablesError::Tables(TableError::Invalid {
            what: "arm_m",
            index: 7
        })
    );
    let bad_cfg = ControllerConfig { mu: -1.0, ..cfg };
    assert!(matches!(
        Controller::<f32>::from_tables(bad_cfg, &t).unwrap_err(),
        FromTablesError::Config(e) if e.param() == "mu"
    ));
}

/// `BLOB_MAX_LEN` is what its docs say, the largest blob: the largest grid (table mode,
/// every capacity at its maximum, with skew) fits, and needs no less than half of it.
#[test]
fn the_largest_configuration_fits_blob_max_len() {
    let cfg = ControllerConfig {
        mode: Mode::Table,
        force_nodes: softgrip::controller::MAX_FORCE_NODES as u16,
        table_samples: softgrip::controller::MAX_TABLE_SAMPLES as u16,
        aspect_count: softgrip::controller::MAX_ASPECTS as u16,
        skew: Some(softgrip::controller::SkewParams::PAPER),
        ..ControllerConfig::default()
    };
    let c = Controller::<f32>::new(cfg).unwrap();
    let mut buf = [0u8; BLOB_MAX_LEN];
    let len = encode(&cfg, &c.capacity().tables(), &mut buf).unwrap();
    println!("largest blob: {len} of {BLOB_MAX_LEN} bytes");
    assert!(len <= BLOB_MAX_LEN && 2 * len > BLOB_MAX_LEN, "{len}");
    assert!(Blob::parse(&buf[..len]).is_ok());
}
