"""Reference for bumpsim-verdict's OLC: pyisomme's calculate_olc.

Usage: pyisomme_olc.py INPUT_FILE [INPUT_FILE ...]
Each INPUT_FILE holds "time velocity" per line (s, m/s, the velocity along
the direction the vehicle decelerates in). Prints one OLC per file, m/s^2,
with 17 significant digits.
"""
import logging
import sys

import numpy as np
import pandas as pd

logging.disable(logging.CRITICAL)

from pyisomme.calculate import calculate_olc  # noqa: E402
from pyisomme.channel import Channel  # noqa: E402


def olc(path):
    rows = np.loadtxt(path, ndmin=2)
    data = pd.DataFrame({"value": rows[:, 1]}, index=pd.Index(rows[:, 0], name="time"))
    c_olc = calculate_olc(Channel("10VEHCCG0000VEXP", data, unit="m/s"))[0]
    return float(c_olc.convert_unit("m/s^2").data.iloc[0, 0])


for path in sys.argv[1:]:
    print(f"{olc(path):.17e}")
