"""Reference for bumpsim's filters: scipy's Butterworth design and sosfiltfilt.

Usage: scipy_filter.py ORDER CUTOFF_HZ FS_HZ PADLEN INPUT_FILE
INPUT_FILE holds one sample per line. Prints the zero-phase filtered samples,
one per line, with 17 significant digits (odd padding, as bumpsim).
"""
import sys

import numpy as np
from scipy import signal

order, cutoff, fs, padlen = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
x = np.loadtxt(sys.argv[5])
sos = signal.butter(order, cutoff, fs=fs, output="sos")
y = signal.sosfiltfilt(sos, x, padtype="odd", padlen=padlen)
sys.stdout.write("\n".join(f"{v:.17e}" for v in y) + "\n")
