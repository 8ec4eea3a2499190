//! The `accuracy` command line: the quick report's sections, tables and plot, and its exit
//! code on an unwritable `--out`. No timing assertions: only that times are finite.

mod common;

use std::path::{Path, PathBuf};

fn run(args: &[&str]) -> (i32, String, String) {
    common::host_sim(&[&["accuracy"], args].concat())
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("softgrip-accuracy-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The Markdown tables of `md`: each a header row and its data rows, cells trimmed.
fn tables(md: &str) -> Vec<(Vec<String>, Vec<Vec<String>>)> {
    let cells = |line: &str| -> Vec<String> {
        line.trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect()
    };
    let mut out = Vec::new();
    let lines: Vec<&str> = md.lines().collect();
    let mut i = 0;
    while i + 1 < lines.len() {
        if lines[i].starts_with('|') && lines[i + 1].starts_with("| ---") {
            let header = cells(lines[i]);
            let mut rows = Vec::new();
            i += 2;
            while i < lines.len() && lines[i].starts_with('|') {
                let row = cells(lines[i]);
                assert_eq!(row.len(), header.len(), "ragged row: {}", lines[i]);
                rows.push(row);
                i += 1;
            }
            out.push((header, rows));
        } else {
            i += 1;
        }
    }
    out
}

/// Whether a column holds numbers: errors, times, instruction counts, ratios.
fn numeric_column(name: &str) -> bool {
    name.starts_with("err")
        || name.contains(" err")
        || name == "under-ask"
        || name == "speed ratio"
        || ["[µs]", "[ns]", "[instr]"].iter().any(|u| name.contains(u))
}

fn check_report(dir: &Path) {
    let md = std::fs::read_to_string(dir.join("accuracy.md")).unwrap();
    for head in [
        "- Machine: ",
        "- Date: ",
        "- Command: `",
        "accuracy --quick",
    ] {
        assert!(md.contains(head), "no {head:?} in the header");
    }
    for (i, title) in [
        "Quadrature order",
        "Centre-of-rotation samples per sweep",
        "Size of the aspect grid",
        "Interpolation: force nodes of the moment arm",
        "f32 against f64 precomputation",
        "libm against micromath in the tick",
        "Ellipse against table against exact integration per tick",
    ]
    .iter()
    .enumerate()
    {
        assert!(
            md.contains(&format!("## {}. {title}\n", i + 1)),
            "no section {title}"
        );
    }
    for section in [
        "## Pareto front",
        "## The defaults, and why",
        "## Brute force against the core at matched accuracy",
        "## On the emulated target",
    ] {
        assert!(md.contains(section), "no {section}");
    }
    assert!(md.contains("**speed ratio "), "no brute-force speed ratio");
    assert!(md.contains("(accuracy.svg)"), "the plot is not linked");

    let tables = tables(&md);
    assert!(tables.len() >= 12, "only {} tables", tables.len());
    let mut numbers = 0;
    for (header, rows) in &tables {
        for (c, name) in header.iter().enumerate() {
            if !numeric_column(name) {
                continue;
            }
            for row in rows {
                let cell = row[c].replace(" (relative)", "");
                if cell == "n/a" {
                    continue;
                }
                let v: f64 = cell
                    .parse()
                    .unwrap_or_else(|_| panic!("{name}: {cell:?} is not a number"));
                assert!(v.is_finite() && v >= 0.0, "{name}: {v}");
                numbers += 1;
            }
        }
    }
    assert!(numbers > 200, "only {numbers} numbers in the tables");
    // Every knob table has a Pareto column and the front is marked somewhere.
    let knob_tables = tables
        .iter()
        .filter(|(h, _)| h.first().map(String::as_str) == Some("setting"))
        .count();
    assert_eq!(knob_tables, 7);
    let pareto = tables
        .iter()
        .find(|(h, _)| h.get(1).map(String::as_str) == Some("configuration") && h[0] == "#")
        .expect("the Pareto table");
    assert!(pareto.1.iter().any(|r| r.last().unwrap().contains("tick")));
    assert!(pareto.1.iter().any(|r| r[1].contains("exact per tick")));

    let svg = std::fs::read_to_string(dir.join("accuracy.svg")).unwrap();
    assert!(svg.starts_with("<svg"), "not an SVG");
    assert!(svg.trim_end().ends_with("</svg>"));
    assert!(svg.contains("Pareto front") && svg.contains("<circle"));
}

#[test]
fn quick_report_has_every_section_finite_numbers_and_the_plot() {
    let dir = scratch("quick");
    let (code, out, err) = run(&["--quick", "--out", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "stderr: {err}");
    assert!(
        out.contains("default ellipse:") && out.contains("wrote "),
        "{out}"
    );
    check_report(&dir);
    // Not a terminal: no bar, but the phases as lines.
    assert!(
        err.contains("accuracy: core against brute force\n"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn quiet_prints_nothing_on_stderr_and_the_same_on_stdout() {
    let dir = scratch("quiet");
    let (code, out, err) = run(&["--quick", "--quiet", "--out", dir.to_str().unwrap()]);
    assert_eq!(code, 0, "stderr: {err}");
    assert!(err.is_empty(), "{err}");
    assert!(
        out.contains("default ellipse:") && out.contains("wrote "),
        "{out}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_out_under_a_regular_file_fails_with_one_line() {
    let dir = scratch("bad-out");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("plain-file");
    std::fs::write(&file, "not a directory").unwrap();
    let bad = file.join("report");
    let (code, out, err) = run(&["--quick", "--out", bad.to_str().unwrap()]);
    assert_ne!(code, 0);
    assert!(out.is_empty(), "{out}");
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.starts_with("error: --out"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
