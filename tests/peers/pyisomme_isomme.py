"""Independent check of bumpsim's ISO-MME files with pyisomme (ISO/TS 13499).

    python3 pyisomme_isomme.py read PATH
        Reads an ISO-MME test (folder, .mme or .zip) with pyisomme and prints,
        per channel, what pyisomme understood: code, unit as pyisomme spells it,
        the factor from that unit to the SI unit of the code's physical
        dimension (1.0 when unit and code agree), filter class, channel
        frequency class, first-sample time, sampling interval, count, values.

    python3 pyisomme_isomme.py rewrite PATH OUT
        Reads PATH with pyisomme, adds a moment channel (unit N·m, which
        pyisomme writes as 'N m'), and writes the test with pyisomme's writer as
        a folder OUT/PY and as OUT/PY.zip. Prints, for each written form, the
        channels as pyisomme reads its own output back (same fields as 'read').

Output is JSON on stdout. Called by the bumpsim CLI tests.
"""

import json
import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

logging.disable(logging.CRITICAL)

from pyisomme import Isomme  # noqa: E402
from pyisomme.channel import Channel  # noqa: E402


def describe(channel):
    code = channel.code
    default = code.get_default_unit()
    factor = None
    if default is not None and channel.unit.is_equivalent(default):
        factor = float(channel.unit.to(default))
    times = np.asarray(channel.data.index, dtype=float)
    values = channel.data.iloc[:, 0].to_numpy(dtype=float)
    cfc = channel.info.get("Channel frequency class")
    return {
        "code": str(code),
        "unit": channel.unit.to_isomme(),
        "unit_to_default": factor,
        "filter_class": code.filter_class,
        "channel_frequency_class": cfc if isinstance(cfc, (int, float)) else None,
        "time_of_first_sample": float(times[0]),
        "sampling_interval": float((times[-1] - times[0]) / (len(times) - 1)),
        "samples": len(values),
        "times": times.tolist(),
        "values": values.tolist(),
    }


def read(path):
    test = Isomme().read(path)
    return {
        "velocity_test_object_1": test.get_test_info("Velocity test object 1"),
        "mass_test_object_1": test.get_test_info("Mass test object 1"),
        "channels": [describe(c) for c in test.channels],
    }


def rewrite(path, out):
    test = Isomme().read(path)
    first = test.channels[0]
    moment = pd.DataFrame(
        first.data.iloc[:, 0].to_numpy(dtype=float) * 0.25, index=first.data.index
    )
    test.channels.append(
        Channel(
            "10NECKUP0000MOXP",
            moment,
            unit="Nm",
            info=[
                ("Name of the channel", "Neck moment (pyisomme)"),
                ("Reference channel", "implicit"),
            ],
        )
    )
    out = Path(out)
    folder, archive = out / "PY", out / "PY.zip"
    test.test_number = "PY"
    test.write(folder)
    test.write(archive)
    return {"folder": read(folder), "zip": read(archive)}


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "read":
        result = read(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "rewrite":
        result = rewrite(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
    json.dump(result, sys.stdout, default=str)


if __name__ == "__main__":
    main()
