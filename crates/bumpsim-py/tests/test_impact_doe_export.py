"""Impact, mass reduction, DOE design/fit/predict and FE decks against the
CLI's JSON, CSV and deck files on the same inputs."""

import json

import numpy as np
import pytest

import bumpsim
from conftest import read_csv


def numbers_equal(ours, theirs, rel=1e-12, where="$"):
    """Recursive JSON comparison: numbers to `rel`, everything else exactly."""
    if isinstance(theirs, dict):
        assert set(ours) == set(theirs), where
        for k in theirs:
            numbers_equal(ours[k], theirs[k], rel, f"{where}.{k}")
    elif isinstance(theirs, list):
        assert len(ours) == len(theirs), where
        for i, (a, b) in enumerate(zip(ours, theirs)):
            numbers_equal(a, b, rel, f"{where}[{i}]")
    elif isinstance(theirs, float) and not isinstance(theirs, bool):
        assert ours == pytest.approx(theirs, rel=rel, abs=1e-300), where
    else:
        assert ours == theirs, where


@pytest.mark.parametrize(
    "args, kwargs",
    [
        (["--case", "thesis-600"], {"case": "thesis-600"}),
        (["--pendulum", "1200", "--speed", "2.5"], {"pendulum": 1200.0, "speed": 2.5}),
        (["--barrier", "--speed", "2.2"], {"barrier": True, "speed": 2.2}),
    ],
)
def test_impact_equals_the_cli_json(run, tmp_path, root, args, kwargs):
    car_path = root / "examples" / "identify" / "car-truth.toml"
    bumper_path = root / "examples" / "impact" / "bumper-a.toml"
    out = tmp_path / "impact.json"
    run("impact", "--car", car_path, "--bumper", bumper_path, *args, "--json", out)
    car = bumpsim.Car.from_file(car_path)
    result = bumpsim.impact(car, bumpsim.Bumper.from_file(bumper_path), **kwargs)
    theirs = json.loads(out.read_text())
    numbers_equal(json.loads(result.to_json()), theirs)
    numbers_equal(result.scenario, theirs["scenario"])
    assert result.peak_force == pytest.approx(theirs["peak_force"], rel=1e-12)
    assert result.max_compression == pytest.approx(theirs["max_compression"], rel=1e-12)
    # independent check: the peak of the returned force history
    assert np.max(np.abs(result.force)) == pytest.approx(result.peak_force, rel=1e-9)
    assert result.displacements.shape == (len(result.bodies), len(result.time))


def test_mass_reduction_equals_the_cli_json(run, tmp_path, root):
    bumper_path = root / "examples" / "impact" / "bumper-b.toml"
    out = tmp_path / "reduction.json"
    run("mass-reduction", "--m1", "650", "--m2", "400", "--k", "4e6", "--bumper",
        bumper_path, "--speed", "2.2", "--criterion", "maximum", "--json", out)
    ours = bumpsim.mass_reduction(650.0, 400.0, 4e6, bumpsim.Bumper.from_file(bumper_path),
                                  2.2, criterion="maximum")
    numbers_equal(ours, json.loads(out.read_text()))


def test_impact_errors(root):
    car = bumpsim.Car.from_file(root / "examples" / "identify" / "car-truth.toml")
    bumper = bumpsim.Bumper.from_file(root / "examples" / "impact" / "bumper-a.toml")
    with pytest.raises(bumpsim.InputError, match="no test 'nope'; the tests: thesis-flat"):
        bumpsim.impact(car, bumper, case="nope")
    # an old name is refused with the new one named
    with pytest.raises(bumpsim.InputError, match="use 'rcar-structural-front'"):
        bumpsim.impact(car, bumper, case="rcar-16")
    with pytest.raises(bumpsim.InputError, match="say what hits"):
        bumpsim.impact(car, bumper, speed=2.0)
    with pytest.raises(bumpsim.InputError, match="criterion"):
        bumpsim.mass_reduction(650.0, 400.0, 4e6, bumper, 2.2, criterion="median")


FACTORS = ["Kax:21210:25684", "Kbnd:20217:23643", "M:1375:1681"]


@pytest.mark.parametrize(
    "kind, extra_cli, extra_py",
    [
        ("full", ["--centre", "3"], {"centre": 3}),
        ("fractional", ["--generators", "C=AB"], {"generators": ["C=AB"]}),
        ("lhs", ["--runs", "12", "--seed", "7", "--randomise"],
         {"runs": 12, "seed": 7, "randomise": True}),
    ],
)
def test_doe_design_equals_the_cli_csv(run, tmp_path, kind, extra_cli, extra_py):
    # generators name factors by letter
    factors = ["A:1:2", "B:10:30", "C:-1:1"] if kind == "fractional" else FACTORS
    out = tmp_path / "design.csv"
    run("doe", "design", kind, "--factors", ",".join(factors), *extra_cli, "-o", out)
    design = bumpsim.doe_design(kind, factors, **extra_py)
    assert design.to_csv() == out.read_text()
    table = read_csv(out)
    for j, name in enumerate(design.names):
        np.testing.assert_array_equal(design.physical[:, j], table[name])
        np.testing.assert_array_equal(design.coded[:, j], table[f"{name} (coded)"])


def test_doe_fit_and_predict_equal_the_cli(run, tmp_path):
    design = bumpsim.doe_design("full", FACTORS, centre=3)
    z = design.coded
    wobble = np.sin(7.0 * np.arange(len(z)))
    m2 = 1987.0 - 52.38 * z[:, 0] + 16.63 * z[:, 1] + 215.63 * z[:, 2] + 3.0 * wobble
    c1 = 206.4 + 27.39 * z[:, 0] - 10.63 * z[:, 1] + 6.53 * z[:, 2] + 0.5 * wobble
    data = tmp_path / "data.csv"
    rows = ["Kax [N/mm],Kbnd [N/mm],M [kg],m2 [kg],c1 [Ns/mm]"]
    rows += [",".join(repr(float(v)) for v in r)
             for r in np.column_stack([design.physical, m2, c1])]
    data.write_text("\n".join(rows) + "\n")
    out = tmp_path / "model.json"
    run("doe", "fit", data, "--factors", "Kax,Kbnd,M", "--responses", "m2,c1",
        "--interactions", "--json", out)
    model = bumpsim.doe_fit(data, ["Kax", "Kbnd", "M"], ["m2", "c1"], interactions=True)
    numbers_equal(json.loads(model.to_json()), json.loads(out.read_text()), rel=1e-12)
    # independent check: the main effects come back near the generating ones
    coefficients = model.as_dict()["responses"][0]["coefficients"]
    assert coefficients["Kax"] == pytest.approx(-52.38, abs=3.0)
    at = [("Kax", 23000.0), ("Kbnd", 22000.0), ("M", 1500.0)]
    prediction = model.predict(at)
    cli_text = run("doe", "predict", out, "--at", ",".join(f"{k}={v}" for k, v in at))
    for value in prediction["values"]:
        assert value["name"] in cli_text
    again = bumpsim.DoeModel.from_file(out).predict(at)
    numbers_equal(prediction, again)


def test_weighted_doe_fit_equals_the_cli(run, tmp_path, root):
    """``se=`` is ``doe fit --se``: the identified car variants of the bundled
    example, k1 and c1 weighted by their identification's standard errors."""
    data = root / "examples" / "doe" / "identified.csv"
    out = tmp_path / "weighted.json"
    run("doe", "fit", data, "--factors", "Kax,M", "--responses", "k1,c1",
        "--se", "k1", "--se", "c1=c1.se", "--json", out)
    model = bumpsim.doe_fit(data, ["Kax", "M"], ["k1", "c1"], se=["k1", "c1=c1.se"])
    cli = json.loads(out.read_text())
    numbers_equal(json.loads(model.to_json()), cli, rel=1e-12)
    assert [r["weighted"]["column"] for r in cli["responses"]] == ["k1.se", "c1.se"]
    # the identification's uncertainty widens M's interval on c1 (OLS p 0.005)
    plain = bumpsim.doe_fit(data, ["Kax", "M"], ["c1"]).to_pandas()
    weighted = model.to_pandas()
    assert weighted.loc[("c1", "M"), "std_error"] > plain.loc[("c1", "M"), "std_error"]
    with pytest.raises(bumpsim.InputError, match="se: standard errors '=x'"):
        bumpsim.doe_fit(data, ["Kax", "M"], ["c1"], se=["=x"])
    with pytest.raises(bumpsim.InputError, match="nope.se"):
        bumpsim.doe_fit(data, ["Kax", "M"], ["c1"], se=["c1=nope.se"])


def test_doe_errors(tmp_path):
    with pytest.raises(bumpsim.InputError, match="factors"):
        bumpsim.doe_design("full", ["Kax:1"])
    with pytest.raises(bumpsim.InputError):
        bumpsim.doe_design("nonsense", FACTORS)
    data = tmp_path / "d.csv"
    data.write_text("A [-],y [-]\n0,1\n1,2\n2,4\n")
    with pytest.raises(bumpsim.InputError, match=r"no column 'B'; columns: A, y"):
        bumpsim.doe_fit(data, ["B"], ["y"])


def test_lsdyna_and_calculix_decks_equal_the_cli(run, tmp_path, root):
    car_path = root / "examples" / "simulate" / "car-3dof.toml"
    car = bumpsim.Car.from_file(car_path)
    title = f"{car.name} (from {car_path})"
    k = tmp_path / "car.k"
    run("export", "lsdyna", car_path, "-o", k, "--units", "mm-ms-kg", "--id-offset", "1000",
        "--attach", "11,12", "--initial-velocity", "2.2")
    deck = bumpsim.lsdyna_deck(car, units="mm-ms-kg", id_offset=1000, attach=[11, 12],
                               initial_velocity=2.2, title=title)
    assert deck == k.read_text()
    inp = tmp_path / "deck.inp"
    force_csv = root / "examples" / "simulate" / "pendulum-force.csv"
    run("export", "calculix", car_path, "--force", force_csv, "-o", inp)
    # the CLI reads the force CSV (ms, kN); read_test gives the same samples in SI
    force = bumpsim.read_test(force_csv).channels[0]
    deck = bumpsim.calculix(car, time=force.time, force=force.data, title=title)
    assert deck == inp.read_text()
    run("export", "calculix", car_path, "--force", force_csv, "--id-offset", "500",
        "--prefix", "CAR_", "-o", inp)
    deck = bumpsim.calculix(car, time=force.time, force=force.data, title=title,
                            id_offset=500, prefix="CAR_")
    assert deck == inp.read_text()
    run("export", "lsdyna", car_path, "-o", k, "--force", force_csv, "--output-interval",
        "1e-4", "--standalone")
    deck = bumpsim.lsdyna_deck(car, time=force.time, force=force.data, output_interval=1e-4,
                               standalone=True, title=title)
    assert deck == k.read_text()
    # independent check: the critical step of the lightest mass on its stiffest spring
    # is of the order of sqrt(m1 / k1) (undamped; damping only shortens it)
    assert 0 < bumpsim.critical_time_step(car) <= 2 * (1.8 / 4.75e5) ** 0.5


def test_export_errors(root):
    car = bumpsim.Car.from_file(root / "examples" / "simulate" / "car-3dof.toml")
    with pytest.raises(bumpsim.InputError, match="units"):
        bumpsim.lsdyna_deck(car, units="furlongs")
    with pytest.raises(bumpsim.InputError, match="time and force go together"):
        bumpsim.calculix(car, time=np.arange(3.0))


@pytest.mark.parametrize(
    "cli_args, kwargs",
    [
        (["--case", "rcar-structural-front"], {"case": "rcar-structural-front"}),
        (["--angle", "30", "--overlap", "40", "--side", "right", "--speed", "2.5"],
         {"angle": 30.0, "overlap": 40.0, "side": "right", "speed": 2.5}),
        (["--pole", "0.254", "--pole-offset", "0.2", "--pendulum", "1100", "--speed", "2.2"],
         {"pole": 0.254, "pole_offset": 0.2, "pendulum": 1100.0, "speed": 2.2}),
    ],
)
def test_planar_impact_equals_the_cli_json(run, tmp_path, root, cli_args, kwargs):
    car_path = root / "examples" / "planar" / "saloon.toml"
    out = tmp_path / "planar.json"
    printed = run("planar", "--car", car_path, *cli_args, "--json", out)
    car = bumpsim.PlanarCar.from_file(car_path)
    result = bumpsim.planar_impact(car, **kwargs)
    numbers_equal(json.loads(result.to_json()), json.loads(out.read_text()))
    assert result.result["peak_force"] == json.loads(out.read_text())["result"]["peak_force"]
    # one request behind both front ends: the same text, byte for byte
    # (the CLI adds the files it wrote)
    shown = "".join(l for l in printed.splitlines(keepends=True) if not l.startswith("wrote "))
    assert result.summary() == shown


def test_a_preset_runs_with_its_tyre_law_as_in_the_cli(run, tmp_path, root):
    """A car whose file says locked wheels, struck by a preset whose protocol
    prescribes free-rolling ones: Python ran the file's sliding tyres, the
    CLI the preset's rolling ones."""
    text = (root / "examples" / "planar" / "saloon.toml").read_text()
    sliding = text.replace("front = { rolling_resistance", 'front = { law = "sliding", rolling_resistance')
    sliding = sliding.replace("rear = { rolling_resistance", 'rear = { law = "sliding", rolling_resistance')
    assert sliding.count('law = "sliding"') == 2
    car_path = tmp_path / "sliding.toml"
    car_path.write_text(sliding)
    out = tmp_path / "preset.json"
    run("planar", "--car", car_path, "--case", "rcar-structural-front", "--json", out)
    car = bumpsim.PlanarCar.from_file(car_path)
    result = bumpsim.planar_impact(car, case="rcar-structural-front")
    numbers_equal(json.loads(result.to_json()), json.loads(out.read_text()))
    # the preset's rolling tyres replaced the file's: the bundled rolling car's run
    rolling = bumpsim.PlanarCar.from_file(root / "examples" / "planar" / "saloon.toml")
    same = bumpsim.planar_impact(rolling, case="rcar-structural-front")
    numbers_equal(same.result, result.result)


def test_planar_errors(root):
    car = bumpsim.PlanarCar.from_file(root / "examples" / "planar" / "saloon.toml")
    with pytest.raises(bumpsim.InputError, match="no test 'nope'"):
        bumpsim.planar_impact(car, case="nope")
    with pytest.raises(bumpsim.InputError, match="use 'iihs-bumper-corner-front'"):
        bumpsim.planar_impact(car, case="iihs-corner-front")
    with pytest.raises(bumpsim.InputError, match="side"):
        bumpsim.planar_impact(car, angle=10.0, side="middle", speed=2.0)


def test_the_one_table_lists_and_runs_the_same_tests_as_the_cli(run, root):
    # the names of bumpsim.presets() are those `bumpsim planar --case list` prints
    listed = run("planar", "--case", "list")
    cli = {line.split()[0] for line in listed.splitlines()
           if line and not line.startswith((" ", "#"))}
    names = {p["name"] for p in bumpsim.presets()}
    assert names == cli and len(names) == 35
    corner = next(p for p in bumpsim.presets() if p["name"] == "rcar-structural-front")
    assert "40 % overlap" in corner["dropped_in_1d"]
    # every front end runs a table test: a pendulum of the vehicle's mass in planar
    car = bumpsim.PlanarCar.from_file(root / "examples" / "planar" / "saloon.toml")
    result = bumpsim.planar_impact(car, case="part581-corner-front-left")
    assert result.result["peak_force"] > 0.0


def test_doe_stiffness_equals_the_cli(run, tmp_path):
    # a curve in mm and kN, as the CLI reads it; the package takes SI arrays
    d_mm = np.linspace(0.0, 40.0, 81)
    f_kn = 2.5 * d_mm + 0.01 * np.sin(np.arange(81))
    curve = tmp_path / "curve.csv"
    curve.write_text("displacement [mm],force [kN]\n"
                     + "".join(f"{float(d)!r},{float(f)!r}\n" for d, f in zip(d_mm, f_kn)))
    text = run("doe", "stiffness", curve)
    result = bumpsim.doe_stiffness(d_mm * 1e-3, f_kn * 1e3)
    # independent check: the line's slope is 2.5 kN/mm = 2.5e6 N/m up to the wobble
    assert result["slope"] == pytest.approx(2.5e6, rel=1e-3)
    assert result["points"] > 3 and result["r2"] > 0.999
    # the CLI prints rounded values: the same points and slope (N/mm, 4 digits)
    assert f"line through {result['points']} points" in text
    assert f"stiffness {result['slope'] * 1e-3:.4g} N/mm" in text
    with pytest.raises(bumpsim.InputError, match="stiffness"):
        bumpsim.doe_stiffness([0.0, 1.0], [0.0, 1.0])
