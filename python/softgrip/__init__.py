"""softgrip from Python: friction limit surfaces of soft fingertips and the slip-prevention
controller, computed by the Rust core (``softgrip`` crate) through PyO3.

Nothing numeric is done in Python: this module converts arguments and results between
numpy arrays and the extension module ``softgrip._softgrip``.

Units: forces in newtons [N], moments in newton-metres [N·m], lengths in metres [m],
times in seconds [s]; ``f``, ``m`` and ``d`` of a limit surface are dimensionless
(``f = |f_t|/(μN)``, ``m = |m_n|/(μNa)``, ``d = d_c/a``).
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from . import _softgrip
from ._softgrip import CONFIG_FIELDS, ConfigError, Controller, TickStatus

__all__ = [
    "CONFIG_FIELDS",
    "ConfigError",
    "Controller",
    "TickStatus",
    "default_config",
    "fls",
    "half_width",
    "required_force",
]

__version__ = "0.1.0"


def default_config() -> dict[str, Any]:
    """The defaults of ``ControllerConfig`` (``Controller()`` uses them), as a dict."""
    return _softgrip.default_config()


def half_width(c: float, gamma: float, normal_force: float) -> float:
    """Contact half-width ``a = c·N^γ`` [m] at ``normal_force`` [N] (``c`` in m/N^γ)."""
    return _softgrip.half_width(float(c), float(gamma), float(normal_force))


def fls(
    shape: str = "rect",
    k: float = 2.0,
    aspect: float = 1.0,
    skew: float = 0.0,
    alpha: float = 1.1,
    samples: int = 64,
    *,
    locus: Optional[float] = None,
    order: int = 28,
    at: Optional[Any] = None,
) -> dict[str, Any]:
    """One friction limit surface, as ``host-sim fls --format json`` computes it (f64).

    Parameters: ``shape`` "rect" (hemicylinder) or "disc" (hemisphere); ``k >= 1`` the
    pressure exponent (``float("inf")`` for uniform pressure); ``aspect`` l/a of the
    rectangle; ``skew`` Δ/a in [0, 1) (0: symmetric); ``alpha`` the skew law's rate;
    ``samples`` centres of rotation in the sweep (2..4096); ``locus`` h/a (default Δ/2);
    ``order`` quadrature nodes per side (4..128); ``at`` evaluate at these d_c/a instead of
    along the sweep.

    Returns a dict: ``d``, ``f``, ``m`` (numpy arrays: d_c/a, |f_t|/(μN), |m_n|/(μNa);
    the closing point d = ∞ is left out as by the CLI), ``pitch`` (m̃ at d = 0),
    ``star_shaped``, ``ellipse`` (least-squares fit ``f_semi_axis``, ``m_semi_axis``,
    ``rms_residual``, and the gap to the Eq. 10 ellipse ``max_radial_gap``,
    ``max_relative_gap``, ``max_gap_at``, ``max_outside``) and ``inscribed`` (the ellipse
    ellipse mode fits inside the surface: ``f_semi_axis``, ``m_over_pitch_semi_axis``,
    ``force_over_exact_max_pct``, ``force_over_exact_mean_pct`` [%]), plus the inputs.

    Raises ``ConfigError`` (a ``ValueError``) naming the bad parameter.
    """
    at_list = None if at is None else [float(x) for x in np.ravel(np.asarray(at, dtype=float))]
    r = _softgrip.fls(
        str(shape),
        float(k),
        float(aspect),
        float(skew),
        float(alpha),
        None if locus is None else float(locus),
        int(samples),
        int(order),
        at_list,
    )
    for key in ("d", "f", "m"):
        r[key] = np.asarray(r[key], dtype=float)
    return r


def required_force(
    ft: Any,
    mn: Any,
    mu: float,
    c: float,
    gamma: float,
    *,
    shape: str = "rect",
    length: float = 0.01,
    k: float = 2.0,
    safety: float = 1.3,
    mode: str = "ellipse",
    skew: float = 0.0,
    alpha: float = 1.1,
    locus: Optional[float] = None,
    n_min: float = 0.2,
    n_max: float = 20.0,
) -> dict[str, Any]:
    """docs/model.md's slip-prevention rule for many loads, as ``host-sim required-force``.

    ``ft`` |f_t| [N] and ``mn`` |m_n| [N·m] are numbers or arrays (broadcast together; signs
    are ignored); ``mu`` the friction coefficient; ``c`` [m/N^γ] and ``gamma`` the contact
    law a = c·N^γ; ``length`` the rectangle's half-length l [m]; ``safety`` s >= 1;
    ``mode`` "ellipse" or "table"; ``skew``/``alpha``/``locus`` the pressure peak's skew
    (table mode sees it); ``n_min``/``n_max`` the controller's force grid [N].

    One controller is built (f64 precomputation, 64 force nodes, f64 libm tick) and asked
    for every load. Returns a dict of arrays shaped like the broadcast loads:
    ``normal_force`` (N_req(s) [N]), ``n_slip`` (N_req(1) [N]), ``a`` (half-width at
    ``normal_force`` [m]), ``utilisation`` (of the load at ``command``), ``status``
    ("ok"/"saturated"), ``command`` (``normal_force`` clamped into [n_min, n_max] [N]); and
    ``mode`` and ``ellipse_axes`` (the inscribed ellipse's semi-axes; (1, 1) in table mode).
    ``exact_force`` of the CLI (a reference computed by host-sim, not by the core) is not
    included.

    Raises ``ConfigError`` (a ``ValueError``) naming the bad parameter.
    """
    f_arr, m_arr = np.broadcast_arrays(np.asarray(ft, dtype=float), np.asarray(mn, dtype=float))
    shape_out = f_arr.shape
    r = _softgrip.required_force(
        f_arr.ravel().tolist(),
        m_arr.ravel().tolist(),
        float(mu),
        float(c),
        float(gamma),
        str(shape),
        float(length),
        float(k),
        float(safety),
        str(mode),
        float(skew),
        float(alpha),
        None if locus is None else float(locus),
        float(n_min),
        float(n_max),
    )
    for key in ("normal_force", "n_slip", "a", "utilisation", "command"):
        r[key] = np.asarray(r[key], dtype=float).reshape(shape_out)
    r["status"] = np.asarray(r["status"], dtype=object).reshape(shape_out)
    r["ellipse_axes"] = tuple(r["ellipse_axes"])
    return r
