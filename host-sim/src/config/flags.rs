//! `--config FILE` and one flag per configuration field, generated from
//! [`ControllerConfig::default`]'s serialized fields: a new field gets its flag without an
//! edit here. A flag is spelled by the rename table ([`super::names`]); its value is parsed
//! as the default's type (a float, an integer) or, for a name (`--shape rect`, `--mode
//! table`), read by the field's serde. The flags override the file, the file the command's
//! base configuration.

use super::names::flag;
use super::overlay;
use crate::input::{read_capped_text, FINGER_CAP_BYTES};
use crate::CliError;
use clap::{value_parser, Arg, ArgMatches, Command};
use softgrip::controller::ControllerConfig;
use std::path::PathBuf;
use std::sync::OnceLock;

/// The configuration flags a command takes (`#[command(flatten)]`).
#[derive(Debug, Clone, Default)]
pub struct ConfigArgs {
    /// `--config FILE`: a TOML of configuration fields at its top level.
    pub file: Option<PathBuf>,
    /// The per-field flags given, keyed by field.
    pub flags: toml::Table,
}

/// One generated flag: the field, its flag (leaked once: clap wants `'static` names) and
/// its default's value.
struct FieldFlag {
    field: String,
    flag: &'static str,
    value_name: &'static str,
    default: toml::Value,
}

fn field_flags() -> &'static [FieldFlag] {
    static FLAGS: OnceLock<Vec<FieldFlag>> = OnceLock::new();
    FLAGS.get_or_init(|| {
        let table = toml::Table::try_from(ControllerConfig::default()).unwrap_or_default();
        super::fields()
            .iter()
            .filter_map(|f| {
                let default = table.get(*f)?.clone();
                Some(FieldFlag {
                    field: f.to_string(),
                    flag: Box::leak(flag(f).into_boxed_str()),
                    value_name: Box::leak(f.to_uppercase().into_boxed_str()),
                    default,
                })
            })
            .collect()
    })
}

impl FieldFlag {
    fn arg(&self) -> Arg {
        let arg = Arg::new(self.flag)
            .long(self.flag)
            .value_name(self.value_name)
            .help(format!(
                "Sets ControllerConfig's `{}` (its default: {}; the command's base may \
                 differ).",
                self.field, self.default
            ));
        match self.default {
            toml::Value::Float(_) => arg.value_parser(value_parser!(f64)),
            toml::Value::Integer(_) => arg.value_parser(value_parser!(i64)),
            _ => arg.value_parser(value_parser!(String)),
        }
    }

    fn value(&self, m: &ArgMatches) -> Option<toml::Value> {
        match self.default {
            toml::Value::Float(_) => m.get_one::<f64>(self.flag).map(|v| (*v).into()),
            toml::Value::Integer(_) => m.get_one::<i64>(self.flag).map(|v| (*v).into()),
            _ => m.get_one::<String>(self.flag).map(|v| v.clone().into()),
        }
    }
}

impl clap::FromArgMatches for ConfigArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = Self::default();
        args.update_from_arg_matches(m)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        if let Some(p) = m.get_one::<PathBuf>("config") {
            self.file = Some(p.clone());
        }
        for f in field_flags() {
            if let Some(v) = f.value(m) {
                self.flags.insert(f.field.clone(), v);
            }
        }
        Ok(())
    }
}

impl clap::Args for ConfigArgs {
    fn augment_args(cmd: Command) -> Command {
        let cmd = cmd.arg(
            Arg::new("config")
                .long("config")
                .value_name("FILE")
                .value_parser(value_parser!(PathBuf))
                .help(
                    "A controller configuration: a TOML of ControllerConfig fields \
                     (docs/controller.md); the per-field flags override it.",
                ),
        );
        field_flags().iter().fold(cmd, |cmd, f| cmd.arg(f.arg()))
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl ConfigArgs {
    /// The fields given: the file's, then the flags' over them, each checked for its key
    /// and type. Errors name `--config` with the file and key, or the flag.
    pub fn table(&self) -> Result<toml::Table, CliError> {
        let base = ControllerConfig::default();
        let mut table = toml::Table::new();
        if let Some(path) = &self.file {
            let text = read_capped_text(path, "--config", FINGER_CAP_BYTES)
                .map_err(|e| CliError::Usage(e.to_string()))?;
            let shown = path.display();
            table = toml::from_str(&text).map_err(|e| {
                CliError::Usage(format!("--config: {shown}: {}", e.message().trim()))
            })?;
            overlay(&base, &table)
                .map_err(|e| CliError::Usage(format!("--config: {shown}: {e}")))?;
        }
        overlay(&base, &self.flags)
            .map_err(|e| CliError::Usage(format!("--{}: {}", flag(&e.key), e.reason)))?;
        table.extend(self.flags.clone());
        Ok(table)
    }

    /// `base` with [`ConfigArgs::table`]'s fields in place of its values (not validated).
    pub fn apply(&self, base: &ControllerConfig) -> Result<ControllerConfig, CliError> {
        overlay(base, &self.table()?).map_err(|e| CliError::Usage(e.to_string()))
    }

    /// Whether the flags or the file set `field` (the file is read again: call it on
    /// errors only).
    pub fn sets(&self, field: &str) -> bool {
        self.table().is_ok_and(|t| t.contains_key(field))
    }
}
