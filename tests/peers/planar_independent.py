#!/usr/bin/env python3
"""An independent planar crash-test series (issue 32): what a lab would record.

Usage: planar_independent.py OUT_DIR [--seeds FIRST:COUNT] [--yaw-rate]

With --seeds FIRST:COUNT, seeds k = FIRST .. FIRST+COUNT-1 each write a
complete series into OUT_DIR/seed-<k>/ of a car of its own (the base car's
body mass, yaw inertia, grip and side members drawn log-normally with
numpy seed 2000 + k, SPREADS) under noise of numpy seed 1000 + k (the
coverage test of the planar intervals, issue 44: a fixed car would make
the model family's offset the same in every seed); series.json then gives
that car's truth. Without it: the base car, noise seed 11.

With --yaw-rate the series is issue 44's low-information layout in this
family: the two sills and a yaw-rate sensor (0.1 deg/s white noise), no
side-member accelerometers; the held-out offset test is a 40 % offset 10 deg
wall at 15 km/h (YAW_RATE_TESTS); and OUT_DIR/study-doc.toml is the study as
docs/planar.md has a lab write it (the tyres' law by default, the side
members' law named, here "progressive", the bumper fitted with the joint
stage, the sills in velocity with nuisance biases). Without it every file is
byte-identical to the one before the option.

Writes OUT_DIR/<TEST>.csv (10 kHz, `time [s]` from -20 ms, load cells in N,
accelerometers in m/s^2) for five tests of one car, OUT_DIR/series.json
(the car's truth, the test sheet and each test's set-up as a lab reports it)
and OUT_DIR/study.toml (a bumpsim planar study of the three training tests,
the two held-out ones as `validate = true`).

The model is written here, not taken from bumpsim, and is of another family:

- the body (mass M, yaw inertia I about the CG) carries two side members
  (masses m_L, m_R at y = +/-b) on prismatic guides along the body x axis,
  each held by a *progressive* crush spring F = k (d + d^3/d0^2) and a
  damper; the equations are Newton-Euler with the guides' reaction forces
  solved as unknowns (a 7 x 7 linear system per evaluation), not eliminated;
- a rigid bumper beam rests on the two side-member tips (lever rule); its
  face is 40 foam strips, each elastic-plastic with hardening and bottoming
  (F = min(k_r d, F_p + k_h (d - F_p/k_r)) + k_b max(d - d_b, 0) on
  loading, elastic unloading from the largest crush at slope k_u);
- four rolling tyres with transient slip (Pacejka's first-order relaxation,
  sigma dalpha'/dt + |v_x| alpha' = v_y) and a Magic-Formula saturation
  F_y = -mu N sin(C atan(B alpha')), B = C_alpha / (C mu N); rolling
  resistance f_r N tanh(v_x / 0.05 m/s);
- strikers: a rigid wall (any angle, any overlap) divided into four load
  cells, a rigid pole with a two-axis load cell, a guided flat pendulum with
  one load cell;
- classical RK4 at 20 us, the foam history updated after each step;
  sampled every 100 us with white noise (30 N per load cell, 0.05 g per
  accelerometer) and accelerometer biases; t = 0 is the lab's trigger, a
  few millimetres before first contact.
"""
import json
import math
import sys
from pathlib import Path

import numpy as np

G = 9.80665

CAR = {
    "body_mass": 1160.0, "yaw_inertia": 2050.0, "cg_behind_bumper": 2.1,
    "wheelbase": 2.7, "cg_behind_front_axle": 1.18, "track": 1.56,
    "members": {"mass": [13.0, 10.0], "spring": [1.5e6, 1.15e6], "d0": 0.25,
                "damper": [2.6e3, 2.1e3], "spacing": 1.0},
    "beam": {"width": 1.6, "strips": 40, "ramp": 2.4e5, "plateau": 9.0e3,
             "hardening": 2.0e4, "bottom": 0.07, "bottoming": 1.5e6, "unloading": 3.0e6},
    "tyres": {"cornering_stiffness": 75e3, "relaxation_length": 0.55, "mu": 0.85,
              "shape": 1.3, "rolling_resistance": 0.015},
    "sills": {"xi": 0.45, "eta": 0.7},
}

TESTS = [
    {"name": "PENDULUM", "kind": "pendulum", "mass": 1100.0, "speed_kmh": 8.0, "train": True},
    {"name": "POLE", "kind": "pole", "diameter": 0.254, "offset": 0.0, "speed_kmh": 8.0,
     "train": True},
    {"name": "WALL10", "kind": "wall", "angle_deg": 10.0, "overlap": 1.0, "side": "left",
     "speed_kmh": 10.0, "train": True},
    {"name": "OFFSET40", "kind": "wall", "angle_deg": 0.0, "overlap": 0.4, "side": "left",
     "speed_kmh": 15.0, "train": False},
    {"name": "POLE-OFFSET", "kind": "pole", "diameter": 0.254, "offset": -0.35,
     "speed_kmh": 8.0, "train": False},
]

# --yaw-rate: issue 44's held-out offset test, a 40 % offset 10 deg wall
YAW_RATE_TESTS = TESTS[:3] + [dict(TESTS[3], angle_deg=10.0)] + TESTS[4:]

STEP, SAMPLE, PRE, DURATION, GAP = 20e-6, 1e-4, 0.02, 0.18, 0.004


class Car:
    def __init__(self, c):
        self.c = c
        m = c["members"]
        self.mb, self.iz = c["body_mass"], c["yaw_inertia"]
        self.xf = c["cg_behind_bumper"]
        self.mm = np.array(m["mass"])
        self.eta_m = np.array([0.5 * m["spacing"], -0.5 * m["spacing"]])
        b = c["beam"]
        w = b["width"] / b["strips"]
        self.eta_s = -0.5 * b["width"] + w * (np.arange(b["strips"]) + 0.5)
        half = 0.5 * m["spacing"]
        self.alpha = (self.eta_s + half) / (2 * half)  # left share of each strip
        L, a, tw = c["wheelbase"], c["cg_behind_front_axle"], c["track"]
        self.wheels = [(a, 0.5 * tw), (a, -0.5 * tw), (a - L, 0.5 * tw), (a - L, -0.5 * tw)]
        total = self.total_mass()
        front, rear = total * G * (L - a) / L, total * G * a / L
        self.loads = np.array([0.5 * front, 0.5 * front, 0.5 * rear, 0.5 * rear])

    def total_mass(self):
        return self.mb + self.mm.sum()

    def foam(self, d, dmax):
        """Strip forces (N) at crush d with the largest crush so far dmax."""
        b = self.c["beam"]
        def load(x):
            plateau = b["plateau"] + b["hardening"] * np.maximum(x - b["plateau"] / b["ramp"], 0.0)
            bottomed = b["bottoming"] * np.maximum(x - b["bottom"], 0.0)
            return np.minimum(b["ramp"] * x, plateau) + bottomed
        loading = load(d)
        unloading = np.maximum(load(dmax) - b["unloading"] * (dmax - d), 0.0)
        f = np.where(d >= dmax, loading, unloading)
        return np.where(d > 0.0, f, 0.0)

    def tyre_forces(self, v_e, v_n, w, slip):
        """Forces (body frame) and moment of the four tyres."""
        t = self.c["tyres"]
        fe = fn = mz = 0.0
        for (xi, eta), load, s in zip(self.wheels, self.loads, slip):
            we = v_e - w * eta
            peak = t["mu"] * load
            b = t["cornering_stiffness"] / (t["shape"] * peak)
            fy = -peak * math.sin(t["shape"] * math.atan(b * s))
            fx = -t["rolling_resistance"] * load * math.tanh(we / 0.05)
            fe, fn = fe + fx, fn + fy
            mz += xi * fy - eta * fx
        return fe, fn, mz

    def slip_rates(self, v_e, v_n, w, slip):
        t = self.c["tyres"]
        out = []
        for (xi, eta), s in zip(self.wheels, slip):
            we, wn = v_e - w * eta, v_n + w * xi
            out.append((wn - abs(we) * s) / t["relaxation_length"])
        return out


class Striker:
    """The striker's contact: strip penetrations and force directions (world)."""

    def __init__(self, test, car):
        self.kind, self.test, self.car = test["kind"], test, car
        v = test["speed_kmh"] / 3.6
        if self.kind == "pendulum":
            self.mass = test["mass"]
            self.speed = v
        elif self.kind == "pole":
            self.radius = 0.5 * test["diameter"]
            self.centre = np.array([car.xf + self.radius + GAP, test["offset"]])
        else:
            th = math.radians(test["angle_deg"])
            self.normal = np.array([-math.cos(th), -math.sin(th)])  # towards the car
            half = 0.5 * car.c["beam"]["width"]
            cover = test["overlap"] * 2 * half
            # the covered strips' lateral band, from the struck side
            self.band = (half - cover, math.inf) if test["side"] == "left" else (-math.inf, cover - half)
            ends = [np.array([car.xf, y]) for y in (max(self.band[0], -half), min(self.band[1], half))]
            self.level = min(self.normal @ p for p in ends) - GAP * 1.0

    def penetration(self, points, s):
        """Penetrations (m) and unit force directions on the car (world) per strip."""
        if self.kind == "pendulum":
            face = self.car.xf + GAP - s  # s: the pendulum's travel towards the car
            return points[:, 0] - face, np.tile([-1.0, 0.0], (len(points), 1))
        if self.kind == "pole":
            rel = points - self.centre
            lateral = np.abs(rel[:, 1])
            reach = np.sqrt(np.maximum(self.radius ** 2 - rel[:, 1] ** 2, 0.0))
            depth = np.where(lateral < self.radius, rel[:, 0] + reach, -1.0)
            direction = np.column_stack([-reach, rel[:, 1]]) / self.radius
            return depth, direction
        depth = self.level - points @ self.normal
        covered = (points[:, 1] >= self.band[0]) & (points[:, 1] <= self.band[1])
        return np.where(covered, depth, -1.0), np.tile(self.normal, (len(points), 1))


def simulate(car, striker):
    """States and channels of one test, sampled every SAMPLE from -PRE."""
    n_strips = len(car.eta_s)
    moving = striker.kind != "pendulum"
    speed = striker.test["speed_kmh"] / 3.6
    # q = X, Y, psi, uL, uR, s ; v likewise ; tyre slips (4)
    state = np.zeros(16)
    if moving:
        state[6] = speed
    else:
        state[11] = striker.speed
    dmax = np.zeros(n_strips)

    def forces(st):
        X, Y, psi, uL, uR, s = st[:6]
        c, sn = math.cos(psi), math.sin(psi)
        e, n = np.array([c, sn]), np.array([-sn, c])
        beam = car.xf + car.alpha * uL + (1 - car.alpha) * uR
        points = np.array([X, Y]) + np.outer(beam, e) + np.outer(car.eta_s, n)
        depth, direction = striker.penetration(points, s)
        f = car.foam(depth, dmax)
        return e, n, points, depth, f, direction

    def rhs(st):
        X, Y, psi, uL, uR, s, vX, vY, w, vuL, vuR, vs = st[:12]
        slip = st[12:]
        e, n, points, depth, f, direction = forces(st)
        vec = f[:, None] * direction  # world force of each strip on the car
        along, across = vec @ e, vec @ n
        # lever rule: each strip's forces onto the two side-member tips
        to_member = [np.sum(car.alpha * along), np.sum((1 - car.alpha) * along)]
        to_member_n = [np.sum(car.alpha * across), np.sum((1 - car.alpha) * across)]
        ve, vn = vX * e[0] + vY * e[1], vX * n[0] + vY * n[1]
        te, tn, tm = car.tyre_forces(ve, vn, w, slip)
        m = car.c["members"]
        u, vu = np.array([uL, uR]), np.array([vuL, vuR])
        spring = -np.array(m["spring"]) * (u + u ** 3 / m["d0"] ** 2) - np.array(m["damper"]) * vu
        # unknowns: A (2), psi'' , u''_L, u''_R, guide forces N_L, N_R
        a = np.zeros((7, 7))
        rhs_v = np.zeros(7)
        body_force = (te * e + tn * n)
        body_moment = tm
        for i in range(2):
            xi = car.xf + u[i]
            r = xi * e + car.eta_m[i] * n
            k_cross_r = np.array([-r[1], r[0]])
            mi = car.mm[i]
            ext = to_member[i] * e + to_member_n[i] * n
            known = -w * w * r + 2 * w * vu[i] * n  # centripetal and Coriolis
            for comp in range(2):
                row = 2 * i + comp
                a[row, comp] = mi
                a[row, 2] = mi * k_cross_r[comp]
                a[row, 3 + i] = mi * e[comp]
                a[row, 5 + i] = -n[comp]
                rhs_v[row] = ext[comp] + spring[i] * e[comp] - mi * known[comp]
        # body: M A = F - sum(S_i e + N_i n);  I psi'' = M_z - sum r_i x (S_i e + N_i n)
        rows = np.zeros((3, 7))
        rvals = np.zeros(3)
        for comp in range(2):
            rows[comp, comp] = car.mb
            for i in range(2):
                rows[comp, 5 + i] = n[comp]
            rvals[comp] = body_force[comp] - sum(spring[i] * e[comp] for i in range(2))
        rows[2, 2] = car.iz
        rvals[2] = body_moment
        for i in range(2):
            r = (car.xf + u[i]) * e + car.eta_m[i] * n
            rows[2, 5 + i] = r[0] * n[1] - r[1] * n[0]
            rvals[2] -= r[0] * (spring[i] * e[1]) - r[1] * (spring[i] * e[0])
        a[4:7, :] = rows
        rhs_v[4:7] = rvals
        sol = np.linalg.solve(a, rhs_v)
        A, psidd, udd = sol[:2], sol[2], sol[3:5]
        sdd = 0.0
        if striker.kind == "pendulum":
            # the pendulum travels s towards the car; the car pushes it back
            sdd = np.sum(vec[:, 0]) / striker.mass
        slip_rates = car.slip_rates(ve, vn, w, slip)
        deriv = np.concatenate([st[6:12], [A[0], A[1], psidd, udd[0], udd[1], sdd], slip_rates])
        extras = (A, psidd, udd, vec, e, points)
        return deriv, extras

    samples = int(round((PRE + DURATION) / SAMPLE)) + 1
    every = int(round(SAMPLE / STEP))
    out = []
    # before t = 0 nothing touches: the trigger is at t = 0
    for k in range(samples):
        t = -PRE + k * SAMPLE
        if t < 0:
            out.append(record(car, striker, state, None, t))
            continue
        deriv, extras = rhs(state)
        out.append(record(car, striker, state, extras, t))
        for _ in range(every):
            k1, _ = rhs(state)
            k2, _ = rhs(state + 0.5 * STEP * k1)
            k3, _ = rhs(state + 0.5 * STEP * k2)
            k4, _ = rhs(state + STEP * k3)
            state = state + STEP / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
            depth = forces(state)[3]
            np.maximum(dmax, depth, out=dmax)
    return out


def record(car, striker, state, extras, t):
    """The channels at one sample: load cells (N), accelerometers (m/s^2)."""
    s = car.c["sills"]
    if extras is None:
        A, psidd, udd, vec, e = np.zeros(2), 0.0, np.zeros(2), None, np.array([1.0, 0.0])
        points = None
    else:
        A, psidd, udd, vec, e, points = extras
    w, u = state[8], state[3:5]
    along = A @ e
    sills = [along - psidd * s["eta"] - w * w * s["xi"], along + psidd * s["eta"] - w * w * s["xi"]]
    members = [along - psidd * car.eta_m[i] - w * w * (car.xf + u[i]) + udd[i] for i in range(2)]
    return {"t": t, "cells": cells(striker, vec, points), "sills": sills, "members": members,
            "yaw_rate": float(w)}


def cells(striker, vec, points):
    """The striker's load cells: the force on the car they carry (N)."""
    if striker.kind == "pendulum":
        return [0.0 if vec is None else float(-np.sum(vec[:, 0]))]
    if striker.kind == "pole":
        if vec is None:
            return [0.0, 0.0]
        total = np.sum(vec, axis=0)  # the force on the car: -x (pole_x) and y (pole_y)
        return [float(-total[0]), float(total[1])]
    edges = wall_cells(striker)
    if vec is None:
        return [0.0] * 4
    tangent = np.array([-striker.normal[1], striker.normal[0]])
    coord = points @ tangent
    mag = vec @ striker.normal
    return [float(np.sum(mag[(coord >= lo) & (coord < hi)])) for lo, hi in edges]


def wall_cells(striker):
    """Four equal cells across the wall's face, as tangent coordinates."""
    half = 0.5 * striker.car.c["beam"]["width"] + 0.2
    lo = max(striker.band[0], -half) if math.isfinite(striker.band[0]) else -half
    hi = min(striker.band[1], half) if math.isfinite(striker.band[1]) else half
    tangent = np.array([-striker.normal[1], striker.normal[0]])
    # y along the wall face to the tangent coordinate (the face through the car's front)
    corners = [np.array([striker.car.xf, y]) @ tangent for y in (lo, hi)]
    a, b = min(corners), max(corners)
    width = (b - a) / 4
    return [(a + j * width, a + (j + 1) * width) for j in range(4)]


def cell_centres(striker):
    """Each wall cell's centre on the face (world at t = 0, m)."""
    tangent = np.array([-striker.normal[1], striker.normal[0]])
    centres = []
    for lo, hi in wall_cells(striker):
        tau = 0.5 * (lo + hi)
        # the point on the face line with this tangent coordinate
        p = striker.level * striker.normal + tau * tangent
        centres.append([float(p[0]), float(p[1])])
    return centres


def write(out, car, test, rows, rng, index, yaw_rate=False):
    noise_f, noise_a, noise_w = 30.0, 0.05 * G, math.radians(0.1)
    bias = [0.02 * G * (1 if index % 2 else -1), -0.015 * G]
    cols = ["time [s]"]
    n_cells = len(rows[0]["cells"])
    names = {"pendulum": ["pendulum"], "pole": ["pole_x", "pole_y"]}.get(test["kind"],
                                                                       [f"cell{j + 1}" for j in range(4)])
    cols += [f"{nm} [N]" for nm in names[:n_cells]]
    cols += ["sill_left [m/s^2]", "sill_right [m/s^2]"]
    cols += ["yaw_rate [rad/s]"] if yaw_rate else ["member_left [m/s^2]", "member_right [m/s^2]"]
    lines = [",".join(cols)]
    for r in rows:
        vals = [r["t"]]
        vals += [c + rng.normal(0, noise_f) for c in r["cells"]]
        vals += [r["sills"][i] + bias[i] + rng.normal(0, noise_a) for i in range(2)]
        if yaw_rate:
            vals.append(r["yaw_rate"] + rng.normal(0, noise_w))
        else:
            vals += [r["members"][i] + rng.normal(0, noise_a) for i in range(2)]
        lines.append(",".join(f"{v:.9g}" for v in vals))
    (out / f"{test['name']}.csv").write_text("\n".join(lines) + "\n")


def study(out, car, tests, strikers, documented=False):
    c = car.c
    s = c["sills"]
    lines = [
        "# A planar study of the independent series (tests/peers/planar_independent.py).",
        "[model]",
        'planar = "start.toml"',
        "starts = 16",
        "seed = 1",
        "friction = true",
    ]
    if documented:
        # as docs/planar.md ("Defaults chosen by evidence") has a lab write it:
        # the tyres' law left to the default, the side members' law named
        # (this car's crush springs are progressive), the bumper fitted for
        # the forward predictions jointly with the car, the sills compared in
        # velocity with their biases as nuisances
        lines += ['links = "progressive"', 'bumper = "fit"', "joint = 2.0"]
    else:
        lines += [
            "# the cornering stiffness stays the start's (60 kN/rad per tyre): these tests",
            "# hardly load the tyres sideways, so they do not determine it (cornering = true",
            "# estimates it, and the identification then says it is not determined)",
            "cornering = false",
        ]
    lines += [f'mass = "{car.total_mass():.1f} kg"    # the test sheet', ""]
    if documented:
        lines += ["[identification]", 'objective = "velocity"', 'bias = "nuisance"', ""]
    for test, st in zip(tests, strikers):
        name, kind = test["name"], test["kind"]
        speed = 0.0 if kind == "pendulum" else test["speed_kmh"] / 3.6
        lines += ["[[case]]", f'name = "{name}"', f"speed = {speed!r}", "cfc = 180"]
        if not test["train"]:
            lines.append("validate = true")
        path = f"{name}.csv"
        if kind == "pendulum":
            lines.append(f'striker = {{ pendulum = {test["mass"]}, speed = "{test["speed_kmh"]} km/h" }}')
            lines.append("forces = [")
            lines.append(f'  {{ path = "{path}", channel = "pendulum", lateral = "estimate", direction = [-1.0, 0.0] }},')
        elif kind == "pole":
            ax = [c["cg_behind_bumper"] + st.radius + GAP, test["offset"]]
            lines.append(f'striker = {{ pole = {test["diameter"]}, pole_offset = {test["offset"]}, speed = "{test["speed_kmh"]} km/h" }}')
            lines.append("forces = [")
            for ch, d in (("pole_x", [-1.0, 0.0]), ("pole_y", [0.0, 1.0])):
                lines.append(f'  {{ path = "{path}", channel = "{ch}", lateral = {test["offset"]}, direction = {d}, anchor = {ax} }},')
        else:
            side = test["side"]
            lines.append(f'striker = {{ angle = {test["angle_deg"]}, overlap = {100 * test["overlap"]}, side = "{side}", speed = "{test["speed_kmh"]} km/h" }}')
            lines.append("forces = [")
            width = wall_cells(st)[0][1] - wall_cells(st)[0][0]
            for j, p in enumerate(cell_centres(st)):
                lines.append(f'  {{ path = "{path}", channel = "cell{j + 1}", lateral = {p[1]:.6f}, direction = [{st.normal[0]:.9f}, {st.normal[1]:.9f}], anchor = [{p[0]:.6f}, {p[1]:.6f}], cell = {width:.6f} }},')
        lines.append("]")
        lines.append("sensors = [")
        lines.append(f'  {{ path = "{path}", channel = "sill_left", body = [{s["xi"]}, {s["eta"]}] }},')
        lines.append(f'  {{ path = "{path}", channel = "sill_right", body = [{s["xi"]}, {-s["eta"]}] }},')
        if documented:
            lines.append(f'  {{ path = "{path}", channel = "yaw_rate" }},')
        else:
            lines.append(f'  {{ path = "{path}", channel = "member_left", chain = 0 }},')
            lines.append(f'  {{ path = "{path}", channel = "member_right", chain = 1 }},')
        lines.append("]")
        lines.append("")
    (out / ("study-doc.toml" if documented else "study.toml")).write_text("\n".join(lines))


def start(out, car):
    """A start car a lab might write: symmetric, 20-40 % off, the bumper as tested."""
    c = car.c
    b = c["beam"]
    # the bumper as its component test gives it: the strips' loading curve
    # (whole bumper) and unloading slope
    d = np.array([0.0, b["plateau"] / b["ramp"], b["bottom"], 0.12, 0.2, 0.3])
    f = np.array([float(car.foam(np.array([x]), np.array([x]))[0]) for x in d]) * b["strips"]
    curve = ", ".join(f"[{x:.6g}, {y:.6g}]" for x, y in zip(d, f))
    text = f"""# The start of the identification: a symmetric guess (not the truth).
name = "independent series start"
[body]
mass = 1400.0
yaw_inertia = 2700.0
cg_behind_bumper = {c["cg_behind_bumper"]}
wheelbase = {c["wheelbase"]}
cg_behind_front_axle = {c["cg_behind_front_axle"]}
track = {c["track"]}
[left]
masses = [16.0]
dampers = [1.5e3]
springs = [1.0e6]
[right]
masses = [16.0]
dampers = [1.5e3]
springs = [1.0e6]
[bumper]
width = {b["width"]}
side_member_spacing = {c["members"]["spacing"]}
segments = 40
curve = [{curve}]
unloading = {b["unloading"] * b["strips"]}
[tyres]
front = {{ rolling_resistance = 0.015, mu_lateral = 0.6 }}
rear = {{ rolling_resistance = 0.015, mu_lateral = 0.6 }}
"""
    (out / "start.toml").write_text(text)


# Log-normal spreads of the seeded cars (--seeds): each seed's car is the
# base car with these parameters scaled by exp(spread * N(0, 1)).
SPREADS = {"body_mass": 0.05, "yaw_inertia": 0.15, "mu": 0.15, "mass": 0.2, "spring": 0.15,
           "damper": 0.2}


def seeded(rng):
    """The base car with its mass, yaw inertia, grip and side members drawn (SPREADS)."""
    c = json.loads(json.dumps(CAR))
    factor = lambda key: math.exp(SPREADS[key] * rng.standard_normal())
    c["body_mass"] *= factor("body_mass")
    c["yaw_inertia"] *= factor("yaw_inertia")
    c["tyres"]["mu"] *= factor("mu")
    for key in ("mass", "spring", "damper"):
        c["members"][key] = [v * factor(key) for v in c["members"][key]]
    return c


def series(out, c, rng, yaw_rate=False):
    out.mkdir(parents=True, exist_ok=True)
    car = Car(c)
    tests = YAW_RATE_TESTS if yaw_rate else TESTS
    strikers = [Striker(t, car) for t in tests]
    for i, (test, st) in enumerate(zip(tests, strikers)):
        rows = simulate(car, st)
        write(out, car, test, rows, rng, i, yaw_rate)
    start(out, car)
    sheet = {"total_mass": car.total_mass(), "yaw_inertia": c["yaw_inertia"], "mu": c["tyres"]["mu"],
             "car": c, "tests": tests}
    (out / "series.json").write_text(json.dumps(sheet, indent=1))
    # last: the marker of a finished series
    study(out, car, tests, strikers, documented=yaw_rate)


def main(argv):
    out = Path(argv[0])
    yaw_rate = "--yaw-rate" in argv
    if "--seeds" not in argv:
        series(out, CAR, np.random.default_rng(11), yaw_rate)
        return
    first, count = (int(v) for v in argv[argv.index("--seeds") + 1].split(":"))
    for k in range(first, first + count):
        here = out / f"seed-{k}"
        if not (here / ("study-doc.toml" if yaw_rate else "study.toml")).exists():
            series(here, seeded(np.random.default_rng(2000 + k)), np.random.default_rng(1000 + k),
                   yaw_rate)
    (out / f"seeds-{first}-{count}.txt").write_text(f"{count}\n")  # last: the marker


if __name__ == "__main__":
    main(sys.argv[1:])
