//! `ControllerConfig` is the one list of the controller's fields: its serde implementation,
//! its `FIELDS`, the protocol's `SCHEMA`, the tables export and the Python package all
//! follow the struct, and the copies that must be written out (the Python stub and
//! `help()` signature) are checked here against it, so a field missing from one fails.

use softgrip::controller::{ControllerConfig, Mode, SkewParams};
use softgrip::protocol::SCHEMA;
use std::path::PathBuf;

fn repo_file(rel: &str) -> String {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join(rel);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The field names serde writes, sorted.
fn serde_fields() -> Vec<String> {
    let cfg = ControllerConfig {
        skew: Some(SkewParams::PAPER),
        ..ControllerConfig::DEFAULT
    };
    let value = toml::Table::try_from(cfg).unwrap();
    value.keys().cloned().collect()
}

#[test]
fn fields_are_the_serialized_fields() {
    let mut fields: Vec<String> = ControllerConfig::FIELDS
        .iter()
        .map(|f| f.to_string())
        .collect();
    fields.sort();
    assert_eq!(serde_fields(), fields);
}

#[test]
fn the_schema_lists_every_field_in_order_with_its_type() {
    let part = ControllerConfig::SCHEMA;
    assert!(SCHEMA.contains(&format!(";{part};")), "{SCHEMA}");
    assert!(
        SCHEMA.contains(&format!(";{};", SkewParams::SCHEMA)),
        "{SCHEMA}"
    );
    let listed: Vec<&str> = part
        .trim_start_matches("ControllerConfig{")
        .trim_end_matches('}')
        .split(',')
        .map(|f| f.split(':').next().unwrap())
        .collect();
    assert_eq!(listed, ControllerConfig::FIELDS);
    assert!(part.contains("skew:Option<SkewParams>,"), "{part}");
    assert!(part.contains("force_nodes:u16,"), "{part}");
}

#[test]
fn text_gives_any_subset_and_an_unknown_key_is_refused_by_name() {
    let cfg: ControllerConfig = toml::from_str("safety = 1.5\nmode = \"table\"\n").unwrap();
    assert_eq!(
        cfg,
        ControllerConfig {
            safety: 1.5,
            mode: Mode::Table,
            ..ControllerConfig::DEFAULT
        }
    );
    let empty: ControllerConfig = toml::from_str("").unwrap();
    assert_eq!(empty, ControllerConfig::DEFAULT);
    let err = toml::from_str::<ControllerConfig>("safty = 1.5\n").unwrap_err();
    assert!(err.message().contains("safty"), "{err}");
    let err = toml::from_str::<ControllerConfig>(
        "[skew]\ndelta_over_a = 0.5\nalpha = 1.1\nlocus_over_a = 0.25\nbeta = 1\n",
    )
    .unwrap_err();
    assert!(err.message().contains("beta"), "{err}");
    let json: ControllerConfig = serde_json::from_str(r#"{"n_max_n": 30.0}"#).unwrap();
    assert_eq!(json.n_max_n, 30.0);
    assert_eq!(json.mu, ControllerConfig::DEFAULT.mu);
}

#[test]
fn the_python_stub_and_signature_name_every_field() {
    let stub = repo_file("python/softgrip/_softgrip.pyi");
    let init = stub
        .split("def __init__(")
        .nth(1)
        .and_then(|s| s.split(") -> None").next())
        .expect("Controller.__init__ in the stub");
    let controller = repo_file("python/src/controller.rs");
    let signature = controller
        .split("text_signature = \"(*, mu=")
        .nth(1)
        .and_then(|s| s.split("\")]").next())
        .map(|s| format!("mu={s}"))
        .expect("Controller's text_signature");
    let named: Vec<&str> = signature
        .split(',')
        .filter_map(|p| p.split('=').next())
        .map(|n| n.trim().trim_start_matches('\\').trim())
        .collect();
    for field in ControllerConfig::FIELDS {
        assert!(
            init.contains(&format!("\n        {field}: ")),
            "python/softgrip/_softgrip.pyi: Controller.__init__ lacks {field}"
        );
        assert!(
            named.contains(field),
            "python/src/controller.rs: Controller's text_signature lacks {field}"
        );
    }
}
