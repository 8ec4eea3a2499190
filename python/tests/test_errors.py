"""Bad arguments raise ValueError (softgrip.ConfigError) naming the parameter."""

import math

import pytest

import softgrip


def raises_param(param, fn, *args, **kwargs):
    with pytest.raises(ValueError) as info:
        fn(*args, **kwargs)
    assert isinstance(info.value, softgrip.ConfigError)
    assert info.value.param == param
    assert str(info.value).startswith(f"{param}:"), str(info.value)
    return info.value


@pytest.mark.parametrize(
    "field,value",
    [
        ("mu", 0.0), ("mu", math.nan), ("k", 0.5), ("c_m_per_n_gamma", -1.0), ("gamma", 0.7),
        ("half_length_m", 0.0), ("safety", 0.9), ("n_min_n", 0.0), ("n_max_n", 0.1),
        ("rise_rate_n_per_s", 0.0), ("fall_rate_n_per_s", -1.0), ("tick_period_s", 0.0),
        ("stale_timeout_s", 1e-4), ("fault_force_n", 50.0), ("force_range_n", 0.0),
        ("moment_range_nm", 2e9), ("actuator_lag_s", 2.0), ("actuator_slew_n_per_s", 0.0),
        ("quadrature_order", 2), ("force_nodes", 1000), ("table_samples", 1000),
        ("shape", "cone"), ("mode", "exact"), ("force_nodes", -1),
    ],
)
def test_controller_config_errors(field, value):
    kwargs = {field: value}
    if field in ("table_samples",):
        kwargs["mode"] = "table"
    raises_param(field, softgrip.Controller, **kwargs)


def test_skew_errors_name_the_skew_fields():
    raises_param("skew", softgrip.Controller, skew=(1.5, 1.1, 0.5))
    raises_param("alpha", softgrip.Controller, skew=(0.5, -1.0, 0.25))
    raises_param("locus", softgrip.Controller, skew=(0.5, 1.1, -0.1))


def test_unknown_keyword_is_a_type_error():
    with pytest.raises(TypeError):
        softgrip.Controller(friction=0.8)


def test_reconfigure_error_keeps_the_controller():
    c = softgrip.Controller()
    c.tick(1.0, 0.0, 0.001)
    before = c.command_n
    raises_param("mu", c.reconfigure, mu=-1.0)
    assert c.command_n == before
    assert c.config["mu"] == 0.8


@pytest.mark.parametrize(
    "kwargs,param",
    [
        (dict(k=0.5), "k"), (dict(aspect=0.0), "aspect"), (dict(aspect=math.nan), "aspect"),
        (dict(skew=1.0), "skew"), (dict(alpha=math.inf, skew=0.5), "alpha"),
        (dict(samples=1), "samples"), (dict(samples=5000), "samples"),
        (dict(order=2), "order"), (dict(shape="cone"), "shape"), (dict(at=[-1.0]), "at"),
        (dict(locus=-1.0), "locus"),
    ],
)
def test_fls_errors(kwargs, param):
    raises_param(param, softgrip.fls, **kwargs)


@pytest.mark.parametrize(
    "kwargs,param",
    [
        (dict(mu=0.0), "mu"), (dict(c_m_per_n_gamma=0.0), "c_m_per_n_gamma"),
        (dict(gamma=0.6), "gamma"), (dict(half_length_m=-1.0), "half_length_m"),
        (dict(safety=0.5), "safety"), (dict(k=0.0), "k"), (dict(n_min_n=0.0), "n_min_n"),
        (dict(n_max_n=0.1), "n_max_n"), (dict(skew=1.2, mode="table"), "skew"),
        (dict(mode="exact"), "mode"), (dict(shape="cone"), "shape"),
        (dict(ft=[1.0, math.nan]), "ft"), (dict(mn=math.inf), "mn"),
    ],
)
def test_required_force_errors(kwargs, param):
    args = dict(ft=1.0, mn=0.004, mu=0.8, c_m_per_n_gamma=2.5e-3, gamma=0.5)
    args.update(kwargs)
    raises_param(param, softgrip.required_force, **args)


def test_tick_errors():
    c = softgrip.Controller()
    raises_param("slip", c.tick, 1.0, 0.0, 0.001, slip="sideways")
    raises_param("t", c.tick, 1.0, 0.0, -1.0)
    raises_param("ft", c.tick, [1.0, 2.0, 3.0], 0.0, 0.001)
