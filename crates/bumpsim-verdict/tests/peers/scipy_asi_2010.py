"""An independent EN 1317-1:2010 ASI for bumpsim-verdict's tests.

Usage: scipy_asi_2010.py INPUT_FILE [INPUT_FILE ...]
Each INPUT_FILE holds "time a_x a_y" per line (s, m/s^2, constant sample
interval). Each acceleration is padded with 0.5 s of zeros on both sides,
filtered by scipy.signal.butter(2, 13 Hz) run forward and backward
(scipy.signal.filtfilt with its defaults: the "4-pole phaseless"
Butterworth), and ASI = max sqrt((ax/12g)^2 + (ay/9g)^2) over every
sample, g = 9.81 m/s^2. Prints one ASI per file with 17 significant digits.
"""
import sys

import numpy as np
from scipy.signal import butter, filtfilt

G, CUTOFF, PADDING = 9.81, 13.0, 0.5


def asi(path):
    t, ax, ay = np.loadtxt(path, ndmin=2).T
    step = (t[-1] - t[0]) / (len(t) - 1)
    b, a = butter(2, CUTOFF, fs=1.0 / step)
    pad = int(round(PADDING / step))
    fx, fy = (filtfilt(b, a, np.pad(x, pad)) for x in (ax, ay))
    return float(np.max(np.hypot(fx / (12 * G), fy / (9 * G))))


for path in sys.argv[1:]:
    print(f"{asi(path):.17e}")
