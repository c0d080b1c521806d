"""Issue 36 item 5: the verdict and the bumper target region as data. The
Python result equals `bumpsim verdict --json` on the worked example
(examples/verdict), its rows (test x criterion) carry the CLI's values,
limits, margins and outcomes, the target region contains the passing bumper
and excludes the failing one, and bad inputs raise on Python's bases."""

import json
import math
import pickle

import pandas as pd
import pytest

import bumpsim

# the worked example's failing test (the RCAR corner) and its passing
# full-width test; the CLI's target search on them takes about 5 s (debug
# build), the wheel's under a second
PROTOCOL = "rcar-bumper"


@pytest.fixture(scope="module")
def car(root):
    return root / "examples" / "verdict" / "car.toml"


@pytest.fixture(scope="module")
def verdict(car):
    return bumpsim.verdict(car, protocol=PROTOCOL, target=True)


@pytest.fixture(scope="module")
def cli_json(car, cli, tmp_path_factory):
    import subprocess

    out = tmp_path_factory.mktemp("verdict") / "verdict.json"
    done = subprocess.run(
        [str(cli), "verdict", "--car", str(car), "--protocol", PROTOCOL, "--target", "--json", str(out)],
        capture_output=True, text=True,
    )
    assert done.returncode == 0, done.stderr
    return json.loads(out.read_text())


def without_time(document):
    """The document without the search's wall time (it differs between runs)."""
    document = json.loads(json.dumps(document))
    if document.get("target"):
        document["target"].pop("seconds")
    return document


def test_the_json_is_the_clis(verdict, cli_json):
    assert without_time(json.loads(verdict.to_json())) == without_time(cli_json)


def test_rows_are_the_clis_criteria(verdict, cli_json):
    frame = verdict.to_pandas()
    assert list(frame.index.names) == ["test", "criterion"]
    expected = []
    for test in cli_json["verdict"]["tests"]:
        name = test["test"]["name"]
        if test["skipped"]:
            expected.append((name, "not assessed", None))
        for c in test["criteria"]:
            expected.append((name, c["name"], c))
    assert len(frame) == len(expected)
    for (test, criterion, c), (index, row) in zip(expected, frame.iterrows()):
        assert index == (test, criterion)
        if c is None:
            assert row["outcome"] == "not assessed" and pd.isna(row["pass"])
            assert math.isnan(row["value"]) and "rear" in row["detail"]
            continue
        assert (row["value"], row["limit"], row["margin"], row["ratio [1]"]) == (
            c["value"], c["limit"], c["margin"], c["ratio"]
        )
        assert row["unit"] == {"length": "m", "force": "N", "acceleration": "m/s^2", "ratio": "1"}[c["quantity"]]
        assert row["outcome"] == c["outcome"] and row["upper"] == c["upper"]
        judged = {"pass": True, "fail": False, "info": None}[c["outcome"]]
        assert row["pass"] == judged if judged is not None else pd.isna(row["pass"])
        assert row["detail"] == c["detail"]
    assert frame.attrs["passed"] is False and frame.attrs["car"] == verdict.car


def test_the_worked_example_fails_one_criterion_and_names_it(verdict):
    assert not verdict.passed
    assert verdict.failures == [("rcar-bumper-corner-front", "bumper stroke")]
    frame = verdict.to_pandas()
    failing = frame[frame["pass"] == False]  # noqa: E712 (None rows are not failures)
    assert list(failing.index) == [("rcar-bumper-corner-front", "bumper stroke")]
    assert failing["margin"].iloc[0] < 0 and failing["unit"].iloc[0] == "m"
    tests = verdict.tests_to_pandas()
    assert tests.loc["rcar-bumper-corner-front", "passed"] is False
    assert pd.isna(tests.loc["rcar-bumper-rear", "passed"])
    assert tests.loc["rcar-bumper-front", "delta_v [m/s]"] > 0
    assert "FAIL" in verdict.to_text() and "bumper target" in verdict.to_text()


def test_the_target_region_contains_the_passing_bumper_and_not_the_failing_one(verdict, cli_json):
    target = verdict.target
    assert target is not None and target.origin == (3e6, 120e3)
    assert target.contains(3e6, 200e3) and not target.contains(3e6, 120e3)
    rows = target.to_pandas()
    assert rows.index.name == "stiffness [N/m]"
    cli_rows = cli_json["target"]["rows"]
    assert list(rows.index) == [r["stiffness"] for r in cli_rows]
    for (_, row), r in zip(rows.iterrows(), cli_rows):
        if r["interval"] is None:   # nothing passes at this stiffness: the failing criterion
            assert math.isnan(row["force low [N]"]) and row["failing"] == r["failing"]
            continue
        low, high = r["interval"]
        assert row["force low [N]"] == low["force"] and row["binding low"] == low["binding"]
        assert row["force high [N]"] == high["force"] and row["binding high"] == high["binding"]
        assert row["stroke [m]"] == r["stroke"]
    # the binding criterion is named at a boundary inside the search range
    assert any(isinstance(b, str) and "bumper stroke" in b for b in rows["binding low"])
    corridor = target.corridor_to_pandas()
    assert corridor.index.name == "deflection [m]"
    assert list(corridor.columns) == ["lower [N]", "upper [N]"]
    assert list(corridor["upper [N]"]) == cli_json["target"]["corridor"]["upper"]
    assert json.loads(target.to_json())["rows"] == cli_rows


def test_a_bumper_replaces_the_cars(car, tmp_path):
    stronger = tmp_path / "bumper.toml"
    stronger.write_text("ramp = 3e6\nplateau = 200e3\nunloading = 2e7\n")
    v = bumpsim.verdict(car, protocol=["rcar-bumper"], bumper=stronger)
    assert v.passed and v.failures == [] and v.target is None
    same = bumpsim.verdict(str(car), protocol="rcar-bumper", bumper=bumpsim.Bumper.from_file(stronger))
    assert same == v


def test_a_planar_car_and_a_list_of_ends_are_cars(car):
    by_path = bumpsim.verdict(car, protocol="part581-barrier-front")
    by_object = bumpsim.verdict([bumpsim.PlanarCar.from_file(car)], protocol="part581-barrier-front")
    assert by_object == by_path and by_path.passed


def test_pickles_compares_and_prints(verdict):
    for x in (verdict, verdict.target):
        copy = pickle.loads(pickle.dumps(x))
        assert copy == x and type(copy) is type(x)
        assert copy.to_json() == x.to_json()
    assert repr(verdict).startswith("Verdict(") and "bumper stroke in rcar-bumper-corner-front" in repr(verdict)
    assert repr(verdict.target).startswith("BumperTarget(")


def test_bad_inputs_raise_on_pythons_bases(car, root, tmp_path):
    with pytest.raises(ValueError, match="fmvss-999"):
        bumpsim.verdict(car, protocol="fmvss-999")
    with pytest.raises(ValueError, match="margin"):
        bumpsim.verdict(car, protocol="rcar-bumper", margin=1.5)
    with pytest.raises(ValueError, match="damageability"):
        bumpsim.verdict(root / "examples" / "planar" / "saloon.toml", protocol="rcar-bumper")
    with pytest.raises(ValueError, match="two car files"):
        bumpsim.verdict([car, car], protocol="rcar-bumper")
    with pytest.raises(FileNotFoundError):
        bumpsim.verdict(tmp_path / "missing.toml")
    with pytest.raises(TypeError, match="car"):
        bumpsim.verdict(3)
    with pytest.raises(ValueError, match="protocol"):
        bumpsim.verdict(car, protocol=3)
    assert "part581" in bumpsim.protocols() and "source" in bumpsim.protocols()


# issue 45 item 2: R42 unladen then laden on one car, as `--sequence`
SEQUENCE = "r42-longitudinal-front,r42-laden-longitudinal-front"


def test_a_sequence_is_the_clis_and_the_laden_run_inherits_the_set(car, cli, tmp_path):
    import subprocess

    out = tmp_path / "sequence.json"
    done = subprocess.run(
        [str(cli), "verdict", "--car", str(car), "--protocol", SEQUENCE, "--sequence", "--json", str(out)],
        capture_output=True, text=True,
    )
    assert done.returncode == 0, done.stderr
    document = json.loads(bumpsim.verdict(car, protocol=SEQUENCE, sequence=True).to_json())
    assert document == json.loads(out.read_text())
    first, laden = document["verdict"]["tests"]
    assert first["inherited"] is None
    assert laden["inherited"]["from"] == ["r42-longitudinal-front"]
    assert laden["inherited"]["set"] > 0.0
    alone = json.loads(bumpsim.verdict(car, protocol=SEQUENCE).to_json())
    assert alone["verdict"]["tests"][1]["inherited"] is None
