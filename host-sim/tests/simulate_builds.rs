//! A `simulate` run builds each of its controllers once: the factory
//! (`host_sim::sim::controllers::build`) counts what it builds, and a run of two scenes
//! against every controller must have built each exactly twice, once per scene. (Its
//! configuration is checked once per scene, before the runs, and passed down.) And each
//! softgrip controller is precomputed once: the check before the runs precomputes each
//! mode of each scene, and the in-process devices take those controllers over instead of
//! precomputing their own (`host_sim::link::handed` counts every precomputation, the
//! devices' included). In a process of its own: the counts are process-wide.

use clap::Parser;
use host_sim::cmd::simulate::{run_cmd, SimulateArgs};
use host_sim::link::handed::precomputes;
use host_sim::sim::controllers::{builds, ControllerKind};
use softgrip::controller::ControllerConfig;
use std::path::PathBuf;

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    args: SimulateArgs,
}

#[test]
fn a_simulate_run_builds_each_controller_once_per_scene() {
    let dir = std::env::temp_dir().join(format!("softgrip-builds-{}", std::process::id()));
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    let shipped = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes");
    for name in ["lift_hold", "twist"] {
        let text = std::fs::read_to_string(shipped.join(format!("{name}.toml"))).unwrap();
        // Short runs: the count does not depend on the duration.
        let text = text.replace("duration_s = 3.0", "duration_s = 0.3");
        // The two scenes' controllers differ (otherwise the second scene's would be the
        // first's, kept: one precomputation for both).
        let text = match name {
            "twist" => text.replace(
                "[controller]\n",
                &format!(
                    "[controller]\nsafety = {}\n",
                    ControllerConfig::DEFAULT.safety + 0.25
                ),
            ),
            _ => text,
        };
        std::fs::write(scenes.join(format!("{name}.toml")), text).unwrap();
    }
    let cli = Cli::try_parse_from([
        "simulate",
        "--all",
        "--scenes",
        scenes.to_str().unwrap(),
        "--controller",
        "all",
        "--link",
        "direct",
        "--out",
        dir.join("out").to_str().unwrap(),
        "--quiet",
    ])
    .unwrap();
    assert!(builds().is_empty());
    assert_eq!(precomputes(), 0);
    run_cmd(&cli.args).unwrap();
    // softgrip (the scene's mode), softgrip-ellipse and softgrip-table are two
    // configurations per scene: ellipse and table.
    assert_eq!(
        precomputes(),
        2 * 2,
        "two modes of two scenes, each precomputed once"
    );
    let counts = builds();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(counts.len(), ControllerKind::ALL.len(), "{counts:?}");
    for kind in ControllerKind::ALL {
        let name = kind.name();
        assert_eq!(counts.get(name), Some(&2), "{name}: {counts:?}");
    }
}
