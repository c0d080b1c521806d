#!/usr/bin/env python3
"""A planar crash-test series whose side members stiffen (issue 46): progressive links.

Usage: planar_progressive.py OUT_DIR [--contact-damping A] [--shear K] [--seed N]
                              [--right-stiffness F]

  --contact-damping A  the contact's Hunt-Crossley rate term a, s/m (default 0.05)
  --shear K            each bar's lateral (shear) stiffness, N/m (default 2e7)
  --seed N             the noise generator's seed (default 46)
  --right-stiffness F  the right side members' stiffnesses times F (default 1: the
                       series' own asymmetry)

Writes OUT_DIR/<TEST>.csv (10 kHz, `time [s]` from -20 ms; load cells in N,
two sill accelerometers in m/s^2 and a yaw-rate sensor in rad/s),
OUT_DIR/series.json (the truth, the test sheet, each test's set-up and the
largest compression of every link), OUT_DIR/study.toml (a bumpsim planar
study of the three training tests, the held-out tests as `validate = true`;
linear side members), OUT_DIR/study-progressive.toml (the same, its side
members identified progressive: `[model] links = "progressive"`),
OUT_DIR/start.toml (a symmetric linear start a lab might write) and
OUT_DIR/truth-linear.toml (bumpsim's planar car with the series' true masses,
dampers and *initial* stiffnesses: what a linear chain makes of the truth) and
OUT_DIR/truth-progressive.toml (the same with the true progressive links).

Training: a flat pendulum (1100 kg, 8 km/h), a narrow rigid face (0.3 m)
centred at 8 km/h, a 10 deg wall at 10 km/h with four load cells; held out:
a 40 % offset 10 deg wall at 15 km/h (left) and the narrow face 0.4 m off
centre.

The model is written here, of another family than bumpsim's planar car
(no segmented beam, no lever rule, no masses on guides):

- the bumper beam is a rigid body of its own (mass, rotary inertia; x, y
  and its rotation in the world: 3 DOF); its face touches the striker at 31
  points with Hunt-Crossley contact, F = k d^1.5 (1 + 1.5 a d'), a = 0.05 s/m:
  nearly elastic (restitution about 0.8 at 15 km/h), so that bumpsim's bumper,
  the static curve k d^1.5 with an unloading slope, is its translation. (At
  a = 0.25 s/m, the first version's value, the rate term is 2.6 times the
  static force at first touch at 15 km/h and the contact restitution is about 0
  there: a rate-dependent absorber that no bumpsim bumper represents; bumpsim's
  car with the series' true links then predicts the offset test's force at
  64 %. tests/planar/progressive.rs keeps that series as evidence.);
- each side member (at y = +/-b) is two point masses free in the plane
  (2 DOF each): the beam's end is bolted to the front mass by a stiff
  linear mount (1e8 N/m axially and across), the front mass joins the rear
  one by link 1 and the rear mass joins the body by link 2;
- every link is a bar measured in the body's axes (rest length L): its
  compression d = L - (r . e) carries the progressive elastic spring
  F = k d (1 + (d/d0)^2) (odd: tension mirrors compression, nothing is
  dissipated by the spring) and a viscous damper c d' in parallel; its
  shear t = r . n a linear spring k_s t, k_s = 2e7 N/m: an elastic steel
  rail segment's lateral bending, 12 E I / L^3 of a 100 x 60 x 2 mm box
  0.25-0.35 m long is 2e7-6e7 N/m (the first version's 1.5e6 N/m made a
  side member as soft across as its crush law is along). The forces derive from the
  potential V(d, t) of the bar, so the body also takes the couple
  -(V_s t - V_t s) from the turning of its axes (s = r . e): energy and
  angular momentum are exact up to the dampers, contact and tyres;
- tyres without transient slip: F_y = -mu N tanh(C_alpha alpha / (mu N)),
  alpha = atan(v_y / (|v_x| + 0.1 m/s)); rolling resistance f_r N tanh(v_x / 0.05);
- semi-implicit (symplectic) Euler at 10 us;
- channels sampled every 100 us with white noise (30 N per load cell,
  0.05 g per accelerometer with a bias, 0.1 deg/s on the yaw rate); t = 0
  is the lab's trigger, a few millimetres before first contact.

bumpsim's equivalent car: each chain masses [m1 + half the beam, m2],
springs [k1, k2] (initial slopes; the mount is 1e8 N/m in series), dampers
[c1, c2], the progressive law F = k d + (k/d0^2) d^3.
"""
import json
import math
import sys
from pathlib import Path

import numpy as np

G = 9.80665

CAR = {
    "body_mass": 1200.0, "yaw_inertia": 2300.0, "cg_behind_bumper": 2.05,
    "wheelbase": 2.65, "cg_behind_front_axle": 1.15, "track": 1.55,
    "beam": {"mass": 8.0, "width": 1.6, "points": 31, "contact": 3.9e5, "hc_damping": 0.05},
    "side_members": {
        "spacing": 1.0, "mount": 1e8, "mount_damping": 2e3, "mount_length": 0.05,
        "shear": 2e7,
        # index 0 left (+y), 1 right (-y); per side [link 1, link 2]
        "masses": [[4.0, 14.0], [5.0, 11.0]],
        "stiffness": [[1.1e6, 2.4e6], [0.9e6, 2.0e6]],
        "d0": [[0.02, 0.025], [0.018, 0.028]],
        "damping": [[1.5e3, 3.0e3], [1.2e3, 2.5e3]],
        "lengths": [0.25, 0.35],
    },
    "tyres": {"cornering_stiffness": 70e3, "mu": 0.8, "rolling_resistance": 0.015},
    "sills": {"xi": 0.5, "eta": 0.72},
}

TESTS = [
    {"name": "PENDULUM", "kind": "pendulum", "mass": 1100.0, "speed_kmh": 8.0, "train": True},
    {"name": "NARROW", "kind": "narrow", "width": 0.3, "offset": 0.0, "speed_kmh": 8.0,
     "train": True},
    {"name": "WALL10", "kind": "wall", "angle_deg": 10.0, "overlap": 1.0, "side": "left",
     "speed_kmh": 10.0, "train": True},
    {"name": "OFFSET40", "kind": "wall", "angle_deg": 10.0, "overlap": 0.4, "side": "left",
     "speed_kmh": 15.0, "train": False},
    {"name": "NARROW-OFFSET", "kind": "narrow", "width": 0.3, "offset": 0.4, "speed_kmh": 8.0,
     "train": False},
]

STEP, SAMPLE, PRE, DURATION, GAP = 1e-5, 1e-4, 0.02, 0.18, 0.004
BODY, BEAM, PEND = slice(0, 3), slice(3, 6), 14


def axes(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c, s]), np.array([-s, c])


def cross(r, f):
    return r[0] * f[1] - r[1] * f[0]


def spin(w, r):
    return w * np.array([-r[1], r[0]])


class Car:
    """The truth; generalised coordinates q = body X, Y, psi; beam x, y, theta;
    left front, left rear, right front, right rear mass (x, y each); pendulum s."""

    def __init__(self, c):
        self.c = c
        sm = c["side_members"]
        self.xf = c["cg_behind_bumper"]
        self.eta = [0.5 * sm["spacing"], -0.5 * sm["spacing"]]
        b = c["beam"]
        self.Jb = b["mass"] * b["width"] ** 2 / 12.0
        self.y_pts = np.linspace(-0.5 * b["width"], 0.5 * b["width"], b["points"])
        L, a, tw = c["wheelbase"], c["cg_behind_front_axle"], c["track"]
        self.wheels = [(a, 0.5 * tw), (a, -0.5 * tw), (a - L, 0.5 * tw), (a - L, -0.5 * tw)]
        front, rear = self.total_mass() * G * (L - a) / L, self.total_mass() * G * a / L
        self.normal_loads = [0.5 * front, 0.5 * front, 0.5 * rear, 0.5 * rear]
        l1, l2 = sm["lengths"]
        x1 = self.xf - sm["mount_length"]
        # rest positions (body frame): front mass, rear mass, body anchor
        self.rest = [(x1, x1 - l1, x1 - l1 - l2) for _ in range(2)]
        self.mass = np.array([b["mass"]] * 2 + [sm["masses"][s][j] for s in range(2) for j in range(2)])

    def total_mass(self):
        return self.c["body_mass"] + self.c["beam"]["mass"] + sum(map(sum, self.c["side_members"]["masses"]))

    def initial(self, speed):
        """q, v at rest position moving at `speed` along x."""
        q = np.zeros(15)
        q[3] = self.xf
        for s in range(2):
            front, rear, _ = self.rest[s]
            q[6 + 4 * s: 10 + 4 * s] = [front, self.eta[s], rear, self.eta[s]]
        v = np.zeros(15)
        v[[0, 3, 6, 8, 10, 12]] = speed
        return q, v


def bar(q, v, e, n, w_body, p, vp, a, va, length, spring, shear, damping):
    """Forces on the two ends (p front, a rear) of a bar in the body's axes and
    the couple on the body from the turning of its axes; spring(d) -> (F, dF)."""
    r, dr = p - a, vp - va
    s, t = r @ e, r @ n
    # the rate of compression in the turning body frame
    ds = dr @ e + w_body * t
    d = length - s
    f_axial = spring(d) + damping * (-ds)      # compression force, pushes ends apart
    v_s, v_t = -f_axial, shear * t            # dV/ds (with the damper's share), dV/dt
    force = -(v_s * e + v_t * n)               # on the front end
    couple = -(v_s * t - v_t * s)              # on the body, from e(psi), n(psi)
    return force, -force, couple, d


def progressive(k, d0):
    return lambda d: k * d * (1.0 + (d / d0) ** 2)


class Striker:
    def __init__(self, test, car):
        self.kind, self.test, self.car = test["kind"], test, car
        self.speed = test["speed_kmh"] / 3.6
        half = 0.5 * car.c["beam"]["width"]
        if self.kind == "pendulum":
            self.mass = test["mass"]
            self.normal = np.array([-1.0, 0.0])
        elif self.kind == "narrow":
            self.normal = np.array([-1.0, 0.0])
            self.face = car.xf + GAP
            self.band = (test["offset"] - 0.5 * test["width"], test["offset"] + 0.5 * test["width"])
        else:
            th = math.radians(test["angle_deg"])
            self.normal = np.array([-math.cos(th), -math.sin(th)])
            cover = test["overlap"] * 2 * half
            self.band = (half - cover, math.inf) if test["side"] == "left" else (-math.inf, cover - half)
            ends = [np.array([car.xf, y]) for y in (max(self.band[0], -half), min(self.band[1], half))]
            self.level = min(self.normal @ p for p in ends) - GAP

    def depth(self, points, s):
        """Penetration (m) of each beam point (world); negative where it cannot touch."""
        if self.kind == "pendulum":
            return points[:, 0] - (self.car.xf + GAP - s)
        inside = (points[:, 1] >= self.band[0]) & (points[:, 1] <= self.band[1])
        if self.kind == "narrow":
            return np.where(inside, points[:, 0] - self.face, -1.0)
        return np.where(inside, self.level - points @ self.normal, -1.0)

    def cells(self):
        """The wall's four load cells (tangent coordinate ranges), else one."""
        if self.kind != "wall":
            return None
        half = 0.5 * self.car.c["beam"]["width"] + 0.2
        lo = max(self.band[0], -half) if math.isfinite(self.band[0]) else -half
        hi = min(self.band[1], half) if math.isfinite(self.band[1]) else half
        t = self.tangent()
        a, b = sorted(np.array([self.car.xf, y]) @ t for y in (lo, hi))
        width = (b - a) / 4
        return [(a + j * width, a + (j + 1) * width) for j in range(4)]

    def tangent(self):
        return np.array([-self.normal[1], self.normal[0]])


def accelerations(car, striker, q, v, links):
    c, sm = car.c, car.c["side_members"]
    f = np.zeros(15)
    e, n = axes(q[2])
    X = q[0:2]
    # the side members: mount (beam end to front mass), link 1, link 2
    eb, nb = axes(q[5])
    beam_c, beam_v = q[3:5], v[3:5]
    for s in range(2):
        i1, i2 = 6 + 4 * s, 8 + 4 * s
        B = beam_c + car.eta[s] * nb
        vB = beam_v + spin(v[5], B - beam_c)
        _, _, anchor_x = car.rest[s]
        A = X + anchor_x * e + car.eta[s] * n
        vA = v[0:2] + spin(v[2], A - X)
        ends = [(B, vB, None), (q[i1:i1 + 2], v[i1:i1 + 2], i1), (q[i2:i2 + 2], v[i2:i2 + 2], i2),
                (A, vA, None)]
        laws = [(sm["mount_length"], lambda d: sm["mount"] * d, sm["mount"], sm["mount_damping"])]
        for j in range(2):
            laws.append((sm["lengths"][j], progressive(sm["stiffness"][s][j], sm["d0"][s][j]),
                         sm["shear"], sm["damping"][s][j]))
        for j, (length, spring, shear, damping) in enumerate(laws):
            (p, vp, ip), (a, va, ia) = ends[j], ends[j + 1]
            fp, fa, couple, d = bar(q, v, e, n, v[2], p, vp, a, va, length, spring, shear, damping)
            if j > 0 and links is not None:
                links[2 * s + j - 1] = max(links[2 * s + j - 1], d)
            f[2] += couple
            if ip is None:  # the beam's end
                f[3:5] += fp
                f[5] += cross(p - beam_c, fp)
            else:
                f[ip:ip + 2] += fp
            if ia is None:  # the body's anchor
                f[0:2] += fa
                f[2] += cross(a - X, fa)
            else:
                f[ia:ia + 2] += fa
    # contact at the beam's face
    points = beam_c + np.outer(car.y_pts, nb)
    rel = points - beam_c
    vel = beam_v + v[5] * np.column_stack([-rel[:, 1], rel[:, 0]])
    if striker.kind == "pendulum":
        vel = vel - np.array([-v[PEND], 0.0])
    depth = striker.depth(points, q[PEND])
    rate = -(vel @ striker.normal)
    bc = c["beam"]
    mag = np.where(depth > 0, bc["contact"] * np.maximum(depth, 0) ** 1.5
                   * (1 + 1.5 * bc["hc_damping"] * rate), 0.0)
    forces = np.maximum(mag, 0.0)[:, None] * striker.normal[None, :]
    f[3:5] += forces.sum(axis=0)
    f[5] += np.sum(rel[:, 0] * forces[:, 1] - rel[:, 1] * forces[:, 0])
    # tyres on the body
    ve, vn = v[0:2] @ e, v[0:2] @ n
    t = c["tyres"]
    for (xi, eta), N in zip(car.wheels, car.normal_loads):
        we, wn = ve - v[2] * eta, vn + v[2] * xi
        alpha = math.atan(wn / (abs(we) + 0.1))
        fy = -t["mu"] * N * math.tanh(t["cornering_stiffness"] * alpha / (t["mu"] * N))
        fx = -t["rolling_resistance"] * N * math.tanh(we / 0.05)
        fw = fx * e + fy * n
        f[0:2] += fw
        f[2] += cross(xi * e + eta * n, fw)
    a = np.empty(15)
    a[0:2] = f[0:2] / c["body_mass"]
    a[2] = f[2] / c["yaw_inertia"]
    a[3:5] = f[3:5] / bc["mass"]
    a[5] = f[5] / car.Jb
    for k, m in enumerate(car.mass[2:]):
        a[6 + 2 * k: 8 + 2 * k] = f[6 + 2 * k: 8 + 2 * k] / m
    a[PEND] = forces[:, 0].sum() / striker.mass if striker.kind == "pendulum" else 0.0
    return a, forces, points


def simulate(car, striker):
    if striker.kind == "pendulum":
        q, v = car.initial(0.0)
        v[PEND] = striker.speed
    else:
        q, v = car.initial(striker.speed)
    links = [0.0] * 4
    rows = []
    every = int(round(SAMPLE / STEP))
    for k in range(int(round((PRE + DURATION) / SAMPLE)) + 1):
        t = -PRE + k * SAMPLE
        if t < 0:
            rows.append(None)
            continue
        a, forces, points = accelerations(car, striker, q, v, None)
        rows.append(record(car, striker, q, v, a, forces, points))
        for _ in range(every):
            a, _, _ = accelerations(car, striker, q, v, links)
            v = v + STEP * a
            q = q + STEP * v
    return rows, links


def record(car, striker, q, v, a, forces, points):
    s = car.c["sills"]
    e, _ = axes(q[2])
    w = v[2]
    along = a[0:2] @ e
    sills = [along - a[2] * s["eta"] - w * w * s["xi"], along + a[2] * s["eta"] - w * w * s["xi"]]
    edges = striker.cells()
    if edges is None:
        cells = [float(-forces[:, 0].sum())]
    else:
        coord = np.clip(points @ striker.tangent(), edges[0][0], edges[-1][1] - 1e-9)
        mag = forces @ striker.normal
        cells = [float(np.sum(mag[(coord >= lo) & (coord < hi)])) for lo, hi in edges]
    return {"cells": cells, "sills": sills, "yaw_rate": w}


def names(striker):
    return ["load_cell"] if striker.cells() is None else [f"cell{j + 1}" for j in range(4)]


def write(out, test, striker, rows, rng, index):
    noise_f, noise_a, noise_w = 30.0, 0.05 * G, math.radians(0.1)
    bias = [0.02 * G * (1 if index % 2 else -1), -0.015 * G]
    cells = names(striker)
    lines = [",".join(["time [s]"] + [f"{c} [N]" for c in cells]
                      + ["sill_left [m/s^2]", "sill_right [m/s^2]", "yaw_rate [rad/s]"])]
    for k, r in enumerate(rows):
        r = r or {"cells": [0.0] * len(cells), "sills": [0.0, 0.0], "yaw_rate": 0.0}
        vals = [-PRE + k * SAMPLE]
        vals += [c + rng.normal(0, noise_f) for c in r["cells"]]
        vals += [r["sills"][i] + bias[i] + rng.normal(0, noise_a) for i in range(2)]
        vals.append(r["yaw_rate"] + rng.normal(0, noise_w))
        lines.append(",".join(f"{x:.9g}" for x in vals))
    (out / f"{test['name']}.csv").write_text("\n".join(lines) + "\n")


def study(out, car, strikers, file, links):
    s = car.c["sills"]
    lines = [
        "# A planar study of the series of tests/peers/planar_progressive.py",
        "# (progressive side members; sills and the yaw-rate sensor).",
        "[model]", 'planar = "start.toml"', "starts = 16", "seed = 1", "friction = true",
        "cornering = false", "relaxation = false", f'mass = "{car.total_mass():.1f} kg"    # the test sheet',
    ] + ([f'links = "{links}"'] if links else []) + [""]
    for test, st in zip(TESTS, strikers):
        name, path = test["name"], f"{test['name']}.csv"
        speed = 0.0 if st.kind == "pendulum" else st.speed
        lines += ["[[case]]", f'name = "{name}"', f"speed = {speed!r}", "cfc = 180"]
        if not test["train"]:
            lines.append("validate = true")
        if st.kind == "pendulum":
            lines.append(f'striker = {{ pendulum = {st.mass}, speed = "{test["speed_kmh"]} km/h" }}')
            lines += ["forces = [", f'  {{ path = "{path}", channel = "load_cell", lateral = "estimate", direction = [-1.0, 0.0] }},']
        elif st.kind == "narrow":
            lines += ["forces = [", f'  {{ path = "{path}", channel = "load_cell", direction = [-1.0, 0.0], anchor = [{st.face:.6f}, {test["offset"]}] }},']
        else:
            lines.append(f'striker = {{ angle = {test["angle_deg"]}, overlap = {100 * test["overlap"]}, side = "{test["side"]}", speed = "{test["speed_kmh"]} km/h" }}')
            lines.append("forces = [")
            edges, t = st.cells(), st.tangent()
            for j, (lo, hi) in enumerate(edges):
                p = st.level * st.normal + 0.5 * (lo + hi) * t
                lines.append(f'  {{ path = "{path}", channel = "cell{j + 1}", direction = [{st.normal[0]:.9f}, {st.normal[1]:.9f}], anchor = [{p[0]:.6f}, {p[1]:.6f}], cell = {hi - lo:.6f} }},')
        lines += ["]", "sensors = ["]
        lines.append(f'  {{ path = "{path}", channel = "sill_left", body = [{s["xi"]}, {s["eta"]}] }},')
        lines.append(f'  {{ path = "{path}", channel = "sill_right", body = [{s["xi"]}, {-s["eta"]}] }},')
        lines.append(f'  {{ path = "{path}", channel = "yaw_rate" }},')
        lines += ["]", ""]
    (out / file).write_text("\n".join(lines))


LIMIT = 0.3  # m: bumpsim's progressive limit, far past any crush of the series


def progressive_links(side, springs, d0):
    """`[[side.links]]` of bumpsim's progressive law k d + (k/d0^2) d^3 up to LIMIT."""
    return "".join(
        f'[[{side}.links]]\ncurve = "progressive"\nstiffness = "{k!r} N/m"\n'
        f'limit = "{LIMIT} m"\nlimit_force = "{k * LIMIT * (1 + (LIMIT / d) ** 2)!r} N"\n'
        for k, d in zip(springs, d0))


def car_file(car, name, body_mass, inertia, left, right, mu, d0=None):
    """A bumpsim planar car file: chains `left`, `right` = (masses, dampers, springs);
    with `d0` (per side, per link) the springs are the progressive links' initial slopes."""
    c, b = car.c, car.c["beam"]
    # knots dense enough that the linear interpolation follows d^1.5 within 1 %
    # from 0.2 mm (seven knots made it up to 40 % too stiff below 10 mm)
    d = np.concatenate([[0.0], np.geomspace(2e-4, 0.15, 40)])
    curve = ", ".join(f"[{x:.6g}, {y:.6g}]" for x, y in zip(d, b["contact"] * b["points"] * d ** 1.5))

    def chain(side, ch):
        head = f"[{side}]\nmasses = {list(ch[0])}\ndampers = {list(ch[1])}\n"
        if d0 is None:
            return head + f"springs = {list(ch[2])}\n"
        return head + progressive_links(side, ch[2], d0[0 if side == "left" else 1])
    return f"""# {name}
name = "{name}"
[body]
mass = {body_mass}
yaw_inertia = {inertia}
cg_behind_bumper = {c["cg_behind_bumper"]}
wheelbase = {c["wheelbase"]}
cg_behind_front_axle = {c["cg_behind_front_axle"]}
track = {c["track"]}
{chain("left", left)}{chain("right", right)}[bumper]
width = {b["width"]}
side_member_spacing = {c["side_members"]["spacing"]}
segments = 32
curve = [{curve}]
unloading = {1.5 * b["contact"] * b["points"] * 0.1 ** 0.5:.6g}
[tyres]
front = {{ rolling_resistance = 0.015, mu_lateral = {mu} }}
rear = {{ rolling_resistance = 0.015, mu_lateral = {mu} }}
"""


def options(argv):
    """OUT_DIR and the options of the usage."""
    keys = {"--contact-damping": float, "--shear": float, "--seed": int,
            "--right-stiffness": float}
    out, given, rest = None, {}, list(argv)
    while rest:
        word = rest.pop(0)
        if word in keys and rest:
            given[word] = keys[word](rest.pop(0))
        elif out is None and not word.startswith("--"):
            out = word
        else:
            sys.exit(f"planar_progressive.py: unexpected {word!r}\n{__doc__}")
    if out is None:
        sys.exit(__doc__)
    return out, given


def main(argv):
    out, given = options(argv)
    CAR["beam"]["hc_damping"] = given.get("--contact-damping", CAR["beam"]["hc_damping"])
    CAR["side_members"]["shear"] = given.get("--shear", CAR["side_members"]["shear"])
    factor = given.get("--right-stiffness", 1.0)
    CAR["side_members"]["stiffness"][1] = [factor * k for k in CAR["side_members"]["stiffness"][1]]
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    car = Car(CAR)
    rng = np.random.default_rng(given.get("--seed", 46))
    strikers = [Striker(t, car) for t in TESTS]
    peaks, crush = {}, {}
    for i, (test, st) in enumerate(zip(TESTS, strikers)):
        rows, links = simulate(car, st)
        peaks[test["name"]] = max(abs(r["yaw_rate"]) for r in rows if r)
        crush[test["name"]] = {"left": links[0:2], "right": links[2:4]}
        write(out, test, st, rows, rng, i)
    sm = CAR["side_members"]
    half = 0.5 * CAR["beam"]["mass"]
    chain = lambda s: ([sm["masses"][s][0] + half, sm["masses"][s][1]], sm["damping"][s],
                       sm["stiffness"][s])
    (out / "truth-linear.toml").write_text(car_file(
        car, "the truth with linear links (initial stiffnesses)", CAR["body_mass"],
        CAR["yaw_inertia"], chain(0), chain(1), CAR["tyres"]["mu"]))
    (out / "truth-progressive.toml").write_text(car_file(
        car, "the truth in bumpsim's form: progressive links", CAR["body_mass"],
        CAR["yaw_inertia"], chain(0), chain(1), CAR["tyres"]["mu"], sm["d0"]))
    guess = ([8.0, 12.0], [1.5e3, 2.5e3], [1.5e6, 1.5e6])
    (out / "start.toml").write_text(car_file(
        car, "progressive series start: a symmetric linear guess (not the truth)", 1180.0,
        2900.0, guess, guess, 0.6))
    sheet = {"total_mass": car.total_mass(), "yaw_inertia": CAR["yaw_inertia"],
             "mu": CAR["tyres"]["mu"], "car": CAR, "tests": TESTS, "peak_yaw_rate": peaks,
             "largest_link_compression": crush}
    (out / "series.json").write_text(json.dumps(sheet, indent=1))
    study(out, car, strikers, "study-progressive.toml", "progressive")
    study(out, car, strikers, "study.toml", None)  # last: the marker of a finished series


if __name__ == "__main__":
    main(sys.argv[1:])
