//! The one rename table: how the host's front-ends spell a [`ControllerConfig`] field. A
//! field not in the table is spelled as it is (a flag with `-` for `_`, a scene key under
//! `controller.`). Both the flags and the errors read it, so a message names what the user
//! typed.
//!
//! [`ControllerConfig`]: softgrip::controller::ControllerConfig

/// One field the front-ends spell otherwise.
#[derive(Debug, Clone, Copy)]
pub struct Rename {
    /// The configuration's field.
    pub field: &'static str,
    /// The command-line flag, without the dashes.
    pub flag: &'static str,
    /// Where a scene sets the field when its `[controller]` table does not: the finger's
    /// key, or `tick_hz` for the tick period.
    pub scene: Option<&'static str>,
}

/// The table.
pub const RENAMES: &[Rename] = &[
    Rename {
        field: "mu",
        flag: "mu",
        scene: Some("finger.mu"),
    },
    Rename {
        field: "shape",
        flag: "shape",
        scene: Some("finger.shape"),
    },
    Rename {
        field: "k",
        flag: "k",
        scene: Some("finger.k"),
    },
    Rename {
        field: "c_m_per_n_gamma",
        flag: "c",
        scene: Some("finger.c"),
    },
    Rename {
        field: "gamma",
        flag: "gamma",
        scene: Some("finger.gamma"),
    },
    Rename {
        field: "half_length_m",
        flag: "length",
        scene: Some("finger.half_length_m"),
    },
    Rename {
        field: "n_min_n",
        flag: "n-min",
        scene: None,
    },
    Rename {
        field: "n_max_n",
        flag: "n-max",
        scene: None,
    },
    Rename {
        field: "tick_period_s",
        flag: "tick-period-s",
        scene: Some("tick_hz"),
    },
];

fn find(field: &str) -> Option<&'static Rename> {
    RENAMES.iter().find(|r| r.field == field)
}

/// The flag (without dashes) of `field`.
pub fn flag(field: &str) -> String {
    find(field).map_or_else(|| field.replace('_', "-"), |r| r.flag.to_string())
}

/// The field of a flag (without dashes), if it names one of `fields`.
pub fn field_of_flag<'a>(flag: &str, fields: &[&'a str]) -> Option<&'a str> {
    fields.iter().copied().find(|f| self::flag(f) == flag)
}

/// The scene key of `field`: `controller.FIELD` when the scene's `[controller]` table sets
/// it (`in_table`), else where the scene's finger or tick rate sets it.
pub fn scene_key(field: &str, in_table: bool) -> String {
    match find(field).and_then(|r| r.scene) {
        Some(key) if !in_table => key.to_string(),
        _ => format!("controller.{field}"),
    }
}
