"""Impact and planar predictions as distributions and their Sobol indices
(issue 39, item 4): `impact(..., uncertainty=...)` and
`planar_impact(..., uncertainty=...)` give the same `prediction` and
`sensitivity` objects as `bumpsim impact|planar --uncertainty --json`."""

import json
import pickle
import threading

import numpy as np
import pytest

import bumpsim
from test_impact_doe_export import numbers_equal

SAMPLES, BASE = 200, 64
# a planar impact takes ~10 ms: fewer draws and the least base samples there
PLANAR_SAMPLES, PLANAR_BASE = 40, 16


@pytest.fixture
def chain(root, tmp_path):
    """A 1-D car, its bumper and a TOML of spreads and ranges."""
    spreads = tmp_path / "spreads.toml"
    spreads.write_text(
        '[uncertainty]\n"bumper.force" = 0.08\n"masses[0]" = 0.02\n'
        '[ranges]\n"springs[0]" = [0.8, 1.2]\n'
    )
    car = root / "examples" / "identify" / "car-truth.toml"
    return car, root / "examples" / "impact" / "bumper-a.toml", spreads


def test_impact_prediction_and_sobol_equal_the_cli(run, tmp_path, chain):
    car, bumper, spreads = chain
    out = tmp_path / "impact.json"
    run("impact", "--car", car, "--bumper", bumper, "--case", "thesis-600",
        "--uncertainty", spreads, "--samples", SAMPLES, "--seed", 7, "--level", 0.8,
        "--sobol", "--sobol-base", BASE, "--json", out)
    theirs = json.loads(out.read_text())
    result = bumpsim.impact(bumpsim.Car.from_file(car), bumper, case="thesis-600",
                            uncertainty=spreads, samples=SAMPLES, seed=7, level=0.8,
                            sobol=True, sobol_base=BASE)
    numbers_equal(result.prediction, theirs["prediction"])
    numbers_equal(result.sensitivity, theirs["sensitivity"])
    numbers_equal(json.loads(result.to_json()), theirs)
    # the bands as arrays: the JSON's, ordered low <= median <= high
    force = result.bands["force"]
    band = next(b for b in theirs["prediction"]["bands"] if b["name"] == "force")
    np.testing.assert_array_equal(force["time"], band["time"])
    np.testing.assert_array_equal(force["high"], band["band"]["high"])
    assert np.all(force["low"] <= force["median"]) and np.all(force["median"] <= force["high"])
    # the peak force's interval holds its nominal value; pickling keeps the prediction
    peak = result.prediction["outputs"][0]
    assert peak["spread"]["low"] <= peak["nominal"] <= peak["spread"]["high"]
    assert pickle.loads(pickle.dumps(result)) == result
    # the spreads as a table: the JSON's numbers
    pytest.importorskip("pandas")
    table = result.prediction_to_pandas()
    assert list(table.index) == [o["name"] for o in theirs["prediction"]["outputs"]]
    assert table.loc["peak force", "high"] == peak["spread"]["high"]
    assert table.loc["peak force", "unit"] == "N"
    assert table.attrs["sampling"]["samples"] == SAMPLES


def test_impact_without_uncertainty_is_unchanged(root, chain):
    car, bumper, _ = chain
    result = bumpsim.impact(bumpsim.Car.from_file(car), bumper, case="thesis-600")
    assert result.prediction is None and result.sensitivity is None and result.bands is None
    assert result.prediction_to_pandas() is None
    assert "prediction" not in json.loads(result.to_json())


def test_planar_prediction_and_sobol_equal_the_cli(run, tmp_path, root):
    car = root / "examples" / "planar" / "saloon.toml"
    spreads = tmp_path / "planar.toml"
    spreads.write_text('[uncertainty]\n"body.mass" = 0.05\n"bumper.force" = 0.1\n')
    out = tmp_path / "planar.json"
    run("planar", "--car", car, "--angle", 30, "--overlap", 40, "--speed", 2.5,
        "--uncertainty", spreads, "--samples", PLANAR_SAMPLES, "--seed", 3,
        "--sobol", "--sobol-base", PLANAR_BASE, "--json", out)
    theirs = json.loads(out.read_text())
    result = bumpsim.planar_impact(car, angle=30.0, overlap=40.0, speed=2.5,
                                   uncertainty=spreads, samples=PLANAR_SAMPLES, seed=3,
                                   sobol=True, sobol_base=PLANAR_BASE)
    numbers_equal(result.prediction, theirs["prediction"])
    numbers_equal(result.sensitivity, theirs["sensitivity"])
    # to_json carries them as --json does (the rest is test_impact_doe_export's)
    ours = json.loads(result.to_json())
    assert set(ours) == set(theirs)
    assert ours["prediction"] == result.prediction
    assert ours["sensitivity"] == result.sensitivity
    assert pickle.loads(pickle.dumps(result)) == result


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"samples": 5}, "samples"),
        ({"samples": -3}, "samples"),
        ({"level": 1.5}, "level"),
        ({"sobol": True, "sobol_base": 8}, "sobol_base"),
    ],
)
def test_bad_options_name_the_argument(chain, kwargs, name):
    car, bumper, spreads = chain
    with pytest.raises(bumpsim.InputError, match=f"^{name}"):
        bumpsim.impact(car, bumper, case="thesis-600", uncertainty=spreads, **kwargs)


def test_unknown_parameter_and_sobol_alone_are_refused(chain, tmp_path, root):
    car, bumper, spreads = chain
    wrong = tmp_path / "wrong.toml"
    wrong.write_text('[uncertainty]\n"springs[9]" = 0.1\n')
    with pytest.raises(bumpsim.InputError, match=r"^uncertainty: .*springs\[9\]"):
        bumpsim.impact(car, bumper, case="thesis-600", uncertainty=wrong)
    with pytest.raises(bumpsim.InputError, match="^sobol: needs uncertainty"):
        bumpsim.impact(car, bumper, case="thesis-600", sobol=True)
    # a value given is used or refused (it was ignored without uncertainty)
    for extra in ({"samples": 200}, {"seed": 3}, {"sobol_base": 64}):
        name = next(iter(extra))
        with pytest.raises(bumpsim.InputError, match=f"^{name}: needs uncertainty"):
            bumpsim.impact(car, bumper, case="thesis-600", **extra)
    with pytest.raises(bumpsim.InputError, match="^sobol_base: needs sobol=True"):
        bumpsim.impact(car, bumper, case="thesis-600", uncertainty=spreads, sobol_base=64)
    saloon = root / "examples" / "planar" / "saloon.toml"
    with pytest.raises(bumpsim.InputError, match=r"^uncertainty: .*springs\[9\]"):
        bumpsim.planar_impact(saloon, angle=30.0, speed=2.5, uncertainty=wrong)


def test_the_prediction_releases_the_gil(chain):
    car, bumper, spreads = chain
    done = threading.Event()

    def work():
        bumpsim.impact(car, bumper, case="thesis-600", uncertainty=spreads, samples=2000,
                       sobol=True, sobol_base=128)
        done.set()

    worker = threading.Thread(target=work)
    ticks = 0
    worker.start()
    while not done.is_set():
        ticks += 1  # runs only while the worker does not hold the GIL
    worker.join()
    # ~0.3 s of draws and Sobol runs: with the GIL held this loop would run a handful of times
    assert ticks > 10_000, f"the main thread ran {ticks} times during the prediction"
