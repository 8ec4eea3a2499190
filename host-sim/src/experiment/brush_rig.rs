//! The `brush` plant: the physical finger of [`crate::brush`] (elastic foundation,
//! stick–slip bristles), which softgrip does not model. Its indentation is the loaded
//! patch's half-width across the cylinder axis (the disc's radius); its slip onset is the
//! last quasi-static equilibrium of a proportional load ramp from fresh bristles
//! ([`BrushFinger::slip_onset`]). Cost: an onset about 10² equilibrium solves over the
//! patch's elements.

use super::Rig;
use crate::brush::BrushFinger;

impl Rig for BrushFinger {
    fn indentation_half_width_m(&self, normal_n: f64) -> f64 {
        BrushFinger::indentation_half_width_m(self, normal_n)
    }

    fn slip_onset(&self, normal_n: f64, ft_unit_n: f64, mn_unit_nm: f64) -> Option<(f64, f64)> {
        BrushFinger::slip_onset(self, normal_n, ft_unit_n, mn_unit_nm)
    }
}
