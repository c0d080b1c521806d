#!/usr/bin/env python3
"""Writes pendulum-force.csv: a synthetic pendulum load-cell force (standard library only).

A half-sine pulse of 40 kN lasting 80 ms, preceded by 10 ms of pre-trigger
zeros and followed by 70 ms of zeros, sampled at 10 kHz. Time in ms and force
in kN, to show the unit conversion of the CSV reader. The impulse,
2 * 40 kN * 80 ms / pi = 2.04 kN*s, is about what a 1450 kg pendulum at
6 km/h (2.42 kN*s of momentum) transfers to a car in the thesis's tests.
"""
import math
import pathlib

STEP_MS, PEAK_KN, PULSE_MS = 0.1, 40.0, 80.0
rows = ["# synthetic pendulum force, written by make_force.py (see README.md)", "time [ms],force [kN]"]
for k in range(-100, 1501):
    t = k * STEP_MS
    f = PEAK_KN * math.sin(math.pi * t / PULSE_MS) if 0.0 <= t <= PULSE_MS else 0.0
    rows.append(f"{t:.1f},{f:.6f}")
pathlib.Path(__file__).with_name("pendulum-force.csv").write_text("\n".join(rows) + "\n")
