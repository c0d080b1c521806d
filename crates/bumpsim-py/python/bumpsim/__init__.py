"""bumpsim: low-speed bumper impact toolkit (Python bindings of the Rust crates).

Numpy arrays in and out, SI units, errors as :class:`bumpsim.Error`
subclasses carrying the library's messages. Every number comes from the Rust
library; this package only converts. See docs/python.md for a tour and
``__init__.pyi`` for the typed API.
"""

from ._bumpsim import *  # noqa: F401,F403
from ._bumpsim import __version__  # noqa: F401
from . import _bumpsim as _native

__all__ = [name for name in dir(_native) if not name.startswith("_")]
