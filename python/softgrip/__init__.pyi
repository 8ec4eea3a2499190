import os
from typing import Any, Literal, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

from ._softgrip import CONFIG_FIELDS as CONFIG_FIELDS
from ._softgrip import ConfigError as ConfigError
from ._softgrip import Controller as Controller
from ._softgrip import TickStatus as TickStatus
from ._softgrip import SkewArg

__version__: str

ArrayLike = Union[float, Sequence[float], npt.NDArray[np.float64]]

def default_config() -> dict[str, Any]: ...
def half_width(c_m_per_n_gamma: float, gamma: float, normal_force_n: float) -> float:
    """Contact half-width a = c·N^γ [m] at normal_force_n [N]."""

def fls(
    # "rect": a hemicylinder (the patch [-l, l] × [-a, a]); "disc": a hemisphere.
    shape: Literal["rect", "disc"] = "rect",
    k: float = 2.0,
    aspect: float = 1.0,
    skew: float = 0.0,
    alpha: float = 1.1,
    samples: int = 64,
    *,
    locus: Optional[float] = None,
    order: int = 28,
    at: Optional[ArrayLike] = None,
) -> dict[str, Any]:
    """One friction limit surface: arrays d (d_c/a), f (|f_t|/(μN)), m (|m_n|/(μNa)),
    pitch, ellipse (least squares), inscribed (with force overhead [%])."""

def required_force(
    ft: ArrayLike,
    mn: ArrayLike,
    *,
    mu: float = 0.8,
    c_m_per_n_gamma: float = 2.5e-3,
    gamma: float = 0.5,
    shape: Literal["rect", "disc"] = "rect",
    half_length_m: float = 0.01,
    k: float = 2.0,
    safety: float = 1.35,
    mode: Literal["ellipse", "table"] = "ellipse",
    skew: SkewArg = None,
    n_min_n: float = 0.2,
    n_max_n: float = 20.0,
) -> dict[str, Any]:
    """N_req(s) [N] for loads ft [N], mn [N·m], vectorised; as host-sim required-force.
    Keywords: Controller's, with its defaults ("rect" is a hemicylinder, "disc" a
    hemisphere)."""

def load_finger(path: Union[str, "os.PathLike[str]"]) -> dict[str, Any]:
    """A finger TOML (calibrate's --out, or a scene) as Controller keywords."""

class CalibrationWarning(UserWarning):
    """A calibration whose rows contradict its fit; the text names the likely cause."""

def calibrate(
    indentation: Union[str, "os.PathLike[str]"],
    slip: Union[str, "os.PathLike[str]"],
    *,
    shape: Optional[Literal["rect", "disc"]] = None,
    half_length_m: Optional[float] = None,
    conservative: bool = False,
    friction_contact: bool = False,
    cyclic: Optional[Union[str, "os.PathLike[str]"]] = None,
    hold: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> dict[str, Any]:
    """Fits mu, k, c, gamma and the skew to lab CSVs, and the margins to the cyclic and hold
    CSVs when given, as host-sim calibrate; returns its JSON plus finger_toml and controller
    (Controller keywords). "rect" is a hemicylinder."""
