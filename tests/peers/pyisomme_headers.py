"""The complete ISO-MME headers of a test as pyisomme reads them, and its copy.

    python3 pyisomme_headers.py read PATH
        Reads an ISO-MME test (folder, .mme or .zip) with pyisomme; prints the
        test header items and, per channel, its code, filter class, unit, the
        items of its channel header (key and value as pyisomme writes it back,
        in file order), its values, and whether pyisomme finds every part of
        the code in the standard's table (channel_codes.xml).

    python3 pyisomme_headers.py copy PATH OUT
        Reads PATH with pyisomme and writes it unchanged with pyisomme's writer
        as the folder OUT (test number taken from PATH); prints 'read' of OUT.

Output is JSON on stdout. Called by the bumpsim CLI tests (issue 33: the
complete channel header round trip, data status, test objects).
"""

import json
import logging
import sys
from pathlib import Path

import numpy as np

logging.disable(logging.CRITICAL)

from pyisomme import Isomme  # noqa: E402
from pyisomme.info import format_value  # noqa: E402


def items(info):
    return [[key, format_value(value)] for key, value in info.items()]


def describe(channel):
    return {
        "code": str(channel.code),
        "valid": channel.code.is_valid(),
        "filter_class": channel.code.filter_class,
        "unit": channel.unit.to_isomme(),
        "header": items(channel.info),
        "values": channel.data.iloc[:, 0].to_numpy(dtype=float).tolist(),
        "time_of_first_sample": float(np.asarray(channel.data.index, dtype=float)[0]),
    }


def read(path):
    test = Isomme().read(path)
    return {
        "test": items(test.test_info),
        "channels": [describe(c) for c in test.channels],
    }


def copy(path, out):
    test = Isomme().read(path)
    out = Path(out)
    test.test_number = out.name
    test.write(out)
    return read(out)


def main():
    if len(sys.argv) == 3 and sys.argv[1] == "read":
        result = read(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "copy":
        result = copy(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
    json.dump(result, sys.stdout, default=str)


if __name__ == "__main__":
    main()
