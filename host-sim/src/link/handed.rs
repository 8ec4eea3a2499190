//! Controllers precomputed once on the host and handed to the in-process devices.
//!
//! `simulate` checks every scene before the first run, and the check that catches the
//! start-up's own refusals (an `l/a` the grid cannot sample, a sensor range whose required
//! force overflows) is the precomputation itself. Its controller is not thrown away: it
//! goes into a small process-wide store, and the in-process devices (the [`direct`] and
//! [`pty`] links) take their controller from there when the host configures them with the
//! same configuration, instead of precomputing it again. So a run precomputes each
//! controller once. A configuration the store does not hold is precomputed by the device
//! as the firmware does ([`Precompute`]). The firmware in QEMU or on a board always
//! precomputes its own: the store is this process's.
//!
//! The store holds at most [`CAPACITY`] controllers, the latest kept.
//! [`precomputes`] counts every precomputation, on the host and by an in-process device,
//! for the test that a run does each once.
//!
//! [`direct`]: super::direct
//! [`pty`]: super::pty

use softgrip::controller::{Checked, Controller, ControllerConfig, TickMath};
use softgrip::device::{ControllerSource, Precompute};
use softgrip::protocol::WireConfigError;
use softgrip::BuildError;
use std::any::Any;
use std::marker::PhantomData;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Most controllers the store keeps, the oldest dropped first: `simulate` precomputes every
/// scene's before the first run, and `--all` over the shipped scenes in both modes keeps
/// 16.
pub const CAPACITY: usize = 64;

/// The kept controllers, each a `Controller<f32, M>` of some math backend `M`.
static STORE: Mutex<Vec<Box<dyn Any + Send>>> = Mutex::new(Vec::new());
static PRECOMPUTES: AtomicUsize = AtomicUsize::new(0);

/// How many controllers this process has precomputed, on the host ([`precompute`]) and in
/// its in-process devices.
pub fn precomputes() -> usize {
    PRECOMPUTES.load(Ordering::Relaxed)
}

/// The kept controller of backend `M` for `cfg`, if any.
fn kept<M: TickMath<f32> + Send + 'static>(cfg: &ControllerConfig) -> Option<Controller<f32, M>> {
    let store = STORE.lock().unwrap_or_else(|e| e.into_inner());
    store
        .iter()
        .filter_map(|c| c.downcast_ref::<Controller<f32, M>>())
        .find(|c| c.config() == cfg)
        .cloned()
}

/// Precomputes the controller of `config` with the math backend `M`, keeps a copy for the
/// in-process devices, and returns it. A configuration already kept is not precomputed
/// again.
pub fn precompute<M: TickMath<f32> + Send + 'static>(
    config: &Checked,
) -> Result<Controller<f32, M>, BuildError> {
    if let Some(c) = kept::<M>(config.config()) {
        return Ok(c);
    }
    PRECOMPUTES.fetch_add(1, Ordering::Relaxed);
    let c = Controller::<f32, M>::from_checked(config)?;
    let mut store = STORE.lock().unwrap_or_else(|e| e.into_inner());
    if store.len() == CAPACITY {
        store.remove(0);
    }
    store.push(Box::new(c.clone()));
    Ok(c)
}

/// The source of the in-process devices: the kept controller when there is one for the
/// configuration, else the firmware's precomputation.
pub struct Handed<M>(PhantomData<M>);

impl<M> Handed<M> {
    /// The source (it holds nothing: the store is the process's).
    pub fn new() -> Self {
        Self(PhantomData)
    }
}

impl<M> Default for Handed<M> {
    fn default() -> Self {
        Self::new()
    }
}

#[allow(clippy::result_large_err)]
impl<M: TickMath<f32> + Send + 'static> ControllerSource<M> for Handed<M> {
    fn build_into(
        &self,
        cfg: ControllerConfig,
        slot: &mut Controller<f32, M>,
    ) -> Result<(), WireConfigError> {
        if let Some(c) = kept::<M>(&cfg) {
            *slot = c;
            return Ok(());
        }
        PRECOMPUTES.fetch_add(1, Ordering::Relaxed);
        <Precompute<f32> as ControllerSource<M>>::build_into(&Precompute::default(), cfg, slot)
    }
}
