#!/usr/bin/env python3
"""A second independent planar crash-test series (issue 44): sills and a yaw-rate sensor.

Usage: planar_yaw_rate.py OUT_DIR [--seed N]

`--seed N` (N >= 1) varies the car: the body and beam masses, the yaw
inertia, the grip mu and the cornering stiffness, and each crash box's
elastic stiffness, yield force, hardening and damper, each by a factor drawn
uniformly within +/-15 % (numpy's generator seeded with N), and the channels'
noise from a generator of its own (44 + 1000 N); the geometry, the sensors,
the tests and the start car stay. Without it the car and noise are the
defaults below (the series is byte-identical to the one before the option).

Writes OUT_DIR/<TEST>.csv (10 kHz, `time [s]` from -20 ms; load cells in N,
two sill accelerometers in m/s^2 and a yaw-rate sensor in rad/s, nothing
else), OUT_DIR/series.json (the truth, the test sheet, each test's set-up),
OUT_DIR/study.toml (a bumpsim planar study of the three training tests with
the yaw-rate sensor, the held-out tests as `validate = true`),
OUT_DIR/study-sills.toml (the same without the yaw-rate sensor),
OUT_DIR/study-doc.toml (the same study as docs/planar.md has a lab write
it: the tyres' law by default, `links = "yielding"`, `bumper = "fit"`,
`joint = 2.0`, the sills in velocity with nuisance biases) and
OUT_DIR/start.toml (a symmetric start a lab might write).

Training: a flat pendulum, a narrow rigid face (0.3 m) centred, a 10 deg
wall with four load cells; held out: a 40 % offset 10 deg wall at 15 km/h
and the narrow face 0.4 m off centre.

The model is written here and is of a third family, neither bumpsim's
planar car nor tests/peers/planar_independent.py:

- the bumper beam is a rigid body of its own (mass, rotary inertia; x, y
  and its own rotation in the world: 3 DOF), joined to the body by two
  crash boxes at y = +/-b: each an axial bar, elastic-plastic with linear
  isotropic hardening (1-D return mapping) plus a viscous part, and a
  linear shear spring across it, clamped in the side member (its force
  reaches the body through its front end: the pair on beam and body is
  collinear, angular momentum is conserved); no masses on guides, no
  lever rule;
- the beam's face touches the striker at 31 points with Hunt-Crossley
  contact, F = k d^1.5 (1 + 1.5 a d'), elastic (no foam history);
- tyres without transient slip: F_y = -mu N tanh(C_alpha alpha / (mu N)),
  alpha = atan(v_y / (|v_x| + 0.1 m/s)); rolling resistance f_r N tanh(v_x / 0.05);
- semi-implicit (symplectic) Euler at 10 us;
- channels sampled every 100 us with white noise (30 N per load cell,
  0.05 g per accelerometer with a bias, 0.1 deg/s on the yaw rate); t = 0
  is the lab's trigger, a few millimetres before first contact.
"""
import json
import math
import sys
from pathlib import Path

import numpy as np

G = 9.80665

CAR = {
    "body_mass": 1230.0, "yaw_inertia": 2300.0, "cg_behind_bumper": 2.05,
    "wheelbase": 2.65, "cg_behind_front_axle": 1.15, "track": 1.55,
    "beam": {"mass": 9.0, "width": 1.6, "points": 31, "contact": 3.9e5, "hc_damping": 0.25},
    "crash_boxes": {"spacing": 1.0, "length": 0.25, "elastic": [2.6e6, 2.1e6],
                    "yield": [75e3, 62e3], "hardening": [1.6e5, 1.2e5],
                    "damping": [2.4e3, 2.0e3], "shear": 1.2e6},
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


def rot(a):
    c, s = math.cos(a), math.sin(a)
    return np.array([c, s]), np.array([-s, c])


class Car:
    def __init__(self, c):
        self.c = c
        self.M, self.I = c["body_mass"], c["yaw_inertia"]
        b = c["beam"]
        self.mb = b["mass"]
        self.Jb = b["mass"] * b["width"] ** 2 / 12.0
        self.xf = c["cg_behind_bumper"]
        self.y_pts = np.linspace(-0.5 * b["width"], 0.5 * b["width"], b["points"])
        cb = c["crash_boxes"]
        self.eta_cb = np.array([0.5 * cb["spacing"], -0.5 * cb["spacing"]])
        L, a, tw = c["wheelbase"], c["cg_behind_front_axle"], c["track"]
        self.wheels = [(a, 0.5 * tw), (a, -0.5 * tw), (a - L, 0.5 * tw), (a - L, -0.5 * tw)]
        total = self.total_mass()
        front, rear = total * G * (L - a) / L, total * G * a / L
        self.normal_loads = [0.5 * front, 0.5 * front, 0.5 * rear, 0.5 * rear]

    def total_mass(self):
        return self.M + self.mb


class Striker:
    def __init__(self, test, car):
        self.kind, self.test, self.car = test["kind"], test, car
        v = test["speed_kmh"] / 3.6
        if self.kind == "pendulum":
            self.mass, self.speed = test["mass"], v
            self.normal = np.array([-1.0, 0.0])
        elif self.kind == "narrow":
            self.normal = np.array([-1.0, 0.0])
            self.face = car.xf + GAP
            half = 0.5 * test["width"]
            self.band = (test["offset"] - half, test["offset"] + half)
        else:
            th = math.radians(test["angle_deg"])
            self.normal = np.array([-math.cos(th), -math.sin(th)])
            half = 0.5 * car.c["beam"]["width"]
            cover = test["overlap"] * 2 * half
            self.band = (half - cover, math.inf) if test["side"] == "left" else (-math.inf, cover - half)
            ends = [np.array([car.xf, y]) for y in (max(self.band[0], -half), min(self.band[1], half))]
            self.level = min(self.normal @ p for p in ends) - GAP

    def depth(self, points, s):
        """Penetration (m) of each beam point (world), -1 where it cannot touch."""
        if self.kind == "pendulum":
            return points[:, 0] - (self.car.xf + GAP - s)
        if self.kind == "narrow":
            inside = (points[:, 1] >= self.band[0]) & (points[:, 1] <= self.band[1])
            return np.where(inside, points[:, 0] - self.face, -1.0)
        d = self.level - points @ self.normal
        inside = (points[:, 1] >= self.band[0]) & (points[:, 1] <= self.band[1])
        return np.where(inside, d, -1.0)


class State:
    """q: body X, Y, psi; beam x, y, theta (world); s (pendulum travel)."""

    def __init__(self, car, striker):
        self.q = np.zeros(7)
        self.v = np.zeros(7)
        self.q[3] = car.xf  # the beam's centre, world, at rest
        if striker.kind == "pendulum":
            self.v[6] = striker.speed
        else:
            self.v[0] = self.v[3] = striker.test["speed_kmh"] / 3.6
        cb = car.c["crash_boxes"]
        self.plastic = np.zeros(2)   # plastic elongation (m)
        self.hardened = np.zeros(2)  # accumulated plastic crush (m)
        self.axial = np.zeros(2)     # elastic-plastic axial force, tension +
        self.k = np.array(cb["elastic"])
        self.fy = np.array(cb["yield"])
        self.h = np.array(cb["hardening"])


def crash_box_geometry(car, q, v):
    """Each crash box's elongation and shear (body axes) and their rates."""
    e, n = rot(q[2])
    eb, nb = rot(q[5])
    L0 = car.c["crash_boxes"]["length"]
    out = []
    for i, eta in enumerate(car.eta_cb):
        A = q[0:2] + (car.xf - L0) * e + eta * n           # rear end on the body
        B = q[3:5] + eta * nb                               # front end on the beam
        vA = v[0:2] + v[2] * np.array([-(A - q[0:2])[1], (A - q[0:2])[0]])
        vB = v[3:5] + v[5] * np.array([-(B - q[3:5])[1], (B - q[3:5])[0]])
        d, dv = B - A, vB - vA
        out.append((A, B, d @ e - L0, d @ n, dv @ e, dv @ n, e, n))
    return out


def return_map(st, elongation):
    """1-D elastic-plastic bar with linear isotropic hardening."""
    trial = st.k * (elongation - st.plastic)
    limit = st.fy + st.h * st.hardened
    over = np.abs(trial) - limit
    for i in range(2):
        if over[i] > 0:
            dg = over[i] / (st.k[i] + st.h[i])
            sign = math.copysign(1.0, trial[i])
            st.plastic[i] += sign * dg
            st.hardened[i] += dg
    st.axial = st.k * (elongation - st.plastic)


def accelerations(car, striker, st, q, v):
    """Generalised accelerations, the contact forces per point (world) and the cells' inputs."""
    c = car.c
    cb = c["crash_boxes"]
    a = np.zeros(7)
    F_body, M_body = np.zeros(2), 0.0
    F_beam, M_beam = np.zeros(2), 0.0
    cross = lambda r, f: r[0] * f[1] - r[1] * f[0]
    for i, (A, B, el, sh, del_, dsh, e, n) in enumerate(crash_box_geometry(car, q, v)):
        axial = st.axial[i] + cb["damping"][i] * del_   # tension +
        shear = cb["shear"] * sh
        f_on_beam = -(axial * e + shear * n)
        F_beam += f_on_beam
        M_beam += cross(B - q[3:5], f_on_beam)
        F_body -= f_on_beam
        # the crash box is clamped in the side member: the force it takes
        # from the beam at B reaches the body with its moment about B (the
        # root carries the shear's lever L0), so the pair on beam and body
        # is collinear and the angular momentum is conserved. Applied at A
        # instead, the pair's couple L0 x shear came from nothing: +15 % of
        # the contact's angular impulse in the 10 deg walls, none in the
        # narrow faces (no lateral load, no shear)
        M_body += cross(B - q[0:2], -f_on_beam)
    # contact at the beam's face
    eb, nb = rot(q[5])
    points = q[3:5] + np.outer(car.y_pts, nb)
    rel = points - q[3:5]
    vel = v[3:5] + v[5] * np.column_stack([-rel[:, 1], rel[:, 0]])
    if striker.kind == "pendulum":
        vel = vel - np.array([-v[6], 0.0])  # the face moves towards the car
    depth = striker.depth(points, q[6])
    rate = -(vel @ striker.normal)
    bc = c["beam"]
    touching = depth > 0
    mag = np.where(touching, bc["contact"] * np.maximum(depth, 0) ** 1.5
                   * (1 + 1.5 * bc["hc_damping"] * rate), 0.0)
    mag = np.maximum(mag, 0.0)
    forces = mag[:, None] * striker.normal[None, :]
    F_beam += forces.sum(axis=0)
    M_beam += np.sum(rel[:, 0] * forces[:, 1] - rel[:, 1] * forces[:, 0])
    # tyres on the body
    e, n = rot(q[2])
    ve, vn = v[0:2] @ e, v[0:2] @ n
    t = c["tyres"]
    for (xi, eta), N in zip(car.wheels, car.normal_loads):
        we, wn = ve - v[2] * eta, vn + v[2] * xi
        alpha = math.atan(wn / (abs(we) + 0.1))
        fy = -t["mu"] * N * math.tanh(t["cornering_stiffness"] * alpha / (t["mu"] * N))
        fx = -t["rolling_resistance"] * N * math.tanh(we / 0.05)
        f = fx * e + fy * n
        F_body += f
        M_body += cross(xi * e + eta * n, f)
    a[0:2] = F_body / car.M
    a[2] = M_body / car.I
    a[3:5] = F_beam / car.mb
    a[5] = M_beam / car.Jb
    if striker.kind == "pendulum":
        a[6] = forces[:, 0].sum() / striker.mass  # the car pushes the pendulum back
    return a, forces, points


def simulate(car, striker):
    st = State(car, striker)
    samples = int(round((PRE + DURATION) / SAMPLE)) + 1
    every = int(round(SAMPLE / STEP))
    rows = []
    for k in range(samples):
        t = -PRE + k * SAMPLE
        if t < 0:
            rows.append(record(car, striker, st, None))
            continue
        a, forces, points = accelerations(car, striker, st, st.q, st.v)
        rows.append(record(car, striker, st, (a, forces, points)))
        for _ in range(every):
            a, _, _ = accelerations(car, striker, st, st.q, st.v)
            st.v = st.v + STEP * a
            st.q = st.q + STEP * st.v
            geometry = crash_box_geometry(car, st.q, st.v)
            return_map(st, np.array([g[2] for g in geometry]))
    return rows


def record(car, striker, st, extras):
    s = car.c["sills"]
    if extras is None:
        return {"cells": cells(striker, None, None), "sills": [0.0, 0.0], "yaw_rate": 0.0}
    a, forces, points = extras
    e, _ = rot(st.q[2])
    w = st.v[2]
    along = a[0:2] @ e
    sills = [along - a[2] * s["eta"] - w * w * s["xi"], along + a[2] * s["eta"] - w * w * s["xi"]]
    return {"cells": cells(striker, forces, points), "sills": sills, "yaw_rate": w}


def cells(striker, forces, points):
    if striker.kind in ("pendulum", "narrow"):
        return [0.0 if forces is None else float(-forces[:, 0].sum())]
    edges = wall_cells(striker)
    if forces is None:
        return [0.0] * 4
    tangent = np.array([-striker.normal[1], striker.normal[0]])
    # a point touching the wall is on one of its cells: the wall ends where
    # its cells do (the car's travel moves a point's tangent coordinate)
    coord = np.clip(points @ tangent, edges[0][0], edges[-1][1] - 1e-9)
    mag = forces @ striker.normal
    return [float(np.sum(mag[(coord >= lo) & (coord < hi)])) for lo, hi in edges]


def wall_cells(striker):
    half = 0.5 * striker.car.c["beam"]["width"] + 0.2
    lo = max(striker.band[0], -half) if math.isfinite(striker.band[0]) else -half
    hi = min(striker.band[1], half) if math.isfinite(striker.band[1]) else half
    tangent = np.array([-striker.normal[1], striker.normal[0]])
    corners = [np.array([striker.car.xf, y]) @ tangent for y in (lo, hi)]
    a, b = min(corners), max(corners)
    width = (b - a) / 4
    return [(a + j * width, a + (j + 1) * width) for j in range(4)]


def cell_centres(striker):
    tangent = np.array([-striker.normal[1], striker.normal[0]])
    out = []
    for lo, hi in wall_cells(striker):
        p = striker.level * striker.normal + 0.5 * (lo + hi) * tangent
        out.append([float(p[0]), float(p[1])])
    return out


def names(test):
    if test["kind"] in ("pendulum", "narrow"):
        return ["load_cell"]
    return [f"cell{j + 1}" for j in range(4)]


def write(out, test, rows, rng, index):
    noise_f, noise_a, noise_w = 30.0, 0.05 * G, math.radians(0.1)
    bias = [0.02 * G * (1 if index % 2 else -1), -0.015 * G]
    cols = ["time [s]"] + [f"{nm} [N]" for nm in names(test)]
    cols += ["sill_left [m/s^2]", "sill_right [m/s^2]", "yaw_rate [rad/s]"]
    lines = [",".join(cols)]
    for k, r in enumerate(rows):
        vals = [-PRE + k * SAMPLE]
        vals += [c + rng.normal(0, noise_f) for c in r["cells"]]
        vals += [r["sills"][i] + bias[i] + rng.normal(0, noise_a) for i in range(2)]
        vals.append(r["yaw_rate"] + rng.normal(0, noise_w))
        lines.append(",".join(f"{v:.9g}" for v in vals))
    (out / f"{test['name']}.csv").write_text("\n".join(lines) + "\n")


def study(out, car, strikers, yaw_rate, file, documented=False):
    c, s = car.c, car.c["sills"]
    lines = [
        "# A planar study of the series of tests/peers/planar_yaw_rate.py"
        + (" (sills and the yaw-rate sensor)." if yaw_rate else " (the sills alone)."),
        "[model]", 'planar = "start.toml"', "starts = 16", "seed = 1", "friction = true",
    ]
    if documented:
        # as docs/planar.md ("Defaults chosen by evidence") has a lab write it:
        # the tyres' law left to the default, the crash boxes' law named (they
        # yield), the bumper fitted for the forward predictions jointly with
        # the car, the sills compared in velocity with their biases as
        # nuisances ("The joint final stage")
        lines += ['links = "yielding"', 'bumper = "fit"', "joint = 2.0"]
    else:
        lines += ["cornering = false", "relaxation = false"]
    lines += [f'mass = "{car.total_mass():.1f} kg"    # the test sheet', ""]
    if documented:
        lines += ["[identification]", 'objective = "velocity"', 'bias = "nuisance"', ""]
    for test, st in zip(TESTS, strikers):
        name, kind = test["name"], test["kind"]
        speed = 0.0 if kind == "pendulum" else test["speed_kmh"] / 3.6
        lines += ["[[case]]", f'name = "{name}"', f"speed = {speed!r}", "cfc = 180"]
        if not test["train"]:
            lines.append("validate = true")
        path = f"{name}.csv"
        if kind == "pendulum":
            lines.append(f'striker = {{ pendulum = {test["mass"]}, speed = "{test["speed_kmh"]} km/h" }}')
            lines.append("forces = [")
            lines.append(f'  {{ path = "{path}", channel = "load_cell", lateral = "estimate", direction = [-1.0, 0.0] }},')
        elif kind == "narrow":
            # a narrow rigid face: its force acts along -x through the face's centre
            lines.append("forces = [")
            lines.append(f'  {{ path = "{path}", channel = "load_cell", direction = [-1.0, 0.0], anchor = [{st.face:.6f}, {test["offset"]}] }},')
        else:
            lines.append(f'striker = {{ angle = {test["angle_deg"]}, overlap = {100 * test["overlap"]}, side = "{test["side"]}", speed = "{test["speed_kmh"]} km/h" }}')
            lines.append("forces = [")
            width = wall_cells(st)[0][1] - wall_cells(st)[0][0]
            for j, p in enumerate(cell_centres(st)):
                lines.append(f'  {{ path = "{path}", channel = "cell{j + 1}", direction = [{st.normal[0]:.9f}, {st.normal[1]:.9f}], anchor = [{p[0]:.6f}, {p[1]:.6f}], cell = {width:.6f} }},')
        lines += ["]", "sensors = ["]
        lines.append(f'  {{ path = "{path}", channel = "sill_left", body = [{s["xi"]}, {s["eta"]}] }},')
        lines.append(f'  {{ path = "{path}", channel = "sill_right", body = [{s["xi"]}, {-s["eta"]}] }},')
        if yaw_rate:
            lines.append(f'  {{ path = "{path}", channel = "yaw_rate" }},')
        lines += ["]", ""]
    (out / file).write_text("\n".join(lines))


def start(out, car):
    c, b, cb = car.c, car.c["beam"], car.c["crash_boxes"]
    d = np.array([0.0, 0.01, 0.02, 0.04, 0.07, 0.1, 0.15])
    f = b["contact"] * b["points"] * d ** 1.5
    curve = ", ".join(f"[{x:.6g}, {y:.6g}]" for x, y in zip(d, f))
    text = f"""# The start of the identification: a symmetric guess (not the truth).
name = "yaw-rate series start"
[body]
mass = 1450.0
yaw_inertia = 2900.0
cg_behind_bumper = {c["cg_behind_bumper"]}
wheelbase = {c["wheelbase"]}
cg_behind_front_axle = {c["cg_behind_front_axle"]}
track = {c["track"]}
[left]
masses = [6.0]
dampers = [1.5e3]
springs = [1.5e6]
[right]
masses = [6.0]
dampers = [1.5e3]
springs = [1.5e6]
[bumper]
width = {b["width"]}
side_member_spacing = {cb["spacing"]}
segments = 32
curve = [{curve}]
unloading = {1.5 * b["contact"] * b["points"] * 0.1 ** 0.5:.6g}
[tyres]
front = {{ rolling_resistance = 0.015, mu_lateral = 0.6 }}
rear = {{ rolling_resistance = 0.015, mu_lateral = 0.6 }}
"""
    (out / "start.toml").write_text(text)


def varied(seed):
    """The default car with its masses, yaw inertia, tyres and crash boxes
    each scaled by a factor within +/-15 % drawn from `seed`."""
    draw = np.random.default_rng(seed)
    scale = lambda v: float(v * draw.uniform(0.85, 1.15))
    c = json.loads(json.dumps(CAR))
    c["body_mass"] = scale(c["body_mass"])
    c["yaw_inertia"] = scale(c["yaw_inertia"])
    c["beam"]["mass"] = scale(c["beam"]["mass"])
    for key in ("cornering_stiffness", "mu"):
        c["tyres"][key] = scale(c["tyres"][key])
    for key in ("elastic", "yield", "hardening", "damping"):
        c["crash_boxes"][key] = [scale(v) for v in c["crash_boxes"][key]]
    return c


def main(out, seed=None):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    truth = CAR if seed is None else varied(seed)
    car = Car(truth)
    rng = np.random.default_rng(44 if seed is None else 44 + 1000 * seed)
    strikers = [Striker(t, car) for t in TESTS]
    peaks = {}
    for i, (test, st) in enumerate(zip(TESTS, strikers)):
        rows = simulate(car, st)
        peaks[test["name"]] = max(abs(r["yaw_rate"]) for r in rows)
        write(out, test, rows, rng, i)
    study(out, car, strikers, False, "study-sills.toml")
    start(out, car)
    sheet = {"total_mass": car.total_mass(), "yaw_inertia": truth["yaw_inertia"],
             "mu": truth["tyres"]["mu"], "car": truth, "tests": TESTS, "peak_yaw_rate": peaks}
    if seed is not None:
        sheet["seed"] = seed
    (out / "series.json").write_text(json.dumps(sheet, indent=1))
    study(out, car, strikers, True, "study-doc.toml", documented=True)
    study(out, car, strikers, True, "study.toml")  # last: the marker of a finished series


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) == 3 and args[1] == "--seed" and args[2].isdigit() and int(args[2]) >= 1:
        main(args[0], int(args[2]))
    elif len(args) == 1:
        main(args[0])
    else:
        sys.exit("usage: planar_yaw_rate.py OUT_DIR [--seed N], N >= 1")
