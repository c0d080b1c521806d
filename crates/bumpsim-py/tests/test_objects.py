"""Issue 38: every public class pickles (``loads(dumps(x)) == x``), compares
equal to its copy and prints a readable repr; worker processes run impacts;
arrays are read-only and cached for every class; exceptions sit on Python's
bases (``ValueError``, ``FileNotFoundError``)."""

import pickle
from concurrent.futures import ProcessPoolExecutor
import multiprocessing

import numpy as np
import pytest

import bumpsim


@pytest.fixture(scope="module")
def objects(root, tmp_path_factory):
    """One object of every public class, from the bundled examples."""
    ex = root / "examples"
    car = bumpsim.Car.from_file(ex / "identify" / "car-truth.toml")
    bumper = bumpsim.Bumper.from_file(ex / "impact" / "bumper-a.toml")
    time = np.arange(401) * 1e-4
    force = np.where(time < 0.02, 1e4 * np.sin(np.pi * time / 0.02), 0.0)
    response = bumpsim.simulate(car, time, force)
    test = bumpsim.read_test(ex / "identify" / "P600")
    case = bumpsim.LoadCase("mine", time, force, response.displacement[0], window=(0.0, 0.03))
    identification = bumpsim.identify_cases([case], dof=1, starts=2, seed=1)
    saloon = bumpsim.PlanarCar.from_file(ex / "planar" / "saloon.toml")
    design = bumpsim.doe_design("full", ["a:1:2", "b:3:4"], centre=1)
    data = tmp_path_factory.mktemp("objects") / "data.csv"
    rows = [f"{a},{b},{3 * a - b + 0.01 * i}" for i, (a, b) in enumerate(design.physical)]
    data.write_text("a,b,y\n" + "\n".join(rows) + "\n")
    pipeline = data.with_name("pipeline.toml")
    p600 = ex / "identify" / "P600"
    pipeline.write_text(
        f'[[signal]]\nname = "force"\npath = "{p600}"\nchannels = ["P0IMPA*"]\n'
        'steps = [{ pretrigger_bias = true }, { cfc = 180 }]\n'
    )
    study = ex / "identify" / "study.toml"
    verdict = bumpsim.verdict(ex / "verdict" / "car.toml", protocol="rcar-bumper-corner-front", target=True)
    return {
        "Car": car,
        "Response": response,
        "Test": test,
        "Entry": test.entries[0],
        "Channel": test.channels[0],
        "LoadCase": case,
        "Identification": identification,
        "Prediction": identification.predict()[0],
        "Bumper": bumper,
        "Impact": bumpsim.impact(car, bumper, case="thesis-600"),
        "PlanarCar": saloon,
        "PlanarImpact": bumpsim.planar_impact(saloon, angle=30.0, overlap=40.0, speed=2.5),
        "Design": design,
        "DoeModel": bumpsim.doe_fit(data, ["a", "b"], ["y"]),
        "PipelineRun": bumpsim.run_pipeline(pipeline),
        "DofTable": bumpsim.dof_table(study, dofs="1..2", starts=2, seed=1),
        "Posterior": identification.posterior(steps=40),
        "Verdict": verdict,
        "BumperTarget": verdict.target,
    }


CLASSES = [
    "Car", "Response", "Test", "Entry", "Channel", "LoadCase", "Identification",
    "Prediction", "Bumper", "Impact", "PlanarCar", "PlanarImpact", "Design",
    "DoeModel", "PipelineRun", "DofTable", "Posterior", "Verdict", "BumperTarget",
]
# pickled, compared and printed in test_campaign.py
CAMPAIGN_CLASSES = ["Campaign", "CampaignStatus", "Collected"]
# pickled, compared and printed in test_identify_links.py (a links identification)
STUDY_CLASSES = ["StudyIdentification"]


def test_every_public_class_is_checked():
    classes = {
        name for name in dir(bumpsim._native)
        if isinstance(getattr(bumpsim, name), type) and not issubclass(getattr(bumpsim, name), Exception)
    }
    assert classes == set(CLASSES) | set(CAMPAIGN_CLASSES) | set(STUDY_CLASSES)


@pytest.mark.parametrize("name", CLASSES)
def test_pickles_compares_and_prints(objects, name):
    x = objects[name]
    assert type(x).__name__ == name
    copy = pickle.loads(pickle.dumps(x))
    assert copy == x and not (copy != x)
    assert type(copy) is type(x)
    text = repr(x)
    assert text.startswith(name + "(") and "object at 0x" not in text, text


def test_equal_cars_compare_equal_and_different_ones_do_not():
    a = bumpsim.Car([1.0, 2.0], [3.0], [4.0], name="x")
    assert a == bumpsim.Car([1.0, 2.0], [3.0], [4.0], name="x")
    assert a != bumpsim.Car([1.0, 2.0], [3.0], [5.0], name="x")
    assert repr(a) == "Car(masses=[1.0, 2.0], dampers=[3.0], springs=[4.0], name=\"x\")"


def test_a_process_pool_runs_four_impacts_in_parallel(objects):
    car, bumper = objects["Car"], objects["Bumper"]
    cases = ["thesis-600", "thesis-pole", "thesis-flat", "thesis-600"]
    serial = [bumpsim.impact(car, bumper, case=c) for c in cases]
    context = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(max_workers=2, mp_context=context) as pool:
        parallel = list(pool.map(_impact, [(car, bumper, c) for c in cases]))
    assert parallel == serial


def _impact(job):
    car, bumper, case = job
    return bumpsim.impact(car, bumper, case=case)


@pytest.mark.parametrize(
    "name, attribute",
    [
        ("Car", "masses"), ("Response", "displacement"), ("Response", "time"),
        ("Channel", "data"), ("Channel", "time"), ("LoadCase", "force"),
        ("Identification", "masses"), ("Prediction", "simulated"), ("Impact", "force"),
        ("Design", "coded"), ("Posterior", "samples"), ("Posterior", "mean"),
    ],
)
def test_arrays_are_read_only_and_made_once(objects, name, attribute):
    x = objects[name]
    array = getattr(x, attribute)
    assert getattr(x, attribute) is array, "one array per object, not a copy per access"
    before = array.copy()
    with pytest.raises(ValueError, match="read-only"):
        array[..., 0] = 99.0
    assert np.array_equal(getattr(x, attribute), before)
    writable = array.copy()
    writable[..., 0] = 99.0


def test_exceptions_sit_on_pythons_bases():
    assert issubclass(bumpsim.InputError, ValueError)
    assert issubclass(bumpsim.InputError, bumpsim.Error)
    assert issubclass(bumpsim.FileError, OSError)
    assert issubclass(bumpsim.MissingFileError, FileNotFoundError)
    assert issubclass(bumpsim.MissingFileError, bumpsim.FileError)
    assert issubclass(bumpsim.RunError, RuntimeError)
    assert not issubclass(bumpsim.FileError, ValueError)
    # errors raised in a worker process come back whole: class and message
    try:
        bumpsim.Car.from_file("/nonexistent/car.toml")
    except bumpsim.Error as error:
        back = pickle.loads(pickle.dumps(error))
        assert type(back) is bumpsim.MissingFileError and str(back) == str(error)


def test_every_missing_file_is_a_file_not_found_error(tmp_path):
    missing = tmp_path / "missing"
    calls = [
        lambda: bumpsim.Car.from_file(missing / "car.toml"),
        lambda: bumpsim.simulate(missing / "car.toml", [0.0, 1.0], [0.0, 0.0]),
        lambda: bumpsim.identify(missing / "study.toml"),
        lambda: bumpsim.dof_table(missing / "study.toml", dofs="1..2"),
        lambda: bumpsim.read_test(missing / "test.EV5"),
        lambda: bumpsim.read_test(missing),
        lambda: bumpsim.Bumper.from_file(missing / "bumper.toml"),
        lambda: bumpsim.PlanarCar.from_file(missing / "saloon.toml"),
        lambda: bumpsim.DoeModel.from_file(missing / "model.json"),
        lambda: bumpsim.doe_fit(missing / "data.csv", ["a"], ["y"]),
        lambda: bumpsim.run_pipeline(missing / "pipeline.toml"),
        lambda: bumpsim.Campaign.init(missing / "campaign.toml"),
        lambda: bumpsim.Campaign(missing).status(),
    ]
    for call in calls:
        with pytest.raises(FileNotFoundError) as caught:
            call()
        assert isinstance(caught.value, bumpsim.MissingFileError)
        assert "missing" in str(caught.value) and "Errno" not in str(caught.value)


def test_every_bad_value_is_a_value_error(root, tmp_path):
    study = root / "examples" / "identify" / "study.toml"
    car = bumpsim.Car([1.0, 2.0], [3.0], [4.0])
    bad = tmp_path / "bad.toml"
    bad.write_text("masses = [1000.0]\nspring = [1.0]\n")
    calls = [
        (lambda: bumpsim.Car([1.0, -2.0], [3.0], [4.0]), "m2"),
        (lambda: bumpsim.Car.from_file(bad), "spring"),
        (lambda: bumpsim.simulate(car, [0.0, 1.0, 3.0], [0.0, 0.0, 0.0]), "uniform"),
        (lambda: bumpsim.simulate(car, np.zeros((2, 2)), [0.0]), "1-D"),
        (lambda: bumpsim.identify(study, starts=-1), "starts -1"),
        (lambda: bumpsim.identify(study, seed=-1), "seed -1"),
        (lambda: bumpsim.identify(study, dof=0), "1..5"),
        (lambda: bumpsim.dof_table(study, dofs="5..1"), "dof"),
        (lambda: bumpsim.cfc(np.zeros(100), 1e4, -60), "CFC class"),
        (lambda: bumpsim.doe_design("full", ["a:2:1"]), "a"),
    ]
    for call, words in calls:
        with pytest.raises(ValueError, match=words) as caught:
            call()
        assert isinstance(caught.value, bumpsim.InputError), caught.value


def test_a_car_file_is_a_car_everywhere(root):
    path = root / "examples" / "simulate" / "car-3dof.toml"
    time = np.arange(11) * 1e-3
    by_path = bumpsim.simulate(str(path), time, np.ones(11))
    assert by_path == bumpsim.simulate(bumpsim.Car.from_file(path), time, np.ones(11))
    with pytest.raises(TypeError, match="car"):
        bumpsim.simulate(3, time, np.ones(11))
