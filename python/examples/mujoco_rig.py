#!/usr/bin/env python3
"""The lab protocols softgrip's calibration reads, run in MuJoCo on ``mujoco_grasp.py``'s
fingertip pressed on a flat plate; then the fit, and the grasp on the fitted finger.

    python python/examples/mujoco_rig.py all --out lab/           # indentation.csv, slip.csv
    python python/examples/mujoco_rig.py all --out lab/ --calibrate --grasp

The rig is the grasp's fingertip (the same sphere, mass, friction, soft-contact parameters
and solver options: ``mujoco_grasp.CONTACT_OPTIONS`` and its neighbours) on a slide along
the normal, pressed by a force actuator on a plate that is the grasp's box (its size, mass
and material, lying on the face the fingers hold, centred under the tip). The plate is a
free body on a frictionless floor, as free as the box in the grasp: it slides and turns
only against the fingertip. Gravity is off, so the normal force is the actuator's. Each
measurement starts from rest and presses for ``SETTLE_S``; then

- ``indentation`` records the contact's normal force and the half-width of the overlap of
  sphere and plate, ``sqrt(2·R·d − d²)`` at MuJoCo's penetration ``d``, at each of
  ``--indentation-forces`` (one force, 4 N, by default, pressed three times: the
  calibration reads at least three rows; MuJoCo repeats itself to the last digit).
  MuJoCo has no contact patch: ``d`` is its soft constraint's give (``solref``,
  ``solimp`` and the bodies' masses set it) and its friction never reads it. Its
  torsional friction is a fixed length ``μ_t`` (``|m_n| ≤ μ_t·N``), a contact that does
  not grow with the force, while the overlap grows as ``N^½``. With one force the
  calibration holds ``γ`` at 0, MuJoCo's law, and ``--calibrate`` refits ``c`` to the
  torsion onsets (``friction_contact``);
- ``slip``, ``torsion`` and ``combined`` ramp a force on the plate along x (at the height
  of the contact), a moment about the normal, or both along ratios ``m_n/f_t`` [m], by
  ``RAMP_PER_S·N`` per second, until gross slip, and record the contact's wrench
  (``mj_contactForce``) then. Gross slip is the first step at which the contact's wrench
  stops following the load: its change over the step misses the load's by ``ONSET_LAG``
  (half) of it (force and moment on one scale, the moment over the tip's radius), looked
  for from a load of ``ONSET_FROM·N`` on;
- ``all``: ``indentation.csv``, and ``slip.csv`` with the onsets of the three ramps;
- ``hold`` and ``cyclic``: the margin protocols of ``host-sim experiment hold`` and
  ``cyclic`` at 4 N (``hold.csv``, ``cyclic.csv``): per axis the static onset, then from
  fresh contacts each fraction of it held for 1.5 s after a 0.5 s ramp, or cycled 10 times
  at 4 Hz, recording how far the plate slid and turned.

The files have ``host-sim experiment``'s columns (docs/experiments.md); the forces and
ratios are its defaults plus 16 N (the grasp grips at up to 20 N). Without noise a
repeated ramp copies its row: one ramp per force and direction.

``--calibrate`` fits them with ``softgrip.calibrate(..., shape="disc",
friction_contact=True)`` into ``finger.toml`` and prints the fit against MuJoCo's
configured friction and each onset's ``N_slip/N`` on the fitted finger; ``--grasp`` runs
``mujoco_grasp.py``'s scene with softgrip on the fitted finger (and on the example's own,
for comparison) and prints their mean force over the least constant grip that holds.
"""

from __future__ import annotations

import argparse
import json
import math
import pathlib
import sys
from dataclasses import dataclass
from typing import Optional

import mujoco
import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import mujoco_grasp as grasp  # noqa: E402  (the grasp's fingertip and scene)

import softgrip  # noqa: E402

FORCES = (0.5, 1.0, 2.0, 4.0, 8.0, 16.0)  # [N]
INDENTATION_FORCES = (4.0,)  # [N]: one force, so the fit holds gamma at 0 (above)
INDENTATION_ROWS = 3  # presses in all, spread over the forces: calibrate reads at least 3
RATIOS = (1e-3, 2.5e-3, 6e-3)  # m_n/f_t of the combined ramps [m], host-sim's defaults
TORSION_UNIT_NM = 1e-3  # a pure-torsion ramp's moment per unit of load, as host-sim's
SETTLE_S = 0.2  # pressing before a measurement [s]
RAMP_PER_S = 2.0  # the load s rises by 2·N per second (a force ramp: 2·N newtons/s)
RAMP_MAX = 5.0  # a ramp that has not slipped by s = 5·N records nothing
ONSET_FROM = 0.1  # the onset is looked for from s = 0.1·N on (the start's transient)
ONSET_LAG = 0.5  # gross slip: the contact's wrench misses the load's step by half of it
# The plate is the grasp's box lying on the face the fingers hold (normal along its y):
# the same mass and inertia about the contact normal, which set MuJoCo's creep (below).
PLATE_MASS = grasp.BOX_MASS  # [kg]
PLATE_HALF = (grasp.BOX_HALF[0], grasp.BOX_HALF[2], grasp.BOX_HALF[1])  # [m]
N_MAX_PREDICT = 40.0  # the prediction's controller range [N], above every onset's force


def rig_mjcf(mu_t: float) -> str:
    """The rig: a free plate (the grasp's box) on a frictionless floor, and the grasp's
    fingertip above it on a z slide pushed down by a motor.

    The plate is a free body, as the box is in the grasp: MuJoCo's noslip post-processor,
    which the grasp's options turn on, leaves a plate on slide and hinge joints creeping
    at a rate proportional to the load under any load, and holds a free one."""
    r = grasp.TIP_RADIUS
    px, py, pz = PLATE_HALF
    return f"""
<mujoco model="softgrip_rig">
  <option {grasp.CONTACT_OPTIONS} gravity="0 0 0"/>
  <default>
    <geom {grasp.GEOM_SOFTNESS}/>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 0.1" pos="0 0 {-2 * pz}" condim="1"
          priority="1" contype="1" conaffinity="1"/>
    <body name="plate" pos="0 0 {-pz}">
      <freejoint/>
      <geom name="plate" type="box" size="{px} {py} {pz}" mass="{PLATE_MASS}"
            contype="1" conaffinity="1" condim="6" friction="{grasp.BOX_FRICTION}"/>
    </body>
    <body name="finger" pos="0 0 {r}">
      <joint name="fz" type="slide" axis="0 0 1" damping="5"/>
      <geom type="capsule" fromto="0 0 0.005 0 0 0.05" size="0.004" mass="0.05"
            contype="0" conaffinity="0"/>
      <geom name="tip" type="sphere" size="{r}" mass="{grasp.TIP_MASS}" condim="6"
            contype="2" conaffinity="1" friction="{grasp.tip_friction(mu_t)}"/>
    </body>
  </worldbody>
  <actuator>
    <motor name="press" joint="fz" gear="-1"/>
  </actuator>
</mujoco>
"""


@dataclass
class Wrench:
    """The tip–plate contact: normal force [N], |f_t| [N], |m_n| [N·m], penetration [m]."""

    n: float = 0.0
    ft: float = 0.0
    mn: float = 0.0
    depth: float = 0.0


class Rig:
    """The MuJoCo rig; every measurement starts from rest."""

    def __init__(self, mu_t: Optional[float] = None):
        self.mu_t = grasp.torsional_coefficient(grasp.operating_force()) if mu_t is None else mu_t
        self.model = mujoco.MjModel.from_xml_string(rig_mjcf(self.mu_t))
        self.data = mujoco.MjData(self.model)
        geom = lambda n: mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_GEOM, n)  # noqa: E731
        self.pair = {geom("tip"), geom("plate")}
        self.plate = mujoco.mj_name2id(self.model, mujoco.mjtObj.mjOBJ_BODY, "plate")
        self.steps = 0
        self._f6 = np.zeros(6)

    def wrench(self) -> Wrench:
        m, d, f6 = self.model, self.data, self._f6
        w = Wrench()
        for i in range(d.ncon):
            if {int(d.contact.geom1[i]), int(d.contact.geom2[i])} != self.pair:
                continue
            mujoco.mj_contactForce(m, d, i, f6)
            # Contact frame: normal, two tangents; f6 = (N, t1, t2, m_n, r1, r2).
            w.n += f6[0]
            w.ft += math.hypot(f6[1], f6[2])
            w.mn += abs(f6[3])
            w.depth = max(w.depth, -float(d.contact.dist[i]))
        return w

    def step(self, press_n: float, push_n: float = 0.0, turn_nm: float = 0.0) -> Wrench:
        """One step: the finger pressed with ``press_n``, the plate pushed along x with
        ``push_n`` at the height of its top face (no tipping moment) and turned about the
        normal with ``turn_nm``."""
        d = self.data
        d.ctrl[0] = press_n
        d.qfrc_applied[:] = 0.0
        top = d.xpos[self.plate] + np.array([0.0, 0.0, PLATE_HALF[2]])
        mujoco.mj_applyFT(
            self.model, d, np.array([push_n, 0.0, 0.0]), np.array([0.0, 0.0, turn_nm]),
            top, self.plate, d.qfrc_applied,
        )
        mujoco.mj_step(self.model, d)
        self.steps += 1
        return self.wrench()

    def pose(self) -> np.ndarray:
        """The plate's (x [m], y [m], turn about the normal [rad]): its slip under the
        fingertip, which only moves along the normal."""
        x, y = self.data.xpos[self.plate][:2]
        rot = self.data.xmat[self.plate].reshape(3, 3)
        return np.array([x, y, math.atan2(rot[1, 0], rot[0, 0])])

    def press(self, normal_n: float) -> Wrench:
        """From rest, presses with ``normal_n`` for ``SETTLE_S``; the contact then."""
        mujoco.mj_resetData(self.model, self.data)
        w = Wrench()
        for _ in range(int(round(SETTLE_S / grasp.DT))):
            w = self.step(normal_n)
        return w

    def indentation(self, normal_n: float) -> tuple[float, float]:
        """(normal force [N], overlap half-width [m]) at rest under ``normal_n``."""
        w = self.press(normal_n)
        r, d = grasp.TIP_RADIUS, w.depth
        return w.n, math.sqrt(max(2.0 * r * d - d * d, 0.0))

    def slip_onset(self, normal_n: float, ft_unit: float, mn_unit: float) -> Optional[Wrench]:
        """Ramps ``s·(ft_unit [N], mn_unit [N·m])`` on the plate, ``s`` rising at
        ``RAMP_PER_S·normal_n`` per second, until the contact's wrench changes over a step
        by ``ONSET_LAG`` of the load's step away from it; the contact's wrench then, or
        ``None`` if it has not slipped by ``s = RAMP_MAX·normal_n``."""
        self.press(normal_n)
        ds = RAMP_PER_S * normal_n * grasp.DT
        # Force and moment on one scale: the moment as a force at the tip's radius.
        arm = grasp.TIP_RADIUS
        step = ds * np.array([ft_unit, mn_unit / arm])  # the load's rise per step
        s, before = 0.0, np.zeros(2)
        while s < RAMP_MAX * normal_n:
            s += ds
            w = self.step(normal_n, s * ft_unit, s * mn_unit)
            carried = np.array([w.ft, w.mn / arm])
            rise, before = carried - before, carried
            missed = np.linalg.norm(rise - step)
            if s > ONSET_FROM * normal_n and missed > ONSET_LAG * np.linalg.norm(step):
                return w
        return None


def experiment(
    rig: Rig,
    kind: str,
    forces=FORCES,
    ratios=RATIOS,
    indentation_forces=INDENTATION_FORCES,
) -> dict[str, list[tuple[float, ...]]]:
    """The rows of ``kind`` (indentation, slip, torsion, combined, all, hold or cyclic),
    by file name (``all``: indentation and slip)."""
    out: dict[str, list] = {}
    if kind == "hold":
        return dict(hold=hold(rig))
    if kind == "cyclic":
        return dict(cyclic=cyclic(rig))
    if kind in ("indentation", "all"):
        presses = -(-INDENTATION_ROWS // max(len(indentation_forces), 1))
        out["indentation"] = [
            rig.indentation(n) for n in indentation_forces for _ in range(presses)
        ]
    dirs = {
        "slip": [(1.0, 0.0)],
        "torsion": [(0.0, TORSION_UNIT_NM)],
        "combined": [(1.0, r) for r in ratios],
    }
    kinds = list(dirs) if kind == "all" else [kind] if kind in dirs else []
    for k in kinds:
        rows = out.setdefault("slip" if kind == "all" else k, [])
        for n in forces:
            for ft_u, mn_u in dirs[k]:
                w = rig.slip_onset(n, ft_u, mn_u)
                if w is None:
                    continue
                # A pure ramp's unloaded channel is recorded as 0, as host-sim's (MuJoCo's
                # solver leaves it at rounding level), so the fit sees a pure onset.
                rows.append((w.n, w.ft if ft_u else 0.0, w.mn if mn_u else 0.0))
    return out


# --- The margin protocols (host-sim experiment hold and cyclic) ---------------------------
MARGIN_NORMAL_N = 4.0  # [N]
HOLD_FRACTIONS = (0.5, 0.6, 0.7, 0.8, 0.9, 1.0)  # of the axis's static onset
HOLD_RAMP_S, HOLD_S = 0.5, 1.5
CYCLIC_FRACTIONS = (0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95, 1.0)
CYCLES, CYCLE_HZ = 10, 4.0
SLID_OFF_M, SLID_OFF_RAD = 0.01, 0.2  # host-sim's drop: a test stops there
AXES = {"force": (1.0, 0.0), "torsion": (0.0, TORSION_UNIT_NM)}


def axis_load(axis: str, load: float) -> tuple[float, float]:
    """``(f_t, m_n)`` of ``load`` on ``axis``."""
    return (load, 0.0) if axis == "force" else (0.0, load)


def slid_off(pose: np.ndarray) -> bool:
    return bool(np.hypot(pose[0], pose[1]) > SLID_OFF_M or abs(pose[2]) > SLID_OFF_RAD)


def margin_onset(rig: Rig, normal_n: float, axis: str) -> Optional[tuple[float, float]]:
    """One static onset on ``axis``: (normal force [N], load [N or N·m])."""
    w = rig.slip_onset(normal_n, *AXES[axis])
    return None if w is None else (w.n, w.ft if axis == "force" else w.mn)


def hold(rig: Rig, normal_n: float = MARGIN_NORMAL_N, fractions=HOLD_FRACTIONS) -> list:
    """``host-sim experiment hold``'s rows: per axis its onset (``time_s`` 0), then from
    fresh contacts each fraction of it ramped in ``HOLD_RAMP_S`` (``(1 − cos πt/T)/2``)
    and held ``HOLD_S``: how far the plate slid and turned over the hold, and at what rate
    over its last quarter; ``time_s`` is how long the test lasted (less if it slid off).
    The normal force of a held row is the actuator's (the contact's chatters once the
    plate slides); an onset's is the contact's."""
    rows = []
    ramp, held = round(HOLD_RAMP_S / grasp.DT), round(HOLD_S / grasp.DT)
    window = held // 4
    for axis in AXES:
        onset = margin_onset(rig, normal_n, axis)
        if onset is None:
            continue
        rows.append((axis, onset[0], 1.0, *axis_load(axis, onset[1]), 0.0, 0.0, 0.0, 0.0, 0.0))
        for fraction in fractions:
            load = fraction * onset[1]
            rig.press(normal_n)
            origin = rig.pose()
            start, trail = np.zeros(3), []
            ticks, now = 0, np.zeros(3)
            while ticks < ramp + held and not slid_off(now):
                if ticks == ramp:
                    start = now
                u = 0.5 * (1.0 - math.cos(math.pi * (ticks + 1) / ramp)) if ticks < ramp else 1.0
                trail = (trail + [now])[-window:]
                rig.step(normal_n, *axis_load(axis, load * u))
                now = rig.pose() - origin
                ticks += 1
            late, span = trail[0], max(len(trail), 1) * grasp.DT
            rows.append((
                axis, normal_n, fraction, *axis_load(axis, load), ticks * grasp.DT,
                float(np.hypot(*(now - start)[:2])), abs(float(now[2] - start[2])),
                float(np.hypot(*(now - late)[:2])) / span, abs(float(now[2] - late[2])) / span,
            ))
    return rows


def cyclic(rig: Rig, normal_n: float = MARGIN_NORMAL_N, fractions=CYCLIC_FRACTIONS) -> list:
    """``host-sim experiment cyclic``'s rows: per axis its onset (``cycle`` 0), then from
    fresh contacts, for each fraction of it, ``CYCLES`` cycles ``peak·(1 − cos 2πft)/2`` at
    ``CYCLE_HZ``: how far the plate slid and turned over each cycle (zero load to zero
    load), the normal force the actuator's as in ``hold``. A test stops when the plate
    slides off."""
    rows = []
    ticks = max(round(1.0 / (CYCLE_HZ * grasp.DT)), 2)
    for axis in AXES:
        onset = margin_onset(rig, normal_n, axis)
        if onset is None:
            continue
        rows.append((axis, onset[0], 1.0, 0, *axis_load(axis, onset[1]), 0.0, 0.0))
        for fraction in fractions:
            peak = fraction * onset[1]
            rig.press(normal_n)
            origin = rig.pose()
            last = np.zeros(3)
            for cycle in range(1, CYCLES + 1):
                for k in range(1, ticks + 1):
                    u = 0.5 * (1.0 - math.cos(2.0 * math.pi * k / ticks))
                    rig.step(normal_n, *axis_load(axis, peak * u))
                now = rig.pose() - origin
                rows.append((
                    axis, normal_n, fraction, cycle, *axis_load(axis, peak),
                    float(np.hypot(*(now - last)[:2])), abs(float(now[2] - last[2])),
                ))
                last = now
                if slid_off(now):
                    break
    return rows


INDENTATION_HEADER = "normal_force_n,half_width_m"
SLIP_HEADER = "normal_force_n,tangential_force_n,torsional_moment_nm"
HOLD_HEADER = (
    "axis,normal_force_n,fraction,tangential_force_n,torsional_moment_nm,time_s,slide_m,"
    "turn_rad,slide_rate_m_s,turn_rate_rad_s"
)
CYCLIC_HEADER = (
    "axis,normal_force_n,fraction,cycle,tangential_force_n,torsional_moment_nm,slide_m,"
    "turn_rad"
)
HEADERS = dict(indentation=INDENTATION_HEADER, hold=HOLD_HEADER, cyclic=CYCLIC_HEADER)


def cell(v) -> str:
    """A CSV field: the axis as it is, a cycle number as an integer, a number in shortest
    round-trip form."""
    if isinstance(v, str):
        return v
    return str(v) if isinstance(v, int) else repr(float(v))


def write_csvs(rows: dict[str, list], out: pathlib.Path) -> list[pathlib.Path]:
    """Writes each file as ``host-sim experiment`` does: the header, then one row per
    measurement in shortest round-trip numbers."""
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, table in rows.items():
        header = HEADERS.get(name, SLIP_HEADER)
        path = out / f"{name}.csv"
        lines = [header] + [",".join(cell(v) for v in row) for row in table]
        path.write_text("\n".join(lines) + "\n")
        paths.append(path)
    return paths


def read_slip(path: pathlib.Path) -> list[tuple[float, float, float]]:
    lines = path.read_text().splitlines()[1:]
    return [tuple(float(x) for x in line.split(",")) for line in lines if line.strip()]


def calibrate(out: pathlib.Path, margins: bool = False) -> dict:
    """``softgrip.calibrate`` on the rig's files in ``out`` (a disc; μ from the pure-force
    onsets and ``c`` refitted to the torsion onsets, ``friction_contact``; with
    ``margins``, the finger's margins from ``hold.csv`` and ``cyclic.csv``); writes
    ``out/finger.toml`` and returns the fit."""
    files = dict(cyclic=out / "cyclic.csv", hold=out / "hold.csv") if margins else {}
    fit = softgrip.calibrate(
        out / "indentation.csv", out / "slip.csv", shape="disc", friction_contact=True, **files
    )
    (out / "finger.toml").write_text(fit["finger_toml"])
    return fit


def torsional_friction(finger: dict) -> float:
    """A finger's pure-torsion limit per newton, ``μ·a·pitch`` [m] (MuJoCo's ``μ_t`` when
    ``γ = 0``), at 1 N."""
    pitch = softgrip.fls(shape=finger["shape"], k=finger["k"], samples=16)["pitch"]
    a = softgrip.half_width(finger["c_m_per_n_gamma"], finger["gamma"], 1.0)
    return finger["mu"] * a * pitch


def predicted_onsets(finger: dict, rows) -> list[dict]:
    """Each measured onset's ``N_slip/N`` on ``finger``: the normal force at which the
    finger's exact surface (table mode, safety 1) says that load slips, over the force it
    slipped at in MuJoCo (1: predicted exactly; above 1: the finger slips first)."""
    ctl = softgrip.Controller(**finger, mode="table", n_max_n=N_MAX_PREDICT)
    out = []
    for n, ft, mn in rows:
        kind = "force" if mn == 0 else "torsion" if ft == 0 else "mixed"
        n_slip = ctl.slip_force(ft, mn)
        out.append(dict(kind=kind, normal_force_n=n, over=n_slip / n if n_slip else None))
    return out


def grasp_ratios(fingers: dict[str, Optional[dict]], **config) -> dict:
    """``mujoco_grasp``'s scene: the least constant grip that holds (0.5 N grid) and, for
    each named finger (``None``: the example's own), softgrip's run at ``config`` (its
    defaults by default) and mean force over that grip."""
    mu_t = grasp.torsional_coefficient(grasp.operating_force())
    coarse = [grasp.run(grasp.Constant(f), mu_t) for f in (8.0, 10.0, 12.0, 16.0)]
    least = grasp.least_holding_constant(coarse, mu_t)
    out = dict(least_holding_constant_n=least, config=config, runs={})
    for name, finger in fingers.items():
        r = grasp.run(grasp.Softgrip(finger, **config), mu_t)
        out["runs"][name] = dict(
            held=r.held,
            mean_force_n=r.mean_force_n,
            over_least=r.mean_force_n / least if least else None,
            rotation_deg=r.rotation_deg,
            slip_mm=r.slip_mm,
        )
    return out


def summary(fit: dict, rows, mu_t: float) -> dict:
    """The fit against MuJoCo's configured friction, and the onsets' prediction by kind."""
    finger = fit["controller"]
    pred = predicted_onsets(finger, rows)
    by_kind = {}
    for kind in ("force", "torsion", "mixed"):
        vals = [p["over"] for p in pred if p["kind"] == kind]
        if vals:
            by_kind[kind] = dict(count=len(vals), min=min(vals), max=max(vals))
    return dict(
        mu=dict(fitted=finger["mu"], mujoco=grasp.FINGER["mu"]),
        torsional_friction_m=dict(fitted=torsional_friction(finger), mujoco=mu_t),
        k=finger["k"],
        k_ci95=fit["k"]["ci95"],
        c_m=finger["c_m_per_n_gamma"],
        gamma=finger["gamma"],
        joint_fit=fit.get("friction_contact"),
        onsets_n_slip_over_n=by_kind,
    )


def main(argv: Optional[list[str]] = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "kind", choices=["indentation", "slip", "torsion", "combined", "all", "hold", "cyclic"]
    )
    ap.add_argument("--out", required=True, type=pathlib.Path, help="output directory")
    ap.add_argument("--forces", default=",".join(f"{f:g}" for f in FORCES), help="[N]")
    ap.add_argument("--ratios", default=",".join(f"{r:g}" for r in RATIOS), help="[m]")
    ap.add_argument(
        "--indentation-forces", default=",".join(f"{f:g}" for f in INDENTATION_FORCES),
        help="[N]; more than one makes the fit take gamma from the overlap",
    )
    ap.add_argument("--calibrate", action="store_true", help="fit finger.toml (needs all)")
    ap.add_argument(
        "--margins", action="store_true",
        help="with all: also run hold and cyclic, and --calibrate fits the margins from them",
    )
    ap.add_argument("--grasp", action="store_true", help="run the grasp on it (needs --calibrate)")
    ap.add_argument(
        "--config", action="append", default=[], metavar="KEY=VALUE",
        help="a softgrip controller setting for --grasp (repeatable), e.g. safety=1.0",
    )
    ap.add_argument("--json", action="store_true", help="print one JSON object")
    args = ap.parse_args(argv)
    floats = lambda text: [float(x) for x in text.split(",") if x.strip()]  # noqa: E731
    if (args.calibrate or args.grasp or args.margins) and args.kind != "all":
        ap.error("--calibrate, --grasp and --margins need the kind all")
    if args.grasp and not args.calibrate:
        ap.error("--grasp needs --calibrate")
    config = {}
    for item in args.config:
        key, _, value = item.partition("=")
        try:
            config[key.strip()] = float(value)
        except ValueError:
            config[key.strip()] = value.strip()  # mode=table
    rig = Rig()
    rows = experiment(
        rig, args.kind, floats(args.forces), floats(args.ratios),
        floats(args.indentation_forces),
    )
    if args.margins:
        rows.update(hold=hold(rig), cyclic=cyclic(rig))
    report: dict = dict(files=[str(p) for p in write_csvs(rows, args.out)], mujoco_steps=rig.steps)
    if args.calibrate:
        fit = calibrate(args.out, margins=args.margins)
        report["finger_toml"] = str(args.out / "finger.toml")
        report["calibration"] = summary(fit, rows["slip"], rig.mu_t)
        if args.grasp:
            fingers = {"calibrated": fit["controller"], "example": None}
            report["grasp"] = grasp_ratios(fingers, **config)
    if args.json:
        json.dump(report, sys.stdout, indent=2, default=lambda v: None)
        print()
    else:
        print_report(report)
    return 0


def print_report(report: dict) -> None:
    for p in report["files"]:
        print(f"wrote {p}")
    cal = report.get("calibration")
    if not cal:
        return
    print(f"wrote {report['finger_toml']}")
    mu, mt = cal["mu"], cal["torsional_friction_m"]
    print(f"mu: fitted {mu['fitted']:.6f}, MuJoCo {mu['mujoco']:g} "
          f"({100 * (mu['fitted'] / mu['mujoco'] - 1):+.2g} %)")
    print(f"torsional friction at 1 N, mu·a·pitch: fitted {mt['fitted'] * 1e3:.6f} mm, MuJoCo "
          f"mu_t {mt['mujoco'] * 1e3:.6f} mm ({100 * (mt['fitted'] / mt['mujoco'] - 1):+.2g} %)")
    lo, hi = cal["k_ci95"]
    print(f"k {cal['k']:g} (95 %: [{lo:g}, {hi if hi is not None else math.inf:g}]), "
          f"c {cal['c_m'] * 1e3:.4f} mm, gamma {cal['gamma']:g}")
    if cal["joint_fit"]:
        j = cal["joint_fit"]
        print(f"joint fit before the friction contact: mu {j['joint_mu']:.4f}, "
              f"c {j['joint_c'] * 1e3:.4f} mm (the overlap's)")
    for kind, v in cal["onsets_n_slip_over_n"].items():
        print(f"{kind} onsets ({v['count']}): N_slip/N on the fitted finger "
              f"{v['min']:.4f} to {v['max']:.4f}")
    g = report.get("grasp")
    if not g:
        return
    least = g["least_holding_constant_n"]
    cfg = ", ".join(f"{k}={v}" for k, v in g["config"].items()) or "its defaults"
    print(f"grasp (softgrip at {cfg}); least constant grip that holds: {least:g} N")
    for name, r in g["runs"].items():
        ratio = f"{r['over_least']:.3f}" if r["over_least"] else "-"
        print(f"  softgrip on the {name} finger: held {r['held']}, mean "
              f"{r['mean_force_n']:.2f} N, over the least constant {ratio}")


if __name__ == "__main__":
    sys.exit(main())
