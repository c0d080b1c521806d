"""Identification against `bumpsim identify --json` on the bundled study
(examples/identify/study.toml): same seed and starts, so the same
parameters and objective; the result object's fields, predict and to_json."""

import json

import numpy as np
import pytest

import bumpsim

STARTS, SEED = 8, 3


@pytest.fixture(scope="module")
def cli_json(tmp_path_factory, cli, root):
    import subprocess

    out = tmp_path_factory.mktemp("identify") / "result.json"
    subprocess.run(
        [cli, "identify", root / "examples" / "identify" / "study.toml", "--dof", "3",
         "--starts", str(STARTS), "--seed", str(SEED), "--quiet", "--json", out],
        check=True, capture_output=True,
    )
    return json.loads(out.read_text())


@pytest.fixture(scope="module")
def result(root):
    return bumpsim.identify(root / "examples" / "identify" / "study.toml",
                            dof=3, starts=STARTS, seed=SEED)


def test_same_parameters_and_objective_as_the_cli(result, cli_json):
    # same library, same inputs, same seed: the same numbers; 1e-12 leaves
    # room only for the order of parallel sums
    assert result.objective == pytest.approx(cli_json["objective"], rel=1e-12)
    for name in ("masses", "dampers", "springs"):
        np.testing.assert_allclose(getattr(result, name), cli_json[name], rtol=1e-12)
    # which parameters the data determine, the same in both
    assert result.uncertainty["determined"] == cli_json["uncertainty"]["determined"]
    assert [s["parameter"] for s in result.uncertainty["weakest_direction"]] == \
        [s["parameter"] for s in cli_json["uncertainty"]["weakest_direction"]]
    cli_se = cli_json["uncertainty"]["standard_errors"]
    for ours, theirs in zip(result.standard_errors, cli_se):
        assert (ours is None) == (theirs is None)
        if ours is not None:
            assert ours == pytest.approx(theirs, rel=1e-9)
    assert [c["name"] for c in result.cases] == [c["name"] for c in cli_json["cases"]]
    for ours, theirs in zip(result.cases, cli_json["cases"]):
        assert ours["fit_percent"] == pytest.approx(theirs["fit_percent"], rel=1e-12)


def test_to_json_has_the_cli_fields(result, cli_json):
    ours = json.loads(result.to_json())
    assert set(ours) == set(cli_json)
    # every field of the JSON is an attribute too (the model as masses/dampers/springs)
    for field in set(cli_json) - {"notes"}:
        assert hasattr(result, field), field
    assert result.stop == cli_json["stop"] and result.iterations == cli_json["iterations"]
    assert result.residuals == cli_json["residuals"]
    assert ours["objective"] == pytest.approx(cli_json["objective"], rel=1e-12)
    assert ours["notes"] == cli_json["notes"]
    assert ours["starts"] == cli_json["starts"]


def test_parameters_carry_units_and_predict_reproduces_the_fit(result, cli_json):
    units = {p["name"][0]: p["unit"] for p in result.parameters}
    assert units["m"] == "kg" and units["k"] == "N/m" and units["c"] in ("Ns/m", "N·s/m")
    assert [p["value"] for p in result.parameters if p["name"].startswith("m")] == list(
        result.masses
    )
    predictions = result.predict()
    assert [p.name for p in predictions] == [c["name"] for c in result.cases]
    for p, case in zip(predictions, result.cases):
        assert p.fit_percent == pytest.approx(case["fit_percent"], rel=1e-9)
        # the ISO/TS 18571 rating of the window, as the CLI's JSON gives it
        assert p.rating["overall"] == pytest.approx(case["rating"]["overall"], rel=1e-9)
        assert 0.0 <= p.rating["slope"] <= 1.0
        assert p.simulated.shape == p.measured.shape == p.time.shape
    # the thesis's objective (displacement) is the sum of the cases' squared
    # errors; the default one (velocity, each case weighted by its noise,
    # issue 44) is not, and the JSON says how it compared
    if "compared" in cli_json:
        assert cli_json["compared"] == {"domain": "velocity", "weighted": True}
    else:
        assert sum(p.sse for p in predictions) == pytest.approx(result.objective, rel=1e-9)
    car = result.car
    assert car.dof == 3 and list(car.masses) == list(result.masses)


def test_progress_is_called_once_per_start(root):
    calls = []
    bumpsim.identify(root / "examples" / "identify" / "study.toml", dof=1, starts=4,
                     seed=1, progress=lambda: calls.append(1))
    assert len(calls) == 4


def test_bad_study_raises_documented_errors(tmp_path, root):
    # a missing study is a FileNotFoundError (bumpsim.MissingFileError), in the reader's words
    with pytest.raises(FileNotFoundError, match=r"missing\.toml"):
        bumpsim.identify(tmp_path / "missing.toml")
    bad = tmp_path / "study.toml"
    bad.write_text("[model]\ndof = 3\nstarts = 0\n")
    with pytest.raises(bumpsim.InputError, match=r"study\.toml"):
        bumpsim.identify(bad)


def test_identify_from_numpy_recovers_the_car_that_made_the_data():
    # independent check: data simulated from a known 2-DOF car, identified back
    truth = bumpsim.Car([40.0, 900.0], [6e3], [8e5])
    time = np.arange(3001) * 1e-4
    cases = []
    for name, peak, width in [("short", 2e4, 0.03), ("long", 1.2e4, 0.08)]:
        force = np.where(time < width, peak * np.sin(np.pi * time / width), 0.0)
        x1 = bumpsim.simulate(truth, time, force).displacement[0]
        cases.append(bumpsim.LoadCase(name, time, force, x1, output_dof=1))
    result = bumpsim.identify_cases(cases, dof=2, starts=8, seed=1)
    np.testing.assert_allclose(result.masses, truth.masses, rtol=1e-5)
    np.testing.assert_allclose(result.dampers, truth.dampers, rtol=1e-5)
    np.testing.assert_allclose(result.springs, truth.springs, rtol=1e-5)
    assert [c["name"] for c in result.cases] == ["short", "long"]
    assert all(p.fit_percent > 99.99 for p in result.predict())


def test_load_case_errors():
    time = np.arange(10) * 1e-3
    with pytest.raises(bumpsim.InputError, match="9 force samples and 10 displacement|expected the same number"):
        bumpsim.LoadCase("a", time[:9], np.zeros(9), np.arange(10.0))
    with pytest.raises(bumpsim.InputError, match="constant"):
        bumpsim.LoadCase("a", time, np.ones(10), np.zeros(10))
    with pytest.raises(bumpsim.InputError, match=r"no sample inside the window"):
        bumpsim.LoadCase("a", time, np.ones(10), np.arange(10.0), window=(0.0021, 0.0029))
    # a window reaching past the record is refused as the CLI refuses a
    # study's, not cut to the record (its fit would be over another window)
    past = r"window \[0.002, 0.02\] s: expected times within the record, 0 s to 0.009000 s"
    for window, match in [((0.002, 0.02), past), ((-1.0, 0.005), "within the record")]:
        with pytest.raises(bumpsim.InputError, match=match):
            bumpsim.LoadCase("a", time, np.ones(10), np.arange(10.0), window=window)
    inside = bumpsim.LoadCase("a", time, np.ones(10), np.arange(10.0), window=(0.002, 0.009))
    assert inside.window == pytest.approx((0.002, 0.009))
    with pytest.raises(bumpsim.InputError, match=r"displacement: expected a 1-D numpy array of float64"):
        bumpsim.LoadCase("a", time, np.ones(10), np.arange(10))


def test_report_equals_the_cli_report(run, tmp_path, root, result):
    import re

    folder = tmp_path / "report"
    run("identify", root / "examples" / "identify" / "study.toml", "--dof", "3", "--starts",
        str(STARTS), "--seed", str(SEED), "--quiet", "--report", folder)
    html, figures = result.report()
    assert sorted(figures) == sorted(p.name for p in folder.glob("*.svg"))
    for name, svg in figures.items():
        assert svg == (folder / name).read_text(), name
    # the wall-clock run time is the one thing that differs between two runs
    run_time = re.compile(r"\d+(\.\d+)? (s|ms)(?=\.</p>|\n)")
    # and the CLI's viewer line under each figure, which names the files the
    # command wrote (a report made in Python has no files to name)
    viewer = re.compile(r'<p class="view">Open in the viewer: .*?</p>\n')
    cli = viewer.sub("", (folder / "index.html").read_text())
    assert run_time.sub("T", html) == run_time.sub("T", cli)


def test_dof_table_equals_the_cli_table(run, tmp_path, root):
    # `identify --dof 1..3`: same orders, objectives, cross-validation and
    # recommendation (the model choice) as the CLI's JSON and text
    study = root / "examples" / "identify" / "study.toml"
    out = tmp_path / "table.json"
    text = run("identify", study, "--dof", "1..3", "--starts", "4", "--seed", "1", "--quiet", "--json", out)
    theirs = json.loads(out.read_text())
    table = bumpsim.dof_table(study, dofs="1..3", starts=4, seed=1)
    ours = json.loads(table.to_json())
    assert set(ours) == set(theirs)
    assert table.recommended == theirs["recommended_dof"]
    assert [r.dof for r in table.results] == [r["dof"] for r in theirs["results"]] == [1, 2, 3]
    for mine, cli in zip(ours["results"], theirs["results"]):
        assert mine["objective"] == pytest.approx(cli["objective"], rel=1e-12)
        assert (mine["cross_validation"] is None) == (cli["cross_validation"] is None)
        if cli["cross_validation"] is not None:
            assert mine["cross_validation"]["error"] == pytest.approx(cli["cross_validation"]["error"], rel=1e-9)
    # the table's rows as the CLI prints them, but for the run times
    first = table.to_text().splitlines()[0]
    assert first in text.splitlines()
