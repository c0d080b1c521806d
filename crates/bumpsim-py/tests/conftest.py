"""Shared fixtures: the repository, the `bumpsim` CLI the results are compared
with (BUMPSIM_BIN, set by scripts/test; else target/release/bumpsim), and a
runner for it."""

import csv
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[3]
# the test data beside the checkout (as the Rust tests read it); BUMPSIM_SHARED overrides
SHARED = Path(os.environ.get("BUMPSIM_SHARED", ROOT.parent / "shared"))


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli() -> Path:
    path = Path(os.environ.get("BUMPSIM_BIN", ROOT / "target" / "release" / "bumpsim"))
    if not path.is_file():
        pytest.fail(
            f"the bumpsim CLI is not at {path}: build it with "
            "`cargo build --release -p bumpsim-cli` or set BUMPSIM_BIN"
        )
    return path


@pytest.fixture
def run(cli):
    """Runs the CLI with arguments; returns its stdout, fails with its stderr."""

    def run(*args) -> str:
        done = subprocess.run(
            [str(cli), *map(str, args)], capture_output=True, text=True
        )
        assert done.returncode == 0, f"bumpsim {' '.join(map(str, args))}: {done.stderr}"
        return done.stdout

    return run


def read_csv(path: Path) -> dict:
    """A CSV the CLI wrote: header `name [unit]` → numpy column (values as written)."""
    with open(path, newline="") as f:
        rows = [row for row in csv.reader(f) if row and not row[0].startswith("#")]
    header, data = rows[0], np.array(rows[1:], dtype=float)
    return {name: data[:, k] for k, name in enumerate(header)}


def nhtsa_10146() -> Path:
    """The NHTSA test 10146 EV5 file, or a skip naming where it is expected."""
    folder = SHARED / "data" / "nhtsa-10146"
    files = sorted(folder.glob("*.EV5")) + sorted(folder.glob("*.ev5"))
    if not files:
        pytest.skip(f"NHTSA 10146 data absent (expected an .EV5 file in {folder})")
    return files[0]
