"""softgrip.Controller: defaults, rate limits, slip raising the margin, reconfiguration."""

import math

import pytest

import softgrip

DT = 1e-3


def test_defaults_are_the_rust_defaults():
    d = softgrip.default_config()
    assert set(d) == set(softgrip.CONFIG_FIELDS)
    assert d["mu"] == 0.8 and d["shape"] == "rect" and d["k"] == 2.0 and d["skew"] is None
    assert d["safety"] == 1.35 and d["n_min_n"] == 0.2 and d["n_max_n"] == 20.0
    assert d["rise_rate_n_per_s"] == 400.0 and d["fall_rate_n_per_s"] == 20.0
    assert d["mode"] == "ellipse" and d["force_nodes"] == 48
    assert math.isinf(d["actuator_slew_n_per_s"])
    assert softgrip.Controller().config == d


def test_every_field_is_a_keyword():
    # Every field a value of its own (these are today's; a field added later goes through
    # with its default, and every name must be a field).
    chosen = dict(
        mu=0.6, shape="disc", k=4.0, skew=(0.5, 1.1, 0.25), c_m_per_n_gamma=3e-3, gamma=0.4,
        half_length_m=0.02, safety=1.5, n_min_n=0.3, n_max_n=25.0, rise_rate_n_per_s=300.0,
        fall_rate_n_per_s=10.0, tick_period_s=2e-3, stale_timeout_s=0.05, fault_force_n=5.0,
        force_range_n=50.0, moment_range_nm=1.0, mode="table", force_nodes=32,
        quadrature_order=20, table_samples=32, aspect_count=6, actuator_lag_s=0.01,
        actuator_slew_n_per_s=100.0,
    )
    assert set(chosen) <= set(softgrip.CONFIG_FIELDS)
    cfg = {**softgrip.default_config(), **chosen}
    assert list(cfg) == list(softgrip.CONFIG_FIELDS)
    c = softgrip.Controller(**cfg)
    assert c.config == cfg


def test_tick_matches_required_force_and_status_fields():
    c = softgrip.Controller()
    cmd, st = c.tick((1.0, 0.2), 0.004, DT)
    assert st.status == "ok"
    assert st.command_n == cmd == c.command_n
    # The pure rule, with the same load (|f_t| of the two components).
    assert st.required_n == pytest.approx(c.required_force(math.hypot(1.0, 0.2), 0.004), rel=1e-12)
    assert st.n_slip_n == pytest.approx(c.slip_force(math.hypot(1.0, 0.2), 0.004), rel=1e-12)
    # On a hemicylinder, N_slip is N_req at a safety factor of 1.
    assert c.slip_force(1.0, 0.004) == c.required_force(1.0, 0.004, 1.0)
    assert st.n_slip_n < st.required_n
    assert st.mu_estimate == 0.8 and st.margin == 1.0 and not st.fault_active
    assert "TickStatus(" in repr(st)


def test_rise_and_fall_rate_limits():
    c = softgrip.Controller(rise_rate_n_per_s=400.0, fall_rate_n_per_s=20.0)
    prev = c.command_n
    t = 0.0
    target = c.required_force(3.0, 0.01)
    for _ in range(100):
        t += DT
        cmd, st = c.tick(3.0, 0.01, t)
        assert cmd - prev <= 400.0 * DT + 1e-12
        prev = cmd
    assert cmd == pytest.approx(target, rel=1e-12)
    for _ in range(100):
        t += DT
        cmd, _ = c.tick(0.0, 0.0, t)
        assert prev - cmd <= 20.0 * DT + 1e-12
        assert prev - cmd == pytest.approx(20.0 * DT, rel=1e-9)
        prev = cmd


def test_slip_raises_the_margin_and_jumps():
    # Told an ideal actuator (a lag of one tick): no lead, so the command is N_req. At
    # safety 1.3 the held load's utilisation (1/1.3) is above the creep threshold (0.7),
    # so an incipient report is slip, not creep.
    c = softgrip.Controller(actuator_lag_s=0.001, safety=1.3)
    t = 0.0
    for _ in range(50):
        t += DT
        before, st0 = c.tick(1.0, 0.004, t, normal_force=c.command_n)
    # An incipient report counts once it has lasted 2 ms (one tick is sensor noise).
    t += DT
    _, st = c.tick(1.0, 0.004, t, slip="incipient", normal_force=before)
    assert st.margin == 1.0
    t += DT
    cmd, st = c.tick(1.0, 0.004, t, slip="incipient", normal_force=before)
    assert st.margin == pytest.approx(1.05)  # MARGIN_STEP_INCIPIENT
    assert st.required_n > st0.required_n
    assert cmd == pytest.approx(st.required_n)  # the emergency rise: at once, past the rate
    for _ in range(25):  # the response steps again only after 20 ms (counted in ticks)
        t += DT
        cmd, _ = c.tick(1.0, 0.004, t, normal_force=cmd)
    t += DT
    cmd2, st2 = c.tick(1.0, 0.004, t, slip="gross", normal_force=cmd)
    assert st2.margin == pytest.approx(1.35)  # + MARGIN_STEP_GROSS
    assert cmd2 > cmd
    # None and "none" are the same as no signal.
    t += DT
    _, st3 = c.tick(1.0, 0.004, t, slip="none")
    assert st3.margin == st2.margin


def test_reconfigure_carries_the_command():
    c = softgrip.Controller()
    t = 0.0
    for _ in range(100):
        t += DT
        cmd, _ = c.tick(3.0, 0.01, t)
    assert cmd > 5.0
    c.reconfigure(safety=1.5)
    assert c.command_n == cmd  # not back to n_min
    assert c.config["safety"] == 1.5
    t += DT
    cmd2, st = c.tick(3.0, 0.01, t)
    assert abs(cmd2 - cmd) <= 400.0 * DT + 1e-12  # rate limits apply from there
    # A fresh controller starts at n_min instead.
    assert softgrip.Controller(safety=1.5).command_n == 0.2


def test_reconfigure_clamps_into_the_new_range():
    c = softgrip.Controller()
    t = 0.0
    for _ in range(100):
        t += DT
        c.tick(3.0, 0.01, t)
    c.reconfigure(n_max_n=4.0, fault_force_n=4.0)
    assert c.command_n == 4.0


def test_idle_goes_stale_then_to_the_fault_force():
    c = softgrip.Controller(stale_timeout_s=0.005, fault_force_n=10.0)
    c.tick(1.0, 0.0, DT)
    outs = [c.idle() for _ in range(10)]
    assert all(st.status == "stale_input" for _, st in outs)
    assert not outs[0][1].fault_active and outs[-1][1].fault_active
    assert outs[-1][0] > outs[0][0]


def test_bad_measurements_are_faults_not_exceptions():
    c = softgrip.Controller()
    _, st = c.tick(math.nan, 0.0, DT)
    assert st.status == "sensor_fault"
    _, st = c.tick(1.0, 0.0, DT)
    assert st.status == "ok"
    _, st = c.tick(1.0, 0.0, DT)  # the same timestamp again
    assert st.status == "stale_input"


def test_a_round_patchs_moment_carries_its_own_factor():
    # The tick on a hemisphere asks for (s f_t, 1.5 s m_n): more than the plain rule under
    # a moment, the same under a force alone; N_slip stays the model's own.
    c = softgrip.Controller(shape="disc")
    _, st = c.tick((1.0, 0.0), 0.004, DT)
    assert st.required_n == pytest.approx(c.required_force(1.0, 0.004), rel=1e-12)
    assert st.n_slip_n == pytest.approx(c.slip_force(1.0, 0.004), rel=1e-12)
    assert c.required_force(1.0, 0.004, 1.0) > c.slip_force(1.0, 0.004)
    assert c.required_force(1.0, 0.0, 1.0) == c.slip_force(1.0, 0.0)



def test_the_identified_actuator_is_exposed():
    # A first-order lag of 30 ms between the command and the grip, through a load that
    # rises at 40 N/s to 4 N and falls again: the lag is identified from the told 0 (the
    # untold prior) and from a told 60 ms alike (tests/actuator_id.rs holds the method).
    tau = 0.03
    for told in (0.0, 0.06):
        c = softgrip.Controller(actuator_lag_s=told, mode="table")
        if told:
            assert c.actuator_lag_estimate_s == told
        assert math.isinf(c.actuator_slew_estimate_n_per_s)
        n, t = c.command_n, 0.0
        for _ in range(1500):
            t += DT
            ft = min(4.0, 40.0 * t) if t < 0.6 else max(0.5, 4.0 - 40.0 * (t - 0.6))
            cmd, _ = c.tick(ft, 0.0, t, normal_force=n)
            n += (cmd - n) * DT / tau
        assert c.actuator_lag_estimate_s == pytest.approx(tau, rel=0.15), told
        assert c.config["actuator_lag_s"] == told
    # A told slew is the estimate until a slew-limited tick is seen; both are read-only.
    c = softgrip.Controller(actuator_slew_n_per_s=100.0)
    assert c.actuator_slew_estimate_n_per_s == 100.0
    with pytest.raises(AttributeError):
        c.actuator_lag_estimate_s = 0.1
