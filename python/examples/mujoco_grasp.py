#!/usr/bin/env python3
"""A parallel gripper in MuJoCo lifts a box, holds it, shakes it and twists it, with the
grip force set every 1 ms step by ``softgrip.Controller`` and, for comparison, by
constant-force and Coulomb (``s·f_t/μ``) baselines.

    python python/examples/mujoco_grasp.py [--json] [--plot out.png] [--duration S]
    python python/examples/mujoco_grasp.py --sweep 1.0,1.2,1.35,1.5,1.75
    python python/examples/mujoco_grasp.py --finger lab/finger.toml

``--sweep`` runs softgrip in both modes at each listed safety factor instead, and prints a
Markdown table of their mean force over the least constant grip that holds the scene.
``--finger FILE`` gives softgrip's controllers another finger (a finger TOML, e.g. the one
``mujoco_rig.py`` calibrates on these fingertips); the scene stays as it is.

Each fingertip is a soft hemisphere (condim 6, elliptic cone). Each step reads each
fingertip's contact wrench with ``mj_contactForce``, takes the tangential force and the
torsional moment (and the normal force the contact has now), and hands them to one
``softgrip.Controller`` per finger; the gripper squeezes with the larger of the two
commands. The box is grasped 15 mm off its centre of mass, so gravity loads the
fingertips in torsion as well as in shear.

MuJoCo's torsional friction coefficient (a length, m_n <= μ_t·N) is set from softgrip's
finger model at the operating force ``N*``: ``μ_t = μ·a(N*)·pitch``, with ``a = c·N^γ``
and the pitch of softgrip's limit surface. The script also prints how far MuJoCo's fixed
elliptic cone is from softgrip's limit surface over the normal-force range.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from dataclasses import asdict, dataclass, field
from typing import Callable, Optional

import mujoco
import numpy as np

import softgrip

# --- The fingertip (softgrip's finger model) -----------------------------------------------
FINGER = dict(
    shape="disc",  # a hemispherical fingertip: a disc patch of radius a
    mu=0.8,
    k=2.0,
    c_m_per_n_gamma=2.5e-3,  # a = c·N^γ [m]
    gamma=1.0 / 3.0,  # Hertz's exponent for a sphere
)
# The scene's safety factor: it fixes the operating force N* (softgrip's ellipse-mode
# N_req at 1.3, as the scene was first defined, so the scene does not move with the
# library's defaults) and is the Coulomb baseline's margin. softgrip itself runs at its
# own defaults (ellipse mode at 1.35, chosen on the bench's held-out seeds).
SAFETY = 1.3
SCENE_MODE = "ellipse"
N_MIN, N_MAX = 0.2, 20.0

# --- The scene -------------------------------------------------------------------------------
BOX_MASS = 0.2  # [kg]
BOX_HALF = (0.06, 0.02, 0.02)  # half-extents [m]; the fingers squeeze along y
GRASP_OFFSET = 0.010  # grasp point from the box's centre of mass, along x [m]
TIP_RADIUS = 0.01  # [m]
DT = 1e-3  # [s]
# Held: at the end the box sits in the grasp within these of where it was at the lift.
HELD_SLIP_M, HELD_ROT_DEG = 2e-3, 2.0
ACTUATOR_LAG = 3e-3  # first-order lag of the finger actuator [s], the same for every run

# MuJoCo's contact, shared with the calibration rig (mujoco_rig.py) so that the finger it
# calibrates is this one: the solver's options, every geom's soft-contact parameters, the
# box's friction and the fingertips' (MuJoCo takes the larger of two geoms' coefficients,
# so a tip–box contact has the tip's).
CONTACT_OPTIONS = f'timestep="{DT}" cone="elliptic" impratio="100" noslip_iterations="20"'
GEOM_SOFTNESS = 'solref="0.004 1" solimp="0.95 0.99 0.001"'
BOX_FRICTION = "0.1 0.00001 0.00001"
TIP_MASS = 0.02  # [kg]


def tip_friction(mu_t: float) -> str:
    """A fingertip's MuJoCo friction: sliding μ, torsional ``mu_t`` [m], rolling."""
    return f"{FINGER['mu']} {mu_t} 0.00001"


# Phases [s]: close, lift, hold, shake, twist, hold.
T_CLOSE, T_LIFT, T_HOLD1, T_SHAKE, T_TWIST, T_END = 0.3, 1.0, 1.4, 2.4, 3.4, 4.0
LIFT_HEIGHT = 0.10  # [m]
SHAKE_AMPLITUDE, SHAKE_HZ = 0.03, 4.0  # [m], [Hz]: 19 m/s² peak
TWIST_AMPLITUDE, TWIST_HZ = math.radians(30.0), 2.0  # about the grip axis


def operating_force() -> float:
    """``N*``: what softgrip's model rule asks to hold the box still (the hold phase's
    load) at the scene's safety factor, ``N_slip`` of the load scaled by it, on the rule's
    64-node grid. The tick's extra factor on a round patch's moment
    (``DISC_TORSION_SAFETY_FACTOR``, which ``required_force`` includes) is left out, so the
    scene stays as first defined."""
    g = 9.81
    ft = BOX_MASS * g / 2.0
    mn = BOX_MASS * g * GRASP_OFFSET / 2.0
    ctl = softgrip.Controller(**FINGER, mode=SCENE_MODE, force_nodes=64)
    return float(ctl.slip_force(SAFETY * ft, SAFETY * mn))


def disc_pitch() -> float:
    """The pitch ``m̃(0) = max |m_n|/(μNa)`` of softgrip's disc surface (k = 2)."""
    return float(softgrip.fls(shape="disc", k=FINGER["k"], samples=64)["pitch"])


def torsional_coefficient(n_star: float) -> float:
    """MuJoCo's torsional friction ``μ_t`` [m] matching softgrip's finger at ``n_star``."""
    a = softgrip.half_width(FINGER["c_m_per_n_gamma"], FINGER["gamma"], n_star)
    return FINGER["mu"] * a * disc_pitch()


def mjcf(mu_t: float) -> str:
    """The scene: floor, box, a gripper base on x/z slides and a hinge about the grip
    axis (position servos), two fingers on y slides (force actuators)."""
    bx, by, bz = BOX_HALF
    gap = by + TIP_RADIUS + 0.004  # fingers start 4 mm off the box
    z0 = bz  # box centre height at rest
    return f"""
<mujoco model="softgrip_grasp">
  <option {CONTACT_OPTIONS} gravity="0 0 -9.81"/>
  <default>
    <geom {GEOM_SOFTNESS}/>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1" contype="1" conaffinity="1"
          friction="0.5 0.0001 0.0001"/>
    <body name="box" pos="{GRASP_OFFSET} 0 {z0}">
      <freejoint/>
      <geom name="box" type="box" size="{bx} {by} {bz}" mass="{BOX_MASS}"
            contype="1" conaffinity="1" condim="6" friction="{BOX_FRICTION}"
            rgba="0.8 0.5 0.2 1"/>
    </body>
    <body name="base" pos="0 0 {z0}">
      <joint name="x" type="slide" axis="1 0 0" damping="50"/>
      <joint name="z" type="slide" axis="0 0 1" damping="50"/>
      <joint name="ry" type="hinge" axis="0 1 0" damping="2"/>
      <geom type="box" size="0.015 {gap + 0.01} 0.005" pos="0 0 0.05" mass="1.0"
            contype="0" conaffinity="0" rgba="0.4 0.4 0.4 1"/>
      <body name="left" pos="0 {-gap} 0">
        <joint name="yl" type="slide" axis="0 1 0" damping="5" range="-0.01 0.03"/>
        <geom type="capsule" fromto="0 0 0.005 0 0 0.05" size="0.004" mass="0.05"
              contype="0" conaffinity="0"/>
        <geom name="tip_l" type="sphere" size="{TIP_RADIUS}" mass="{TIP_MASS}" condim="6"
              contype="2" conaffinity="1" friction="{tip_friction(mu_t)}"
              rgba="0.2 0.6 0.9 1"/>
      </body>
      <body name="right" pos="0 {gap} 0">
        <joint name="yr" type="slide" axis="0 1 0" damping="5" range="-0.03 0.01"/>
        <geom type="capsule" fromto="0 0 0.005 0 0 0.05" size="0.004" mass="0.05"
              contype="0" conaffinity="0"/>
        <geom name="tip_r" type="sphere" size="{TIP_RADIUS}" mass="{TIP_MASS}" condim="6"
              contype="2" conaffinity="1" friction="{tip_friction(mu_t)}"
              rgba="0.2 0.6 0.9 1"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="ax" joint="x" kp="4000"/>
    <position name="az" joint="z" kp="4000"/>
    <position name="ary" joint="ry" kp="60"/>
    <motor name="fl" joint="yl" gear="1" ctrlrange="0 {N_MAX}" ctrllimited="true"/>
    <motor name="fr" joint="yr" gear="-1" ctrlrange="0 {N_MAX}" ctrllimited="true"/>
  </actuator>
</mujoco>
"""


def smooth(u: float) -> float:
    """Min-jerk ramp 0 → 1 for u in [0, 1]."""
    u = min(max(u, 0.0), 1.0)
    return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u)


def base_target(t: float) -> tuple[float, float, float]:
    """(x, z, θ_y) of the gripper base at time t."""
    z = LIFT_HEIGHT * smooth((t - T_CLOSE) / (T_LIFT - T_CLOSE))
    x = 0.0
    if T_HOLD1 <= t < T_SHAKE:
        w = 2 * math.pi * SHAKE_HZ
        x = SHAKE_AMPLITUDE * math.sin(w * (t - T_HOLD1))
    th = 0.0
    if T_SHAKE <= t < T_TWIST:
        w = 2 * math.pi * TWIST_HZ
        th = TWIST_AMPLITUDE * math.sin(w * (t - T_SHAKE))
    return x, z, th


@dataclass
class Tip:
    """One fingertip's contact: tangential force [N], torsional moment [N·m], normal [N]."""

    ft: float = 0.0
    mn: float = 0.0
    n: float = 0.0


def tip_wrenches(model, data, box_geom: int, tips: tuple[int, int]) -> tuple[Tip, Tip]:
    """Each fingertip's contact wrench with the box (summed over its contacts)."""
    out = (Tip(), Tip())
    f6 = np.zeros(6)
    for i in range(data.ncon):
        g1, g2 = int(data.contact.geom1[i]), int(data.contact.geom2[i])
        for j, tip in enumerate(tips):
            if {g1, g2} == {tip, box_geom}:
                mujoco.mj_contactForce(model, data, i, f6)
                # Contact frame: normal, two tangents; f6 = (N, t1, t2, m_n, r1, r2).
                out[j].n += f6[0]
                out[j].ft += math.hypot(f6[1], f6[2])
                out[j].mn += abs(f6[3])
    return out


class Grip:
    """A grip-force policy: called once per step with both fingertips' loads."""

    name = "?"

    def command(self, t: float, tips: tuple[Tip, Tip]) -> float:  # pragma: no cover
        raise NotImplementedError


class Constant(Grip):
    def __init__(self, force: float):
        self.force = force
        self.name = f"constant {force:g} N"

    def command(self, t, tips):
        return self.force


class Coulomb(Grip):
    """``N = s·f_t/μ`` per finger (torsion ignored), the larger of the two, clamped."""

    name = "coulomb s·f_t/μ"

    def command(self, t, tips):
        n = max(SAFETY * tip.ft / FINGER["mu"] for tip in tips)
        return min(max(n, N_MIN), N_MAX)


class Softgrip(Grip):
    """One ``softgrip.Controller`` per fingertip; the gripper applies the larger command."""

    name = "softgrip"

    def __init__(self, finger: Optional[dict] = None, **overrides):
        # The controller is told the actuator's lag, so it commands ahead of a rising load;
        # its mode and safety factor are the library's defaults. `finger`: Controller
        # keywords of another finger (softgrip.load_finger's), FINGER by default.
        cfg = dict(
            FINGER if finger is None else finger,
            n_min_n=N_MIN,
            n_max_n=N_MAX,
            tick_period_s=DT,
            actuator_lag_s=ACTUATOR_LAG,
        )
        cfg.update(overrides)
        self.ctl = [softgrip.Controller(**cfg), softgrip.Controller(**cfg)]
        self.last = None

    def command(self, t, tips):
        outs = [
            c.tick(tip.ft, tip.mn, t, normal_force=tip.n) for c, tip in zip(self.ctl, tips)
        ]
        self.last = outs
        return max(cmd for cmd, _ in outs)


@dataclass
class Result:
    controller: str
    held: bool
    slip_mm: float  # net slide of the box in the grasp at the end (in the x–z plane) [mm]
    rotation_deg: float  # net turn of the box in the grasp about the grip axis at the end
    peak_slip_mm: float  # largest excursion on the way (includes the contacts' compliance)
    peak_rotation_deg: float
    mean_force_n: float  # mean commanded grip force from the lift on
    peak_force_n: float
    final_height_mm: float
    trace: dict = field(default_factory=dict, repr=False)


def box_in_base(data, box_body: int, base_body: int) -> tuple[np.ndarray, float]:
    """The box's position [m] and its rotation about the grip axis [rad] in the base frame."""
    rb = data.xmat[base_body].reshape(3, 3)
    p = rb.T @ (data.xpos[box_body] - data.xpos[base_body])
    r = rb.T @ data.xmat[box_body].reshape(3, 3)
    return p, math.atan2(r[0, 2], r[0, 0])


def run(policy: Grip, mu_t: float, duration: float = T_END, keep_trace: bool = False) -> Result:
    """Simulates one grasp with ``policy`` setting the grip force. Returns the measures."""
    model = mujoco.MjModel.from_xml_string(mjcf(mu_t))
    data = mujoco.MjData(model)
    gid = lambda n: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, n)  # noqa: E731
    bid = lambda n: mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, n)  # noqa: E731
    box_geom, tips_g = gid("box"), (gid("tip_l"), gid("tip_r"))
    box_body, base_body = bid("box"), bid("base")
    steps = int(round(duration / DT))
    applied = 0.0
    ref = None
    slip = rot = 0.0
    forces = []
    tr = {k: [] for k in ("t", "command", "applied", "ft", "mn", "n", "slip_mm", "rot_deg")}
    tips = (Tip(), Tip())
    for i in range(steps):
        t = (i + 1) * DT
        cmd = policy.command(t, tips)
        # The actuator follows the command with a first-order lag.
        applied += (cmd - applied) * (DT / (ACTUATOR_LAG + DT))
        x, z, th = base_target(t)
        data.ctrl[:] = [x, z, th, applied, applied]
        mujoco.mj_step(model, data)
        tips = tip_wrenches(model, data, box_geom, tips_g)
        p, a = box_in_base(data, box_body, base_body)
        if ref is None and t >= T_CLOSE:
            ref = (p.copy(), a)  # the grasp as it is when the lift starts
        if ref is not None:
            # The fingers float together along y: only the x–z plane is slip.
            dp = float(np.hypot(p[0] - ref[0][0], p[2] - ref[0][2]))
            slip = max(slip, dp)
            rot = max(rot, abs(a - ref[1]))
            forces.append(cmd)
        if keep_trace:
            tr["t"].append(t)
            tr["command"].append(cmd)
            tr["applied"].append(applied)
            tr["ft"].append(max(tp.ft for tp in tips))
            tr["mn"].append(max(tp.mn for tp in tips))
            tr["n"].append(min(tp.n for tp in tips))
            tr["slip_mm"].append(1e3 * dp if ref else 0.0)
            tr["rot_deg"].append(math.degrees(abs(a - ref[1])) if ref else 0.0)
    height = float(data.xpos[box_body][2] - BOX_HALF[2])
    p, a = box_in_base(data, box_body, base_body)
    net_slip = float(np.hypot(p[0] - ref[0][0], p[2] - ref[0][2])) if ref else 0.0
    net_rot = abs(a - ref[1]) if ref else 0.0
    # Held: lifted, and at the end neither slid 2 mm nor turned 2° in the grasp for good.
    lifted = height > 0.8 * LIFT_HEIGHT if duration >= T_LIFT else True
    held = lifted and net_slip < HELD_SLIP_M and net_rot < math.radians(HELD_ROT_DEG)
    return Result(
        controller=policy.name,
        held=bool(held),
        slip_mm=1e3 * net_slip,
        rotation_deg=math.degrees(net_rot),
        peak_slip_mm=1e3 * slip,
        peak_rotation_deg=math.degrees(rot),
        mean_force_n=float(np.mean(forces)) if forces else 0.0,
        peak_force_n=float(np.max(forces)) if forces else 0.0,
        final_height_mm=1e3 * height,
        trace=tr if keep_trace else {},
    )


def cone_vs_fls(mu_t: float, forces=(0.5, 1.0, 2.0, 5.0, 10.0, 20.0)) -> list[dict]:
    """How far MuJoCo's elliptic cone ``(f/(μN))² + (m/(μ_t N))² = 1`` is from softgrip's
    limit surface at each normal force, radially along softgrip's surface points: positive
    means MuJoCo lets the contact carry more than softgrip's finger can (it holds where the
    real finger slips). The surface (in f̃ = f/(μN), m̃ = m/(μNa)) comes from softgrip.fls."""
    surf = softgrip.fls(shape="disc", k=FINGER["k"], samples=256)
    mu = FINGER["mu"]
    rows = []
    for n in forces:
        a = softgrip.half_width(FINGER["c_m_per_n_gamma"], FINGER["gamma"], n)
        f = mu * n * surf["f"]  # [N]
        m = mu * n * a * surf["m"]  # [N·m]
        # The cone's radius along the ray through each surface point, over the point's.
        rho = 1.0 / np.sqrt((f / (mu * n)) ** 2 + (m / (mu_t * n)) ** 2)
        gap = 100.0 * (rho - 1.0)
        rows.append(
            dict(
                normal_force_n=n,
                a_mm=1e3 * a,
                torsion_mujoco_nm=mu_t * n,
                torsion_softgrip_nm=mu * n * a * surf["pitch"],
                torsion_gap_pct=100.0 * (mu_t / (mu * a * surf["pitch"]) - 1.0),
                max_gap_pct=float(gap.max()),
                min_gap_pct=float(gap.min()),
                mean_abs_gap_pct=float(np.mean(np.abs(gap))),
            )
        )
    return rows


def baselines(finger: Optional[dict] = None) -> list[Grip]:
    constants = [Constant(f) for f in (4.0, 6.0, 8.0, 10.0, 12.0, 16.0)]
    return [Softgrip(finger), Coulomb()] + constants


def least_holding_constant(
    results: list[Result], mu_t: float, duration: float = T_END, step_n: float = 0.5
) -> Optional[float]:
    """The least constant grip on a `step_n` grid that holds the scene: the coarse
    table's weakest holding constant, refined down in `step_n` steps to just above its
    strongest failing one. A reference chosen knowing the scene, not a controller (the
    bench's clairvoyant constant grip)."""
    # A constant grip's mean command is its force: no name to parse.
    coarse = sorted(
        (r.mean_force_n, r.held) for r in results if r.controller.startswith("constant")
    )
    holding = [f for f, held in coarse if held]
    if not holding:
        return None
    best = holding[0]
    failing = max((f for f, held in coarse if not held and f < best), default=0.0)
    f = best - step_n
    while f > failing + 1e-9:
        if not run(Constant(f), mu_t, duration).held:
            break
        best = f
        f -= step_n
    return best


def safety_sweep(
    safeties: list[float],
    mu_t: float,
    least_n: Optional[float],
    duration: float = T_END,
    finger: Optional[dict] = None,
) -> list[dict]:
    """softgrip in each mode at each safety factor: held, mean force and its ratio to the
    least holding constant grip (`None` when no constant of the grid holds)."""
    rows = []
    for s in safeties:
        row = dict(safety=s)
        for mode in ("ellipse", "table"):
            r = run(Softgrip(finger, mode=mode, safety=s), mu_t, duration)
            row[mode] = dict(
                held=r.held,
                mean_force_n=r.mean_force_n,
                over_least=r.mean_force_n / least_n if least_n else None,
                rotation_deg=r.rotation_deg,
            )
        rows.append(row)
    return rows


def print_sweep(rows: list[dict], least_n: Optional[float]) -> None:
    default = softgrip.default_config()
    ref = f"{least_n:g} N" if least_n else "no holding constant"
    print(f"| safety | ellipse: mean N (× {ref}) | table: mean N (× {ref}) |")
    print("| ---: | ---: | ---: |")
    for row in rows:
        cells = []
        for mode in ("ellipse", "table"):
            c = row[mode]
            ratio = f" ({c['over_least']:.3f})" if c["over_least"] is not None else ""
            text = f"{c['mean_force_n']:.2f}{ratio}" + ("" if c["held"] else ", drops")
            if mode == default["mode"] and abs(row["safety"] - default["safety"]) < 1e-9:
                text = f"**{text}**"
            cells.append(text)
        safety = f"{row['safety']:.2f}"
        safety = safety[:-1] if safety.endswith("0") else safety
        print(f"| {safety} | {cells[0]} | {cells[1]} |")


def main(argv: Optional[list[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    ap.add_argument("--plot", metavar="PNG", help="draw the forces and the slip into PNG")
    ap.add_argument("--duration", type=float, default=T_END, help="seconds to simulate")
    ap.add_argument(
        "--sweep",
        metavar="S1,S2,...",
        help="run softgrip in both modes at these safety factors and print a Markdown table",
    )
    ap.add_argument(
        "--finger",
        metavar="TOML",
        help="softgrip's finger from this finger TOML (the scene keeps FINGER)",
    )
    args = ap.parse_args(argv)
    finger = softgrip.load_finger(args.finger) if args.finger else None

    n_star = operating_force()
    mu_t = torsional_coefficient(n_star)
    if args.sweep:
        safeties = [float(x) for x in args.sweep.split(",") if x.strip()]
        constants = [p for p in baselines() if isinstance(p, Constant)]
        coarse = [run(p, mu_t, args.duration) for p in constants]
        least_n = least_holding_constant(coarse, mu_t, args.duration)
        rows = safety_sweep(safeties, mu_t, least_n, args.duration, finger)
        if args.json:
            json.dump(dict(least_holding_constant_n=least_n, rows=rows), sys.stdout, indent=2)
            print()
        else:
            print_sweep(rows, least_n)
        return 0
    results = [
        run(p, mu_t, args.duration, keep_trace=bool(args.plot)) for p in baselines(finger)
    ]
    cone = cone_vs_fls(mu_t, sorted({0.5, 1.0, 2.0, 5.0, 10.0, 20.0, round(n_star, 3)}))
    soft = results[0]
    holding_constants = [
        r for r in results if r.controller.startswith("constant") and r.held
    ]
    weakest = min(holding_constants, key=lambda r: r.mean_force_n, default=None)
    least_n = least_holding_constant(results, mu_t, args.duration)
    verdict = dict(
        softgrip_holds=soft.held,
        weakest_holding_constant=weakest.controller if weakest else None,
        softgrip_mean_below_every_holding_constant=bool(
            soft.held and all(soft.mean_force_n < r.mean_force_n for r in holding_constants)
        ),
        least_holding_constant_n=least_n,
        softgrip_mean_over_least_holding_constant=(
            soft.mean_force_n / least_n if least_n else None
        ),
    )

    if args.json:
        out = dict(
            finger=FINGER,
            # An infinite k (uniform pressure) is null, as calibrate's JSON writes it.
            softgrip_finger={
                key: None if isinstance(v, float) and math.isinf(v) else v
                for key, v in (FINGER if finger is None else finger).items()
            },
            safety=SAFETY,
            softgrip_config={k: softgrip.default_config()[k] for k in ("mode", "safety")},
            operating_force_n=n_star,
            mujoco_torsional_friction_m=mu_t,
            results=[{k: v for k, v in asdict(r).items() if k != "trace"} for r in results],
            cone_vs_fls=cone,
            verdict=verdict,
        )
        json.dump(out, sys.stdout, indent=2)
        print()
    else:
        print(
            f"finger: {FINGER['shape']} k={FINGER['k']} mu={FINGER['mu']} "
            f"a={FINGER['c_m_per_n_gamma'] * 1e3:g} mm·N^{FINGER['gamma']:.3g}; "
            f"operating force N* = {n_star:.3f} N; MuJoCo torsional friction "
            f"mu_t = mu·a(N*)·pitch = {mu_t * 1e3:.4f} mm"
        )
        if finger is not None:
            print(f"softgrip's finger, from {args.finger}: {finger}")
        print()
        print(
            f"{'controller':<18} {'held':>5} {'slip mm':>8} {'rot deg':>8} "
            f"{'mean N':>7} {'peak N':>7} {'height mm':>9}"
        )
        for r in results:
            print(
                f"{r.controller:<18} {'yes' if r.held else 'NO':>5} {r.slip_mm:>8.2f} "
                f"{r.rotation_deg:>8.2f} {r.mean_force_n:>7.2f} {r.peak_force_n:>7.2f} "
                f"{r.final_height_mm:>9.1f}"
            )
        print()
        print("MuJoCo's elliptic cone vs softgrip's limit surface (disc, k = 2); gap = the")
        print("cone's radius over the surface's along each load direction − 1 (+: MuJoCo")
        print("holds loads the finger would slip under)")
        print(
            f"{'N [N]':>6} {'a [mm]':>7} {'torsion MJ':>11} {'torsion sg':>11} "
            f"{'torsion %':>10} {'max %':>7} {'min %':>7} {'mean|.| %':>9}"
        )
        for c in cone:
            print(
                f"{c['normal_force_n']:>6g} {c['a_mm']:>7.3f} {c['torsion_mujoco_nm']:>11.3e} "
                f"{c['torsion_softgrip_nm']:>11.3e} {c['torsion_gap_pct']:>+10.1f} "
                f"{c['max_gap_pct']:>+7.1f} {c['min_gap_pct']:>+7.1f} {c['mean_abs_gap_pct']:>9.1f}"
            )
        print()
        print(
            "softgrip holds: {softgrip_holds}; weakest constant grip that holds: "
            "{weakest_holding_constant}; softgrip's mean force below every constant grip "
            "that holds: {softgrip_mean_below_every_holding_constant}".format(**verdict)
        )
        if least_n:
            print(
                f"least constant grip that holds, on a 0.5 N grid (chosen knowing the "
                f"scene): {least_n:g} N; softgrip's mean force over it: "
                f"{soft.mean_force_n / least_n:.3f}"
            )
    if args.plot:
        plot(results, cone, args.plot)
    return 0


def plot(results: list[Result], cone: list[dict], path: str) -> None:
    try:
        import matplotlib
    except ImportError:
        sys.exit("--plot needs matplotlib: pip install matplotlib")

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(10, 10), sharex=True)
    for r in results:
        tr = r.trace
        style = dict(lw=2.0) if r.controller == "softgrip" else dict(lw=0.8, alpha=0.7)
        axes[0].plot(tr["t"], tr["command"], label=r.controller, **style)
        axes[1].plot(tr["t"], tr["slip_mm"], label=r.controller, **style)
        axes[2].plot(tr["t"], tr["rot_deg"], label=r.controller, **style)
    soft = results[0].trace
    ax0b = axes[0].twinx()
    ax0b.plot(soft["t"], np.asarray(soft["mn"]) * 1e3, "k:", lw=1, label="softgrip: |m_n| [mN·m]")
    ax0b.set_ylabel("|m_n| under softgrip [mN·m]")
    axes[0].set_ylabel("grip force command [N]")
    axes[1].set_ylabel("box slip in grasp [mm]")
    axes[2].set_ylabel("box rotation in grasp [deg]")
    axes[2].set_xlabel("time [s]")
    for ax in axes:
        for t0, lab in ((T_CLOSE, "lift"), (T_LIFT, "hold"), (T_HOLD1, "shake"), (T_SHAKE, "twist"), (T_TWIST, "hold")):
            ax.axvline(t0, color="0.8", lw=0.8)
            if ax is axes[0]:
                ax.text(t0 + 0.02, 0.97, lab, transform=ax.get_xaxis_transform(), va="top", fontsize=8)
    for ax in axes[1:]:
        ax.set_yscale("symlog", linthresh=0.1)
        ax.set_ylim(bottom=0.0)
    axes[0].legend(loc="upper left", fontsize=7, ncol=2, bbox_to_anchor=(0.0, 0.9))
    axes[0].set_title("MuJoCo grasp: lift, hold, shake, twist — softgrip vs constant and Coulomb grips")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
