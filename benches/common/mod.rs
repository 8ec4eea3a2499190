//! Every benchmark of `benches/tick.rs` and `benches/fls.rs`, by criterion id, with what
//! it measures. docs/host-costs.md lists exactly these, in this order, with criterion's
//! medians: `tests/host_costs.rs` renders that table from `target/criterion/ID/new/
//! estimates.json` and checks it. A bench registers its ids through [`id`], so a new
//! benchmark that is not listed here fails at `cargo bench` instead of missing from the
//! page.

/// (criterion id, what it measures).
pub const BENCHES: &[(&str, &str)] = &[
    (
        "tick_ellipse_f32_libm",
        "tick, ellipse mode, f32, libm: 256 unrelated loads in turn",
    ),
    (
        "tick_ellipse_f32_micromath",
        "tick, ellipse mode, f32, micromath: the same loads",
    ),
    (
        "tick_ellipse_f64_libm",
        "tick, ellipse mode, f64, libm: the same loads",
    ),
    (
        "tick_table_f32_libm",
        "tick, table mode, f32, libm: the same loads",
    ),
    (
        "tick_table_f32_micromath",
        "tick, table mode, f32, micromath: the same loads",
    ),
    (
        "tick_table_f64_libm",
        "tick, table mode, f64, libm: the same loads",
    ),
    (
        "tick_smooth_ellipse_f32_libm",
        "tick, ellipse mode, f32: a load turning at 1 Hz, 1 kHz ticks",
    ),
    (
        "tick_smooth_table_f32_libm",
        "tick, table mode, f32: a load turning at 1 Hz, 1 kHz ticks",
    ),
    (
        "startup_ellipse_f32",
        "start-up (`Controller::new`), ellipse mode, f32, default sizes",
    ),
    ("startup_ellipse_f64", "start-up, ellipse mode, f64"),
    ("startup_table_f32", "start-up, table mode, f32"),
    ("startup_table_f64", "start-up, table mode, f64"),
    (
        "sweep_128/rect_k2_symmetric",
        "128-point sweep into a table, rectangle `l = a`, k = 2",
    ),
    (
        "sweep_128/rect_k2_skewed",
        "128-point sweep, skewed rectangle",
    ),
    ("sweep_128/disc_k2_symmetric", "128-point sweep, disc k = 2"),
    (
        "point/rect_k2_symmetric",
        "one point (`FlsModel::point`), rectangle k = 2",
    ),
    ("point/rect_k2_skewed", "one point, skewed rectangle"),
    ("point/disc_k2_symmetric", "one point, disc k = 2"),
    (
        "point/disc_k2_skewed",
        "one point, skewed disc (a 2-D integral)",
    ),
    (
        "brute_force_point/rect_k2_d0.7_cells6",
        "brute-force point (`softgrip-reference`) at about 1e-6 (6 cells)",
    ),
    (
        "brute_force_point/rect_k2_d0.7_cells32",
        "brute-force point at about 1e-10 (32 cells)",
    ),
];

/// `id`, after checking that [`BENCHES`] lists it (a group's benchmark is
/// `"GROUP/NAME"`).
#[allow(dead_code)]
pub fn id(id: &str) -> &str {
    assert!(
        BENCHES.iter().any(|(listed, _)| *listed == id),
        "benchmark {id} is not listed in benches/common/mod.rs (docs/host-costs.md lists \
         every benchmark; tests/host_costs.rs checks it)"
    );
    id
}
