"""Reference for bumpsim's designs: pyDOE3 ff2n and fracfact.

Usage: pydoe3_designs.py ff2n K | fracfact "a b c ab"
Prints the design rows as JSON.
"""
import json
import sys

import pyDOE3

kind, arg = sys.argv[1], sys.argv[2]
design = pyDOE3.ff2n(int(arg)) if kind == "ff2n" else pyDOE3.fracfact(arg)
print(json.dumps(design.tolist()))
