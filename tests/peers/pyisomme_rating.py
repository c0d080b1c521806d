"""Reference for bumpsim's ISO/TS 18571 rating: pyisomme's Correlation_ISO18571.

Usage: pyisomme_rating.py STEP INPUT_FILE [STEP INPUT_FILE ...]
Each INPUT_FILE holds one sample pair per line, "reference candidate", sampled
every STEP seconds from time 0. Both become pyisomme channels (acceleration
codes, m/s^2) and pyisomme rates the candidate against the reference: it takes
them at 10 kHz (interpolating when STEP is not 1e-4 s) and calls
objective_rating_metrics' ISO18571. Prints, one line per pair, the unrounded
overall, corridor, phase, magnitude and slope ratings with 17 significant
digits. (Pairs are batched because the warping's numba code compiles once per
process, about 10 s.)
"""
import logging
import sys

import numpy as np
import pandas as pd

logging.disable(logging.CRITICAL)

from pyisomme import Correlation_ISO18571  # noqa: E402
from pyisomme.channel import Channel  # noqa: E402



def channel(values, time):
    data = pd.DataFrame({"value": values}, index=pd.Index(time, name="time"))
    return Channel("10VEHC0000CG00ACXP", data, unit="m/s^2")


def ratings(step, path):
    pairs = np.loadtxt(path, ndmin=2)
    time = np.arange(pairs.shape[0]) * step
    rating = Correlation_ISO18571(channel(pairs[:, 0], time), channel(pairs[:, 1], time))
    return [
        rating.overall_rating(ndigits=-1),
        rating.corridor_rating(ndigits=-1),
        rating.phase_rating(ndigits=-1),
        rating.magnitude_rating(ndigits=-1),
        rating.slope_rating(ndigits=-1),
    ]


arguments = sys.argv[1:]
for step, path in zip(arguments[0::2], arguments[1::2]):
    values = ratings(float(step), path)
    sys.stdout.write(" ".join(f"{float(v):.17e}" for v in values) + "\n")
