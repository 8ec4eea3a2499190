"""The extension module (Rust, PyO3). Use it through ``softgrip``."""

from typing import Any, Literal, Optional, Sequence, Union

CONFIG_FIELDS: tuple[str, ...]

SlipName = Literal["none", "incipient", "gross"]
SkewArg = Union[None, float, tuple[float, float, float], dict[str, float]]

class ConfigError(ValueError):
    """A bad argument. ``param`` is the name of the parameter (the keyword)."""

    param: str

class TickStatus:
    """What one tick decided (Rust's ``TickOutput``)."""

    @property
    def status(self) -> Literal["ok", "saturated", "sensor_fault", "stale_input"]: ...
    @property
    def command_n(self) -> float:
        """The commanded normal force [N]."""
    @property
    def required_n(self) -> float:
        """N_req(s) with the present margin [N]."""
    @property
    def n_slip_n(self) -> float:
        """N_slip = N_req(1) [N]."""
    @property
    def utilisation(self) -> float:
        """The load's utilisation at the measured normal force (< 1 holds)."""
    @property
    def fault_active(self) -> bool: ...
    @property
    def iterations(self) -> int: ...
    @property
    def mu_estimate(self) -> float:
        """The friction coefficient the controller believes now."""
    @property
    def margin(self) -> float:
        """The margin multiplying the safety factor (1 until a slip signal)."""

class Controller:
    """The slip-prevention controller (f64 precompute and tick).

    Keywords are ``ControllerConfig``'s fields (defaults ``default_config()``): mu,
    shape ("rect"/"disc"), k, skew (None, Δ/a, or (Δ/a, α, h/a)), c_m_per_n_gamma [m/N^γ],
    gamma, half_length_m [m], safety, n_min_n [N], n_max_n [N], rise_rate_n_per_s [N/s],
    fall_rate_n_per_s [N/s], tick_period_s [s], stale_timeout_s [s], fault_force_n [N],
    force_range_n [N], moment_range_nm [N·m], mode ("ellipse"/"table"), force_nodes,
    quadrature_order, table_samples, aspect_count, actuator_lag_s [s],
    actuator_slew_n_per_s [N/s]. A bad value raises ConfigError naming the field.
    """

    def __init__(
        self,
        *,
        mu: float = ...,
        shape: Literal["rect", "disc"] = ...,
        k: float = ...,
        skew: SkewArg = ...,
        c_m_per_n_gamma: float = ...,
        gamma: float = ...,
        half_length_m: float = ...,
        safety: float = ...,
        n_min_n: float = ...,
        n_max_n: float = ...,
        rise_rate_n_per_s: float = ...,
        fall_rate_n_per_s: float = ...,
        tick_period_s: float = ...,
        stale_timeout_s: float = ...,
        fault_force_n: float = ...,
        force_range_n: float = ...,
        moment_range_nm: float = ...,
        mode: Literal["ellipse", "table"] = ...,
        force_nodes: int = ...,
        quadrature_order: int = ...,
        table_samples: int = ...,
        aspect_count: int = ...,
        actuator_lag_s: float = ...,
        actuator_slew_n_per_s: float = ...,
    ) -> None: ...
    def tick(
        self,
        ft: Union[float, Sequence[float]],
        mn: float,
        t: float,
        slip: Optional[SlipName] = None,
        normal_force: Optional[float] = None,
    ) -> tuple[float, TickStatus]:
        """One tick: tangential force ft [N] (|f_t| or its 2 components), torsional moment
        mn [N·m], timestamp t [s] (must increase), slip signal, measured normal force [N]
        (default: the present command). Returns (command [N], status)."""
    def idle(self) -> tuple[float, TickStatus]:
        """A tick with no measurement (counts as stale input)."""
    def reconfigure(self, **config: Any) -> None:
        """The present configuration with these fields changed; the command carries over
        (Rust's take_over_from)."""
    def reset(self) -> None: ...
    def required_force(self, ft: float, mn: float, safety: Optional[float] = None) -> Optional[float]:
        """N_req [N] of a load without touching the state (safety=1: N_slip)."""
    def utilisation(self, ft: float, mn: float, normal_force: float) -> Optional[float]: ...
    @property
    def command_n(self) -> float: ...
    @property
    def mu_estimate(self) -> float: ...
    @property
    def margin(self) -> float: ...
    @property
    def time_rejections(self) -> int: ...
    @property
    def config(self) -> dict[str, Any]: ...
    @property
    def ellipse_axes(self) -> tuple[float, float]: ...

def fls(
    shape: str, k: float, aspect: float, skew: float, alpha: float, locus: Optional[float],
    samples: int, order: int, at: Optional[list[float]],
) -> dict[str, Any]: ...
def required_force(
    ft: list[float], mn: list[float], mu: float, c: float, gamma: float, shape: str,
    length: float, k: float, safety: float, mode: str, skew: float, alpha: float,
    locus: Optional[float], n_min: float, n_max: float,
) -> dict[str, Any]: ...
def default_config() -> dict[str, Any]: ...
def half_width(c: float, gamma: float, n: float) -> float: ...
