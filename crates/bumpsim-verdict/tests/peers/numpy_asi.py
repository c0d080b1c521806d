"""An independent EN 1317-1:1998 ASI for bumpsim-verdict's tests.

Usage: numpy_asi.py INPUT_FILE [INPUT_FILE ...]
Each INPUT_FILE holds "time a_x a_y" per line (s, m/s^2). The 50 ms moving
averages are differences of the cumulative trapezoidal integral (scipy),
the window's end interpolated linearly; ASI = max sqrt((ax/12g)^2 +
(ay/9g)^2) over the windows from first contact (t >= 0) that fit in the
record, g = 9.81 m/s^2.
Prints one ASI per file with 17 significant digits.
"""
import sys

import numpy as np
from scipy.integrate import cumulative_trapezoid

G, WINDOW = 9.81, 0.05


def asi(path):
    t, ax, ay = np.loadtxt(path, ndmin=2).T
    starts = t[(t >= 0.0) & (t + WINDOW <= t[-1] + 1e-12)]
    means = []
    for a in (ax, ay):
        s = cumulative_trapezoid(a, t, initial=0.0)
        means.append((np.interp(starts + WINDOW, t, s) - np.interp(starts, t, s)) / WINDOW)
    return float(np.max(np.hypot(means[0] / (12 * G), means[1] / (9 * G))))


for path in sys.argv[1:]:
    print(f"{asi(path):.17e}")
