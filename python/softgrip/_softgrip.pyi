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
        """The margin multiplying the safety factor, slip_margin * load_factor (the safety
        asked is never below 1)."""
    @property
    def slip_margin(self) -> float:
        """The slip response's part of the margin: 1 until a slip signal raises it."""
    @property
    def load_factor(self) -> float:
        """The load's part of the margin: cyclic_factor while the load cycles, a factor
        ramping from 1 to steady_factor over steady_ramp_s while it is steady, else 1."""
    @property
    def lead_n(self) -> float:
        """How far the target leads the requirement for the actuator's lag [N]."""

class Controller:
    """The slip-prevention controller (f64 precompute and tick).

    Every keyword is a ``ControllerConfig`` field, with the same name, unit and default as
    ``default_config()``, the scene TOML and host-sim's flags. ``shape`` "rect" is a
    hemicylinder (the patch [-l, l] × [-a, a]), "disc" a hemisphere. ``initial_force_n``
    takes over an existing grip without a bump (default: start at ``n_min_n``). A bad
    value raises ConfigError naming the keyword.
    """

    def __init__(
        self,
        *,
        mu: float = 0.8,
        shape: Literal["rect", "disc"] = "rect",
        k: float = 2.0,
        skew: SkewArg = None,
        c_m_per_n_gamma: float = 2.5e-3,
        gamma: float = 0.5,
        half_length_m: float = 0.01,
        safety: float = 1.35,
        n_min_n: float = 0.2,
        n_max_n: float = 20.0,
        rise_rate_n_per_s: float = 400.0,
        fall_rate_n_per_s: float = 20.0,
        tick_period_s: float = 0.001,
        stale_timeout_s: float = 0.02,
        fault_force_n: float = 10.0,
        force_range_n: float = 100.0,
        moment_range_nm: float = 2.0,
        mode: Literal["ellipse", "table"] = "ellipse",
        force_nodes: int = 48,
        quadrature_order: int = 28,
        table_samples: int = 48,
        aspect_count: int = 8,
        actuator_lag_s: float = 0.0,
        actuator_slew_n_per_s: float = float("inf"),
        disc_torsion_factor: float = 1.5,
        cyclic_factor: float = 1.45,
        steady_factor: float = 0.85,
        steady_ramp_s: float = 0.5,
        slip_step_incipient: float = 0.05,
        slip_step_gross: float = 0.3,
        slip_margin_max: float = 3.0,
        creep_margin_max: float = 1.1,
        mu_floor_fraction: float = 0.5,
        untold_lag_s: float = 0.04,
        initial_force_n: Optional[float] = None,
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
        mn [N·m], timestamp t [s] on a monotonic clock (a repeated or earlier stamp is
        refused: status "stale_input", the command holds, time_rejections counts it),
        slip signal ("incipient": the patch's edge slides; "gross": the object slides;
        derive it from sliding, not creep: docs/sensor-inputs.md), measured normal force [N]
        (default: the present command). Returns (command [N], status)."""
    def idle(self) -> tuple[float, TickStatus]:
        """A tick with no measurement (counts as stale input)."""
    def reconfigure(self, **config: Any) -> None:
        """The present configuration with these fields changed; the command carries over
        (Rust's take_over_from)."""
    def reset(self) -> None: ...
    def required_force(self, ft: float, mn: float, safety: Optional[float] = None) -> Optional[float]:
        """N_req [N] of a load without touching the state: what the tick asks of a steady
        load at safety (the configured one by default); a round patch's moment carries
        a factor of 1.5 on top of it."""
    def slip_force(self, ft: float, mn: float) -> Optional[float]:
        """N_slip [N] of a load without touching the state (no safety factor)."""
    def utilisation(self, ft: float, mn: float, normal_force: float) -> Optional[float]: ...
    @property
    def command_n(self) -> float: ...
    @property
    def mu_estimate(self) -> float: ...
    @property
    def margin(self) -> float: ...
    @property
    def actuator_lag_estimate_s(self) -> float:
        """The actuator's lag identified online [s] (0: ideal, or none seen yet)."""
    @property
    def actuator_slew_estimate_n_per_s(self) -> float:
        """The actuator's slew identified online [N/s] (the configured one, inf when not
        given, until a slew-limited tick is seen)."""
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
    ft: list[float], mn: list[float], *, mu: float = 0.8, c_m_per_n_gamma: float = 2.5e-3,
    gamma: float = 0.5, shape: str = "rect", half_length_m: float = 0.01, k: float = 2.0,
    safety: float = 1.35, mode: str = "ellipse", skew: SkewArg = None, n_min_n: float = 0.2,
    n_max_n: float = 20.0,
) -> dict[str, Any]: ...
def default_config() -> dict[str, Any]: ...
def half_width(c_m_per_n_gamma: float, gamma: float, normal_force_n: float) -> float: ...
def calibrate(
    indentation: str, slip: str, *, shape: Optional[str] = None,
    half_length_m: Optional[float] = None,
    conservative: bool = False, friction_contact: bool = False,
    cyclic: Optional[str] = None, hold: Optional[str] = None,
) -> tuple[str, str]: ...
