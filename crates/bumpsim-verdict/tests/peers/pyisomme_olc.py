"""Reference for bumpsim-verdict's OLC: pyisomme's calculate_olc.

Usage: pyisomme_olc.py [--acceleration=V0,SECONDS] INPUT_FILE [...]
Each INPUT_FILE holds "time velocity" per line (s, m/s, the velocity along
the direction the vehicle decelerates in); after --acceleration=V0,SECONDS
it holds "time acceleration" (s, m/s^2, same direction), which pyisomme
integrates itself (Channel.integrate, the value V0 m/s at t = 0); the
velocity is then continued SECONDS at its last value (the car rolling on
after the record, as bumpsim's verdict continues it). Prints one OLC per
file, m/s^2, with 17 significant digits.

calculate_olc returns OLC / 9.81 in a channel whose unit is g0 (9.80665
m/s^2): converting that unit would be 3.4e-4 high, so its value is taken
back with the 9.81 it was divided by (pyisomme 1.1.0, calculate/olc.py).
"""
import logging
import sys

import numpy as np
import pandas as pd

logging.disable(logging.CRITICAL)

from pyisomme.calculate import calculate_olc  # noqa: E402
from pyisomme.channel import Channel  # noqa: E402


def frame(time, values):
    return pd.DataFrame({"value": values}, index=pd.Index(time, name="time"))


def continued(time, values, seconds):
    """The series continued `seconds` at its last value, same step."""
    step = (time[-1] - time[0]) / (len(time) - 1)
    extra = int(np.ceil(seconds / step))
    more = time[-1] + step * np.arange(1, extra + 1)
    return np.concatenate([time, more]), np.concatenate([values, np.full(extra, values[-1])])


def olc(path, acceleration=None):
    rows = np.loadtxt(path, ndmin=2)
    data = frame(rows[:, 0], rows[:, 1])
    if acceleration is None:
        velocity = Channel("10VEHCCG0000VEXP", data, unit="m/s")
    else:
        v0, seconds = acceleration
        integrated = Channel("10VEHCCG0000ACXP", data, unit="m/s^2").integrate(x_0=v0)
        time, v = continued(rows[:, 0], integrated.data.iloc[:, 0].to_numpy(), seconds)
        velocity = Channel("10VEHCCG0000VEXP", frame(time, v), unit="m/s")
    c_olc = calculate_olc(velocity)[0]
    return float(c_olc.data.iloc[0, 0]) * 9.81


acceleration = None
for arg in sys.argv[1:]:
    if arg.startswith("--acceleration="):
        acceleration = [float(x) for x in arg.split("=", 1)[1].split(",")]
        continue
    print(f"{olc(arg, acceleration):.17e}")
    acceleration = None
