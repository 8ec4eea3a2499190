"""softgrip from Python: friction limit surfaces of soft fingertips and the slip-prevention
controller, computed by the Rust core (``softgrip`` crate) through PyO3.

Nothing numeric is done in Python: this module converts arguments and results between
numpy arrays and the extension module ``softgrip._softgrip``.

Units: forces in newtons [N], moments in newton-metres [N·m], lengths in metres [m],
times in seconds [s]; ``f``, ``m`` and ``d`` of a limit surface are dimensionless
(``f = |f_t|/(μN)``, ``m = |m_n|/(μNa)``, ``d = d_c/a``).
"""

from __future__ import annotations

import json
import tomllib
import warnings
from os import PathLike
from typing import Any, Optional, Union

import numpy as np

from . import _softgrip
from ._softgrip import CONFIG_FIELDS, ConfigError, Controller, TickStatus

__all__ = [
    "CONFIG_FIELDS",
    "CalibrationWarning",
    "calibrate",
    "load_finger",
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


def half_width(c_m_per_n_gamma: float, gamma: float, normal_force_n: float) -> float:
    """Contact half-width ``a = c·N^γ`` [m] at ``normal_force_n`` [N] (``c`` in m/N^γ)."""
    return _softgrip.half_width(float(c_m_per_n_gamma), float(gamma), float(normal_force_n))


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

    Parameters (the names of ``host-sim fls``'s flags): ``shape`` "rect" (a hemicylinder:
    the patch [-l, l] × [-a, a]) or "disc" (a hemisphere); ``k >= 1`` the
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
    *,
    mu: float = 0.8,
    c_m_per_n_gamma: float = 2.5e-3,
    gamma: float = 0.5,
    shape: str = "rect",
    half_length_m: float = 0.01,
    k: float = 2.0,
    safety: float = 1.35,
    mode: str = "ellipse",
    skew: Any = None,
    n_min_n: float = 0.2,
    n_max_n: float = 20.0,
) -> dict[str, Any]:
    """docs/model.md's slip-prevention rule for many loads, as ``host-sim required-force``.

    ``ft`` |f_t| [N] and ``mn`` |m_n| [N·m] are numbers or arrays (broadcast together; signs
    are ignored). The keywords are ``Controller``'s, with its defaults: ``mu`` the friction
    coefficient; ``c_m_per_n_gamma`` [m/N^γ] and ``gamma`` the contact law a = c·N^γ;
    ``shape`` "rect" (a hemicylinder: the patch [-l, l] × [-a, a]) or "disc" (a
    hemisphere); ``half_length_m`` the rectangle's half-length l [m]; ``k`` the pressure
    exponent; ``safety`` s >= 1; ``mode`` "ellipse" or "table"; ``skew`` the pressure
    peak's skew as ``Controller`` takes it (None, Δ/a, (Δ/a, α, h/a) or a dict; table mode
    sees it); ``n_min_n``/``n_max_n`` the controller's force grid [N].

    One controller is built (f64 precomputation, 64 force nodes, f64 libm tick) and asked
    for every load. Returns a dict of arrays shaped like the broadcast loads:
    ``normal_force`` (N_req(s) [N]), ``n_slip`` (N_req(1) [N]), ``a`` (half-width at
    ``normal_force`` [m]), ``utilisation`` (of the load at ``command``), ``status``
    ("ok"/"saturated"), ``command`` (``normal_force`` clamped into [n_min_n, n_max_n] [N]);
    and ``mode`` and ``ellipse_axes`` (the inscribed ellipse's semi-axes; (1, 1) in table
    mode). ``exact_force`` of the CLI (a reference computed by host-sim, not by the core)
    is not included.

    Raises ``ConfigError`` (a ``ValueError``) naming the bad keyword.
    """
    f_arr, m_arr = np.broadcast_arrays(np.asarray(ft, dtype=float), np.asarray(mn, dtype=float))
    shape_out = f_arr.shape
    r = _softgrip.required_force(
        f_arr.ravel().tolist(),
        m_arr.ravel().tolist(),
        mu=float(mu),
        c_m_per_n_gamma=float(c_m_per_n_gamma),
        gamma=float(gamma),
        shape=str(shape),
        half_length_m=float(half_length_m),
        k=float(k),
        safety=float(safety),
        mode=str(mode),
        skew=skew,
        n_min_n=float(n_min_n),
        n_max_n=float(n_max_n),
    )
    for key in ("normal_force", "n_slip", "a", "utilisation", "command"):
        r[key] = np.asarray(r[key], dtype=float).reshape(shape_out)
    r["status"] = np.asarray(r["status"], dtype=object).reshape(shape_out)
    r["ellipse_axes"] = tuple(r["ellipse_axes"])
    return r


def _finger_kwargs(finger: dict[str, Any], skew: Optional[dict[str, Any]]) -> dict[str, Any]:
    """A finger table's keys as ``Controller`` keywords."""
    k = finger.get("k", 2.0)
    out = dict(
        shape=finger.get("shape", "rect"),
        k=float("inf") if k is None else float(k),
        mu=float(finger["mu"]),
        c_m_per_n_gamma=float(finger["c"]),
        gamma=float(finger["gamma"]),
        half_length_m=float(finger.get("half_length_m", 0.01)),
    )
    if skew:
        out["skew"] = (
            float(skew["delta_over_a"]),
            float(skew.get("alpha", 1.1)),
            float(skew.get("locus_over_a", skew["delta_over_a"] / 2.0)),
        )
    return out


# The keys of a finger TOML's [margins] table (docs/calibration.md), Controller keywords.
_MARGIN_KEYS = ("cyclic_factor", "steady_factor", "steady_ramp_s", "disc_torsion_factor")


def _margin_kwargs(doc: dict[str, Any], path: Any) -> dict[str, Any]:
    """A finger TOML's ``[margins]`` keys as ``Controller`` keywords; another key is
    refused by name."""
    margins = doc.get("margins", {})
    for key in margins:
        if key not in _MARGIN_KEYS:
            raise ConfigError(
                f"{path}: margins.{key}: unknown key, expected one of {', '.join(_MARGIN_KEYS)}"
            )
    return {key: float(value) for key, value in margins.items()}


def load_finger(path: Union[str, PathLike]) -> dict[str, Any]:
    """The finger of a TOML file (``host-sim calibrate --out``'s, or a scene), as
    ``Controller`` keywords: ``shape`` ("rect": a hemicylinder, "disc": a hemisphere),
    ``k``, ``mu``, ``c_m_per_n_gamma`` (the file's ``c``), ``gamma``, ``half_length_m``
    and, when the file describes a skewed pressure (``[effect.skewed_pressure]``),
    ``skew``; the measured margins of its ``[margins]`` table (``cyclic_factor``,
    ``disc_torsion_factor``; docs/calibration.md). A scene's ``[controller] mu``, the μ
    its controller believes, wins over the finger's.
    ``Controller(**load_finger("finger.toml"), safety=1.3)`` runs it."""
    with open(path, "rb") as f:
        doc = tomllib.load(f)
    if "finger" not in doc:
        raise ConfigError(f"{path}: no [finger] table")
    skew = doc.get("effect", {}).get("skewed_pressure")
    out = _finger_kwargs(doc["finger"], skew)
    out.update(_margin_kwargs(doc, path))
    # A scene's controller may believe another μ than its finger's true one.
    believed = doc.get("controller", {}).get("mu")
    if believed is not None:
        out["mu"] = float(believed)
    return out


class CalibrationWarning(UserWarning):
    """A calibration whose rows contradict its fit (docs/calibration.md, "A fit the rows
    contradict"): its values do not describe the finger; the text names the likely cause."""


def calibrate(
    indentation: Union[str, PathLike],
    slip: Union[str, PathLike],
    *,
    shape: Optional[str] = None,
    half_length_m: Optional[float] = None,
    conservative: bool = False,
    friction_contact: bool = False,
    cyclic: Optional[Union[str, PathLike]] = None,
    hold: Optional[Union[str, PathLike]] = None,
) -> dict[str, Any]:
    """Fits the finger's parameters to a lab's files, as ``host-sim calibrate`` (the same
    code: the crate ``softgrip-calibrate``; docs/calibration.md).

    ``indentation``: a CSV ``normal_force_n,half_width_m``; ``slip``: a CSV
    ``normal_force_n,tangential_force_n,torsional_moment_nm``, one row per slip onset
    (docs/experiments.md). ``shape`` "rect" (a hemicylinder) or "disc" (a hemisphere);
    ``half_length_m`` the hemicylinder's half-length l [m] (measured, not fitted); each
    defaults to what the files record of the rig (``# shape = ...``, ``# half_length_m =
    ...``), else "rect" and 0.01, and one that contradicts the files is refused;
    ``conservative`` moves every parameter to the end of its 95 % interval that lowers the
    grip's capacity. ``friction_contact`` (``--friction-contact``) then takes ``mu`` from
    the pure-force onsets and refits ``c`` (on a long hemicylinder, the half-length) to
    the pure-torsion onsets: exact on pure loads, less so between them (docs/calibration.md);
    not with ``conservative``. ``cyclic`` and ``hold``, the margin protocols' files
    (``host-sim experiment cyclic``, ``hold``; docs/experiments.md), add the finger's
    margins (``--cyclic``, ``--hold``; ``conservative`` takes each factor at its interval's
    upper end).

    Returns ``host-sim calibrate --format json``'s object: each parameter under its TOML
    name (``mu``, ``k``, ``c``, ``gamma``, ``skewed_pressure``) as ``{"value", "ci95",
    "identified", "reason"}``, plus ``fit``, ``margins`` (each ``"not measured"``
    without its file) and ``safety_for_mu`` (``mu / mu_lo``, the least safety factor that
    covers ``mu``'s 95 % interval; a drift of ``mu`` you expect multiplies it); and ``finger_toml`` (the text ``--out``
    writes) and ``controller``, the fitted finger as ``Controller`` keywords.

    Raises ``ConfigError`` naming ``indentation`` or ``slip`` for a bad file (its message
    gives file:line:column) or too few rows (it states the minimum), ``shape`` or
    ``half_length_m`` for one that contradicts the files (naming both values). Warns with
    ``CalibrationWarning`` when the rows contradict the fit; the report's ``warnings``
    lists the same texts, and ``fit["lack_of_fit"]`` the test's figures.
    """
    report, toml_text = _softgrip.calibrate(
        str(indentation),
        str(slip),
        shape=None if shape is None else str(shape),
        half_length_m=None if half_length_m is None else float(half_length_m),
        conservative=bool(conservative),
        friction_contact=bool(friction_contact),
        cyclic=None if cyclic is None else str(cyclic),
        hold=None if hold is None else str(hold),
    )
    r = json.loads(report)
    r["finger_toml"] = toml_text
    doc = tomllib.loads(toml_text)
    r["controller"] = _finger_kwargs(doc["finger"], doc.get("effect", {}).get("skewed_pressure"))
    r["controller"].update(_margin_kwargs(doc, "finger_toml"))
    for text in r["warnings"]:
        warnings.warn(text, CalibrationWarning, stacklevel=2)
    return r
