"""Issue 38: every tabular result as a pandas object, columns named
``name [unit]`` as the CLI's CSV headers (or units in a column or attrs),
time histories indexed by ``time [s]``; pandas is imported only when asked."""

import subprocess
import sys

import numpy as np
import pytest

import bumpsim
from conftest import read_csv

pd = pytest.importorskip("pandas", reason="pandas not installed (optional)")


def test_bumpsim_imports_without_pandas():
    code = "import sys, bumpsim; assert 'pandas' not in sys.modules; print('ok')"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert done.stdout.strip() == "ok", done.stderr


def test_response_frame_is_the_cli_csv(run, tmp_path, root):
    ex = root / "examples" / "simulate"
    out = tmp_path / "response.csv"
    run("simulate", "--car", ex / "car-3dof.toml", "--force", ex / "pendulum-force.csv", "-o", out)
    cli = read_csv(out)
    car = bumpsim.Car.from_file(ex / "car-3dof.toml")
    frame = bumpsim.simulate(car, cli["time [s]"], cli["force [N]"]).to_pandas()
    assert isinstance(frame, pd.DataFrame)
    assert frame.index.name == "time [s]"
    assert ["time [s]"] + list(frame.columns) == list(cli)
    np.testing.assert_allclose(frame.index.to_numpy(), cli["time [s]"], rtol=1e-12)
    for column in frame.columns:
        np.testing.assert_allclose(frame[column].to_numpy(), cli[column], rtol=1e-9, atol=1e-12)
    assert frame.attrs["method"] == "zoh"


def test_channel_series_is_time_indexed(root):
    channel = bumpsim.read_test(root / "examples" / "identify" / "P600").channels[0]
    series = channel.to_pandas()
    assert isinstance(series, pd.Series)
    assert series.index.name == "time [s]"
    assert series.name == f"{channel.code} [{channel.unit}]"
    assert np.array_equal(series.to_numpy(), channel.data)
    assert np.array_equal(series.index.to_numpy(), channel.time)


def test_test_lists_its_channels(root):
    test = bumpsim.read_test(root / "examples" / "identify" / "P600")
    frame = test.to_pandas()
    assert frame.index.name == "number"
    assert list(frame["code"]) == [e.code for e in test.entries]


def test_identification_parameters_with_intervals_cases_and_dof_table(root):
    study = root / "examples" / "identify" / "study.toml"
    result = bumpsim.identify(study, dof=2, starts=4, seed=1)
    frame = result.to_pandas()
    assert frame.index.name == "parameter"
    assert list(frame.index) == [p["name"] for p in result.parameters]
    assert list(frame["unit"]) == [p["unit"] for p in result.parameters]
    assert {"value", "standard_error", "ci95_low", "ci95_high"} <= set(frame.columns)
    assert list(frame["value"]) == [p["value"] for p in result.parameters]
    cases = result.cases_to_pandas()
    assert cases.index.name == "case" and "fit [%]" in cases.columns
    prediction = result.predict()[0].to_pandas()
    assert prediction.index.name == "time [s]"
    assert list(prediction.columns) == ["measured [m]", "simulated [m]"]
    # the objective's key carries its unit, as the CLI prints it after it
    # (the bundled study compares velocities: not m²)
    key = "objective [" + result.objective_unit.replace("²", "^2") + "]"
    assert result.objective_unit != "m²" and "objective [m^2]" not in frame.attrs
    assert frame.attrs[key] == result.objective
    assert f"{result.objective_unit}, fit=" in repr(result)
    table = bumpsim.dof_table(study, dofs="1..2", starts=4, seed=1)
    frame = table.to_pandas()
    assert list(frame.index) == [1, 2] and frame.index.name == "dof"
    assert list(frame[key]) == [r.objective for r in table.results]
    assert "bic [-]" in frame.columns and frame.attrs["recommended"] in (1, 2)
    assert pickle_equal(table)


def pickle_equal(x):
    import pickle

    return pickle.loads(pickle.dumps(x)) == x


def test_impact_histories_and_bumper_curve(run, tmp_path, root):
    car = root / "examples" / "identify" / "car-truth.toml"
    bumper = root / "examples" / "impact" / "bumper-a.toml"
    out = tmp_path / "impact.csv"
    run("impact", "--car", car, "--bumper", bumper, "--case", "thesis-600", "--csv", out)
    cli = read_csv(out)
    hit = bumpsim.impact(bumpsim.Car.from_file(car), bumpsim.Bumper.from_file(bumper), case="thesis-600")
    frame = hit.to_pandas()
    assert ["time [s]"] + list(frame.columns) == list(cli)
    np.testing.assert_allclose(frame["force [N]"].to_numpy(), cli["force [N]"], rtol=1e-9)
    assert frame.attrs["peak_force [N]"] == hit.peak_force
    curve = bumpsim.Bumper.from_file(bumper).to_pandas()
    assert curve.index.name == "compression [m]" and list(curve.columns) == ["force [N]"]


def test_car_planar_and_case_frames(root):
    car = bumpsim.Car([1.0, 2.0], [3.0], [4.0])
    frame = car.to_pandas()
    assert list(frame.index) == ["m1", "m2", "c1", "k1"]
    assert list(frame["unit"]) == ["kg", "kg", "N·s/m", "N/m"] or frame["unit"].iloc[3] == "N/m"
    saloon = bumpsim.PlanarCar.from_file(root / "examples" / "planar" / "saloon.toml")
    planar = bumpsim.planar_impact(saloon, angle=30.0, overlap=40.0, speed=2.5).to_pandas()
    assert planar.index.name == "time [s]" and all("[" in c for c in planar.columns)
    time = np.arange(11) * 1e-3
    case = bumpsim.LoadCase("c", time, np.ones(11), time**2).to_pandas()
    assert case.index.name == "time [s]"
    assert list(case.columns) == ["force [N]", "displacement [m]"]


def test_design_and_fit_frames(run, tmp_path):
    out = tmp_path / "design.csv"
    factors = ["Kax:21210:25684", "Kbnd:20217:23643", "M:1375:1681"]
    run("doe", "design", "full", "--factors", ",".join(factors), "--centre", "3", "-o", out)
    design = bumpsim.doe_design("full", factors, centre=3)
    frame = design.to_pandas()
    cli = read_csv(out)
    assert [frame.index.name] + list(frame.columns) == list(cli)
    for column in frame.columns:
        np.testing.assert_array_equal(frame[column].to_numpy(dtype=float), cli[column])
    data = tmp_path / "data.csv"
    rows = ["Kax,Kbnd,M,y"] + [
        f"{a},{b},{c},{2 * a + b - c + 0.1 * (i % 3)}"
        for i, (a, b, c) in enumerate(design.physical)
    ]
    data.write_text("\n".join(rows) + "\n")
    model = bumpsim.doe_fit(data, ["Kax", "Kbnd", "M"], ["y"])
    fit = model.to_pandas()
    assert fit.index.names == ["response", "term"]
    assert {"coefficient", "ci95_low", "ci95_high", "unit"} <= set(fit.columns)
    assert pickle_equal(model) and repr(model).startswith("DoeModel(")
