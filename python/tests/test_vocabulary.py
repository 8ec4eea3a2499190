"""One vocabulary: every function that takes finger or controller settings takes them under
the configuration's field names, with its defaults, and shows them in help()."""

import inspect
import math

import pytest

import softgrip

# Keywords that are not configuration fields: the loads and the take-over force.
NOT_FIELDS = {"ft", "mn", "initial_force_n"}


def keyword_defaults(fn) -> dict:
    sig = inspect.signature(fn)
    return {
        name: p.default
        for name, p in sig.parameters.items()
        if p.kind == inspect.Parameter.KEYWORD_ONLY and name not in NOT_FIELDS
    }


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isinf(a):
        return math.isinf(b)
    return a == b


def test_controller_signature_is_the_configuration():
    kw = keyword_defaults(softgrip.Controller)
    d = softgrip.default_config()
    assert list(kw) == list(softgrip.CONFIG_FIELDS), "order and names"
    for name, default in kw.items():
        assert same(default, d[name]), (name, default, d[name])
    assert "initial_force_n" in inspect.signature(softgrip.Controller).parameters


def test_required_force_takes_the_configuration_names_and_defaults():
    kw = keyword_defaults(softgrip.required_force)
    d = softgrip.default_config()
    assert set(kw) <= set(softgrip.CONFIG_FIELDS), set(kw) - set(softgrip.CONFIG_FIELDS)
    for name, default in kw.items():
        assert same(default, d[name]), (name, default, d[name])
    # The extension's own signature agrees with the wrapper's.
    inner = keyword_defaults(softgrip._softgrip.required_force)
    assert inner == kw


def test_help_shows_the_keywords():
    text = str(inspect.signature(softgrip.Controller))
    for name in ("mu=0.8", "c_m_per_n_gamma=0.0025", "half_length_m=0.01", "initial_force_n=None"):
        assert name in text, text
    assert "hemicylinder" in softgrip.Controller.__doc__
    assert "hemicylinder" in softgrip.required_force.__doc__
    assert "hemicylinder" in softgrip.fls.__doc__


def test_required_force_defaults_equal_a_default_controller():
    # required_force builds its controller with 64 force nodes (as the CLI does).
    c = softgrip.Controller(force_nodes=64)
    r = softgrip.required_force(1.0, 0.004)
    assert r["normal_force"] == pytest.approx(c.required_force(1.0, 0.004), rel=1e-12)


def test_initial_force_takes_over_a_pre_grip_without_a_bump():
    # A 2 N pre-grip on a light load: the first command stays within one tick's fall.
    c = softgrip.Controller(initial_force_n=2.0)
    assert c.command_n == 2.0
    fall = c.config["fall_rate_n_per_s"] * c.config["tick_period_s"]
    cmd, st = c.tick(0.2, 0.0, 0.001, normal_force=2.0)
    assert st.status == "ok"
    assert cmd == pytest.approx(2.0 - fall, abs=1e-12)
    # Without it, the first command starts from n_min_n: the drop the option prevents.
    fresh = softgrip.Controller()
    cmd0, _ = fresh.tick(0.2, 0.0, 0.001, normal_force=2.0)
    assert cmd0 < 1.0
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.Controller(initial_force_n=math.nan)
    assert e.value.param == "initial_force_n"


def test_a_repeated_or_earlier_timestamp_is_refused_counted_and_holds():
    c = softgrip.Controller()
    cmd1, st1 = c.tick(1.0, 0.004, 0.010)
    assert st1.status == "ok"
    for t in (0.010, 0.009):
        cmd, st = c.tick(5.0, 0.02, t)
        assert st.status == "stale_input"
        assert cmd == cmd1  # the command holds; the refused load is not acted on
    assert c.time_rejections == 2
    cmd, st = c.tick(1.0, 0.004, 0.011)
    assert st.status == "ok"


def test_config_round_trips_every_field_through_serde():
    # The keywords, config() and default_config() all come from ControllerConfig's own
    # field list and serde implementation: same names, same order.
    d = softgrip.default_config()
    assert list(d) == list(softgrip.CONFIG_FIELDS)
    c = softgrip.Controller(skew=(0.5, 1.2, 0.2), mode="table", force_nodes=32, mu=1)
    # A plain field set through serde keeps the ones Python spells its own way.
    c.reconfigure(safety=1.5, actuator_slew_n_per_s=math.inf)
    got = c.config
    assert got["skew"] == (0.5, 1.2, 0.2)
    assert got["mode"] == "table" and got["force_nodes"] == 32 and got["mu"] == 1.0
    assert got["safety"] == 1.5 and math.isinf(got["actuator_slew_n_per_s"])
    assert softgrip.Controller(**got).config == got


def test_a_value_the_field_cannot_hold_names_the_field():
    with pytest.raises(softgrip.ConfigError) as e:
        softgrip.Controller(quadrature_order=70000)
    assert e.value.param == "quadrature_order"
    assert str(e.value).startswith("quadrature_order:")
    with pytest.raises(TypeError, match="^gamma: expected a number"):
        softgrip.Controller(gamma="0.5")
