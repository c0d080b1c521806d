#!/usr/bin/env python3
"""A pendulum into a car with nonlinear links, integrated independently of
bumpsim (issue 46): the check of `bumpsim impact --car LINKS.toml
--pendulum M --speed V`.

Usage: scipy_links_pendulum.py CAR.toml MASS_KG SPEED_M_S [STEP_S] [DURATION_S]

Prints JSON (SI): the peak contact force at the samples (STEP, default
1e-4 s), each link's largest compression and plastic set (the front link
first), the striker's and the car's centre of mass's speeds at the end
along the impact, and the energies at the end.

Written here from the car-file format (docs/formats.md) and the link laws
(bumpsim_core::link's module text), not from bumpsim's code:

- a loading curve F_L (linear, progressive k d + k3 d^3 to its limit and
  the tangent beyond, bilinear with hardening, a table, its last slope
  beyond, held when falling) and an unloading rule: elastic (odd in d) or
  a slope k_u from the largest compression d_max, the slope used
  k_e = max(k_u, F_max/d_max, F_max^2/(2 E_L)) past the elastic limit
  (bilinear: F_y/k; linear: never; progressive and table: 0) and the
  initial slope below it; plastic set d_max - F_max/k_e, plastic work
  E_L(d_max) - F_max^2/(2 k_e);
- the striker (a free rigid mass) meets m1 through the front link, which
  only pushes; links between masses carry tension when they unload past
  their set; dampers in parallel;
- d_max is a state of the ODE (it grows with d while d is at it), so the
  history is integrated with the motion by scipy's DOP853 (rtol 1e-10,
  steps of at most 1e-5 s across the kinks), not by a leapfrog.
"""
import json
import math
import sys
import tomllib

import numpy as np
from scipy.integrate import solve_ivp

UNITS = {
    "kg": 1.0, "t": 1e3, "g": 1e-3,
    "Ns/mm": 1e3, "Ns/m": 1.0, "kNs/m": 1e3,
    "N/mm": 1e3, "N/m": 1.0, "kN/mm": 1e6, "kN/m": 1e3,
    "N": 1.0, "kN": 1e3, "MN": 1e6,
    "mm": 1e-3, "m": 1.0, "cm": 1e-2,
}


def si(value):
    """A number (SI) or text with a unit."""
    if isinstance(value, (int, float)):
        return float(value)
    number, unit = value.split()
    return float(number) * UNITS[unit]


class Link:
    def __init__(self, table):
        self.kind = table["curve"]
        unloading = table.get("unloading", "elastic")
        self.ku = None if unloading == "elastic" else si(unloading)
        if self.kind == "linear":
            self.k = si(table["stiffness"])
            self.elastic_limit = math.inf
        elif self.kind == "progressive":
            self.k = si(table["stiffness"])
            self.lim = si(table["limit"])
            flim = si(table["limit_force"])
            self.k3 = (flim - self.k * self.lim) / self.lim ** 3
            self.elastic_limit = 0.0
        elif self.kind == "bilinear":
            self.k = si(table["stiffness"])
            self.fy = si(table["yield_force"])
            self.r = float(table.get("hardening", 0.0))
            self.elastic_limit = self.fy / self.k
        elif self.kind == "table":
            pts = [(si(d), si(f)) for d, f in table["points"]]
            if pts[0][0] != 0.0:
                pts.insert(0, (0.0, 0.0))
            self.pts = pts
            self.k = pts[1][1] / pts[1][0]
            self.elastic_limit = 0.0
        else:
            raise ValueError(self.kind)

    def load(self, d):
        """F_L(d), d >= 0."""
        if self.kind == "linear":
            return self.k * d
        if self.kind == "progressive":
            if d <= self.lim:
                return self.k * d + self.k3 * d ** 3
            f = self.k * self.lim + self.k3 * self.lim ** 3
            return f + (self.k + 3 * self.k3 * self.lim ** 2) * (d - self.lim)
        if self.kind == "bilinear":
            dy = self.fy / self.k
            return self.k * d if d <= dy else self.fy + self.r * self.k * (d - dy)
        pts = self.pts
        for (d0, f0), (d1, f1) in zip(pts, pts[1:]):
            if d <= d1:
                return f0 + (f1 - f0) * (d - d0) / (d1 - d0)
        (d0, f0), (d1, f1) = pts[-2], pts[-1]
        slope = (f1 - f0) / (d1 - d0)
        return f1 + max(slope, 0.0) * (d - d1)

    def energy(self, d):
        """E_L(d) = integral of F_L from 0 to d, in closed form."""
        if d <= 0:
            return 0.0
        if self.kind == "linear":
            return 0.5 * self.k * d * d
        if self.kind == "progressive":
            e = lambda x: 0.5 * self.k * x * x + 0.25 * self.k3 * x ** 4
            if d <= self.lim:
                return e(d)
            return e(self.lim) + 0.5 * (self.load(self.lim) + self.load(d)) * (d - self.lim)
        if self.kind == "bilinear":
            dy = self.fy / self.k
            if d <= dy:
                return 0.5 * self.k * d * d
            return 0.5 * self.fy * dy + 0.5 * (self.fy + self.load(d)) * (d - dy)
        # a table: trapezoids are exact on its linear pieces
        total, pts = 0.0, self.pts
        for (d0, f0), (d1, _) in zip(pts, pts[1:]):
            if d <= d0:
                break
            top = min(d, d1)
            total += 0.5 * (f0 + self.load(top)) * (top - d0)
        if d > pts[-1][0]:
            total += 0.5 * (pts[-1][1] + self.load(d)) * (d - pts[-1][0])
        return total

    def unloading(self, dmax):
        """(F_max, k_e) of the unloading line from dmax."""
        top = self.load(dmax) if dmax > 0 else 0.0
        if dmax <= 0 or dmax <= self.elastic_limit:
            return top, self.k
        e = self.energy(dmax)
        balance = top * top / (2 * e) if e > 0 else self.k
        return top, max(self.ku, top / dmax, balance)

    def force(self, d, dmax):
        if self.ku is None:
            return math.copysign(self.load(abs(d)), d)
        if d >= dmax:
            return self.load(d)
        top, ke = self.unloading(dmax)
        return top - ke * (dmax - d)


def main():
    car = tomllib.load(open(sys.argv[1], "rb"))
    mass, speed = float(sys.argv[2]), float(sys.argv[3])
    step = float(sys.argv[4]) if len(sys.argv) > 4 else 1e-4
    duration = float(sys.argv[5]) if len(sys.argv) > 5 else 0.25
    m = np.array([si(x) for x in car["masses"]])
    c = [si(x) for x in car.get("dampers", [])]
    links = [Link(t) for t in car.get("links", [])]
    front = Link(car["front"])
    n = len(m)
    # history states: the front link's d_max, then each link's
    chain = [front] + links

    def crushes(x, xs):
        # the striker moves forwards (+x) into m1: front d = x_s - x_1,
        # link j d = x_j - x_(j+1)
        return [xs - x[0]] + [x[j] - x[j + 1] for j in range(n - 1)]

    def rates(v, vs):
        return [vs - v[0]] + [v[j] - v[j + 1] for j in range(n - 1)]

    def forces(x, v, xs, vs, dmax):
        d = crushes(x, xs)
        f = [max(front.force(d[0], max(dmax[0], d[0])), 0.0)]
        for j, link in enumerate(links):
            f.append(link.force(d[j + 1], max(dmax[j + 1], d[j + 1])))
        return d, f

    def rhs(t, y):
        x, v = y[:n], y[n:2 * n]
        xs, vs = y[2 * n], y[2 * n + 1]
        dmax = y[2 * n + 2:]
        d, f = forces(x, v, xs, vs, dmax)
        r = rates(v, vs)
        a = np.zeros(n)
        a[0] += f[0]
        for j in range(n - 1):
            total = f[j + 1] + c[j] * r[j + 1]
            a[j] -= total
            a[j + 1] += total
        a /= m
        grow = [r[i] if (d[i] >= dmax[i] and r[i] > 0) else 0.0 for i in range(len(chain))]
        return np.concatenate([v, a, [vs, -f[0] / mass], grow])

    y0 = np.concatenate([np.zeros(n), np.zeros(n), [0.0, speed], np.zeros(len(chain))])
    times = np.arange(0.0, duration + 0.5 * step, step)
    sol = solve_ivp(rhs, (0.0, times[-1]), y0, method="DOP853", t_eval=times,
                    rtol=1e-10, atol=1e-12, max_step=1e-5)
    y = sol.y
    contact = []
    for k in range(len(times)):
        x, v = y[:n, k], y[n:2 * n, k]
        _, f = forces(x, v, y[2 * n, k], y[2 * n + 1, k], y[2 * n + 2:, k])
        contact.append(f[0])
    dmax = y[2 * n + 2:, -1]
    sets, reached = [], []
    for i, link in enumerate(chain):
        samples = [crushes(y[:n, k], y[2 * n, k])[i] for k in range(len(times))]
        reached.append(max(max(samples), 0.0))
        if link.ku is None:
            sets.append(0.0)
        else:
            top, ke = link.unloading(dmax[i])
            sets.append(dmax[i] - top / ke)
    plastic = 0.0
    for i, link in enumerate(chain):
        if link.ku is not None and dmax[i] > 0:
            top, ke = link.unloading(dmax[i])
            plastic += max(link.energy(dmax[i]) - top * top / (2 * ke), 0.0)
    v_end = y[n:2 * n, -1]
    out = {
        "peak_force": max(contact),
        "max_compression": reached,
        "plastic_set": sets,
        "striker_final_speed": y[2 * n + 1, -1],
        "car_final_speed": float(m @ v_end / m.sum()),
        "plastic": plastic,
        "kinetic": 0.5 * float(m @ v_end ** 2) + 0.5 * mass * y[2 * n + 1, -1] ** 2,
        "initial": 0.5 * mass * speed ** 2,
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
