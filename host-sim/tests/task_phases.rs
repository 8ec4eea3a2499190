//! A scene's task phases are a closed vocabulary: each `[[task]]` table's `kind` picks its
//! variant and allows that kind's keys only, so an unknown kind or another kind's key is
//! refused by name and line instead of being read as a phase that does nothing.

use host_sim::sim::scene::{Phase, Scene};

fn shipped(name: &str) -> String {
    let path = format!("{}/scenes/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(path).unwrap()
}

/// The line of the first occurrence of `needle` in `text` (1-based).
fn line_of(text: &str, needle: &str) -> usize {
    text[..text.find(needle).unwrap()].matches('\n').count() + 1
}

#[test]
fn the_shipped_phases_read_as_their_kinds() {
    let scene = Scene::parse(&shipped("lift_hold")).unwrap();
    let kinds: Vec<&str> = scene.task.iter().map(Phase::kind).collect();
    assert!(
        kinds.contains(&"lift") && kinds.contains(&"hold"),
        "{kinds:?}"
    );
    let scene = Scene::parse(&shipped("shake")).unwrap();
    assert!(scene.task.iter().any(|p| matches!(
        p,
        Phase::Shake { frequency_hz, .. } if *frequency_hz > 0.0
    )));
}

#[test]
fn an_unknown_kind_is_refused_by_name_and_line() {
    let text = shipped("lift_hold").replacen("kind = \"hold\"", "kind = \"hodl\"", 1);
    let err = Scene::parse(&text).unwrap_err().to_string();
    assert!(err.contains("hodl"), "{err}");
    assert!(err.contains("lift") && err.contains("pull"), "{err}");
    let line = line_of(&text, "[[task]]\nkind = \"hodl\"");
    assert!(
        (line..=line + 1).any(|l| err.contains(&format!("line {l}"))),
        "{err}"
    );
}

#[test]
fn another_kinds_key_is_refused_by_name() {
    let text =
        shipped("lift_hold").replacen("kind = \"hold\"", "kind = \"hold\"\nfrequency_hz = 5.0", 1);
    let err = Scene::parse(&text).unwrap_err().to_string();
    assert!(err.contains("frequency_hz"), "{err}");
    assert!(err.contains("line"), "{err}");
}

#[test]
fn a_phase_needs_an_end_after_its_start() {
    let text = shipped("lift_hold");
    assert!(text.contains("start_s = 0.3\nend_s = 1.3\n"));
    let bad = text.replacen(
        "start_s = 0.3\nend_s = 1.3\n",
        "start_s = 0.3\nend_s = 0.3\n",
        1,
    );
    let err = Scene::parse(&bad).unwrap_err().to_string();
    assert!(
        err.contains("phase \"lift\"") && err.contains("end_s > start_s"),
        "{err}"
    );
}
