//! Number formats of the report and the timing tolerance of its rankings.

/// Tick or start-up times within this factor of each other count as equal when ranking
/// (timing noise on a shared machine is a few per cent).
pub const TIME_TOLERANCE: f64 = 1.03;

/// An error or a small number, in scientific notation with one decimal.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// A time with three significant digits.
pub fn time(x: f64) -> String {
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 10.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.2}")
    }
}

/// A per-cent figure with two significant digits.
pub(super) fn pct(x: f64) -> String {
    let p = 100.0 * x;
    if p >= 10.0 {
        format!("{p:.0} %")
    } else if p >= 1.0 {
        format!("{p:.1} %")
    } else {
        format!("{p:.2} %")
    }
}

/// A relative amount: per cent from `1e-3` up, else scientific.
pub(super) fn share(x: f64) -> String {
    if x >= 1e-3 {
        pct(x)
    } else {
        format!("{} (relative)", sci(x))
    }
}
