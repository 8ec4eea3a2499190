//! Scene files: arbitrary text through everything `simulate` builds before it opens the
//! link (the TOML parser and checks, the effect pipeline, the controller configuration,
//! the ground truth's tables). Checks: no panic; every error is one line.
#![no_main]

use host_sim::sim::run::controller_config;
use host_sim::sim::scene::Scene;
use host_sim::sim::truth::Truth;
use libfuzzer_sys::fuzz_target;

fn build(text: &str) -> Result<(), String> {
    let scene = Scene::parse(text).map_err(|e| e.to_string())?;
    let pipeline = scene.pipeline().map_err(|e| e.to_string())?;
    let cfg = controller_config(&scene).map_err(|e| e.to_string())?;
    Truth::build(
        &scene,
        pipeline.true_skew(),
        cfg.n_min_n * 0.05,
        cfg.n_max_n * 1.5,
    )
    .map_err(|e| e.to_string())?;
    Ok(())
}

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    if let Err(e) = build(&text) {
        assert!(!e.contains('\n'), "multi-line error: {e:?}");
    }
});
