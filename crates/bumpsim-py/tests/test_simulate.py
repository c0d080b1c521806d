"""Car models and simulation against `bumpsim simulate` on the same inputs
(examples/simulate), and the documented errors."""

import numpy as np
import pytest

import bumpsim
from conftest import read_csv

# the CLI writes shortest round-trip decimals, so both sides run the same
# arithmetic on the same numbers; 1e-12 of each column's largest magnitude
# (issue #18) leaves room for nothing but summation order
RTOL = 1e-12


@pytest.fixture(scope="module")
def cli_response(tmp_path_factory, cli, root):
    import subprocess

    out = tmp_path_factory.mktemp("simulate") / "out.csv"
    ex = root / "examples" / "simulate"
    subprocess.run(
        [cli, "simulate", "--car", ex / "car-3dof.toml", "--force",
         ex / "pendulum-force.csv", "--initial-velocity", "0.5", "-o", out],
        check=True, capture_output=True,
    )
    return read_csv(out)


def close(actual, expected, what):
    scale = max(np.max(np.abs(expected)), 1e-300)
    error = np.max(np.abs(actual - expected)) / scale
    assert error <= RTOL, f"{what}: relative error {error:.3g} > {RTOL}"


def test_simulation_equals_the_cli(cli_response, root):
    car = bumpsim.Car.from_file(root / "examples" / "simulate" / "car-3dof.toml")
    time, force = cli_response["time [s]"], cli_response["force [N]"]
    r = bumpsim.simulate(car, time, force, method="zoh", initial_velocity=0.5)
    assert r.displacement.shape == (3, len(time))
    assert r.spring_force.shape == (2, len(time))
    close(r.time, time, "time")
    for i in range(3):
        close(r.displacement[i], cli_response[f"x{i + 1} [m]"], f"x{i + 1}")
        close(r.velocity[i], cli_response[f"v{i + 1} [m/s]"], f"v{i + 1}")
        close(r.acceleration[i], cli_response[f"a{i + 1} [m/s^2]"], f"a{i + 1}")
    for j in range(2):
        close(r.spring_force[j], cli_response[f"spring{j + 1} [N]"], f"spring{j + 1}")
        close(r.damper_force[j], cli_response[f"damper{j + 1} [N]"], f"damper{j + 1}")
    for name in ("kinetic_energy", "spring_energy", "dissipated_energy", "work"):
        close(getattr(r, name), cli_response[f"{name} [J]"], name)


def test_car_values_and_file_name(root):
    car = bumpsim.Car.from_file(root / "examples" / "simulate" / "car-3dof.toml")
    assert car.dof == 3
    assert list(car.masses) == [1.8, 74.8, 1670.0]
    assert car.total_mass == pytest.approx(1.8 + 74.8 + 1670.0, rel=1e-15)
    again = bumpsim.Car(car.masses, car.dampers, [4.75e5, 5.0e5])
    assert list(again.springs) == list(car.springs)


def test_methods_agree_with_each_other():
    # independent check: for a force linear between samples foh is exact and
    # zoh differs by at most the hold error; both must end at the impulse
    car = bumpsim.Car([300.0, 900.0], [4e3], [8e5])
    time = np.arange(2001) * 1e-5
    force = np.interp(time, [0.0, 0.01, 0.02], [0.0, 1e4, 0.0])
    zoh = bumpsim.simulate(car, time, force)
    foh = bumpsim.simulate(car, time, force, method="foh")
    impulse = 0.5 * 0.02 * 1e4
    momentum = 300.0 * foh.velocity[0, -1] + 900.0 * foh.velocity[1, -1]
    assert momentum == pytest.approx(impulse, rel=1e-9)
    assert np.max(np.abs(zoh.displacement - foh.displacement)) < 1e-3 * np.max(
        np.abs(foh.displacement)
    )


def test_invalid_model_raises_input_error_with_the_core_message():
    with pytest.raises(bumpsim.InputError, match=r"m2 = -2 kg: a mass must be positive"):
        bumpsim.Car([1.0, -2.0], [1.0], [1.0])
    with pytest.raises(bumpsim.Error):
        bumpsim.Car([1.0, 2.0], [1.0], [])


@pytest.mark.parametrize(
    "force, message",
    [
        (np.zeros(10, dtype=np.float32), r"force: expected a 1-D numpy array of float64, got a 1-D array of float32"),
        (np.zeros((2, 5)), r"force: expected a 1-D numpy array of float64, got a 2-D array of float64 with shape \(2, 5\)"),
        (np.zeros(10, dtype=np.int64), r"got a 1-D array of int64"),
        ("abc", r"force: expected a 1-D numpy array of float64 or a sequence of numbers, got str"),
    ],
)
def test_bad_dtypes_and_shapes_raise_input_error(force, message):
    car = bumpsim.Car([1.0], [], [])
    with pytest.raises(bumpsim.InputError, match=message):
        bumpsim.simulate(car, np.arange(10) * 1e-3, force)


def test_bad_time_base_and_method_raise_input_error():
    car = bumpsim.Car([1.0], [], [])
    time = np.arange(10) * 1e-3
    time[5] += 5e-4
    with pytest.raises(bumpsim.InputError, match=r"time 5 is .* not uniformly sampled"):
        bumpsim.simulate(car, time, np.zeros(10))
    with pytest.raises(bumpsim.InputError, match=r"9 sample times for 10 values"):
        bumpsim.simulate(car, np.arange(9) * 1e-3, np.zeros(10))
    with pytest.raises(bumpsim.InputError, match="euler"):
        bumpsim.simulate(car, np.arange(10) * 1e-3, np.zeros(10), method="euler")
    force = np.zeros(10)
    force[3] = np.nan
    with pytest.raises(bumpsim.InputError, match=r"sample 3 .* is NaN"):
        bumpsim.simulate(car, np.arange(10) * 1e-3, force)


def test_bad_files_raise_file_and_input_errors(tmp_path):
    with pytest.raises(bumpsim.MissingFileError, match=r"missing\.toml: cannot read"):
        bumpsim.Car.from_file(tmp_path / "missing.toml")
    typo = tmp_path / "typo.toml"
    typo.write_text("masses = [1000.0]\nspring = [1.0]\n")
    with pytest.raises(bumpsim.InputError, match=r"typo\.toml.*spring") as caught:
        bumpsim.Car.from_file(typo)
    assert not isinstance(caught.value, bumpsim.FileError)


def test_strided_views_and_lists_give_the_same_result_as_contiguous_arrays():
    car = bumpsim.Car([300.0, 900.0], [4e3], [8e5])
    time = np.arange(401) * 1e-4
    force = 1e4 * np.sin(np.arange(401) * 0.02)
    both = np.column_stack([time, force])  # columns are strided views
    reference = bumpsim.simulate(car, time, force)
    strided = bumpsim.simulate(car, both[:, 0], both[:, 1])
    listed = bumpsim.simulate(car, list(time), list(force))
    assert np.array_equal(strided.displacement, reference.displacement)
    assert np.array_equal(listed.displacement, reference.displacement)


def test_taylor1_with_substeps_equals_the_cli(run, tmp_path, root):
    ex = root / "examples" / "simulate"
    out = tmp_path / "taylor1.csv"
    run("simulate", "--car", ex / "car-3dof.toml", "--force", ex / "pendulum-force.csv",
        "--method", "taylor1", "--substeps", "auto", "-o", out)
    table = read_csv(out)
    car = bumpsim.Car.from_file(ex / "car-3dof.toml")
    r = bumpsim.simulate(car, table["time [s]"], table["force [N]"], method="taylor1",
                         substeps="auto")
    for i in range(3):
        close(r.displacement[i], table[f"x{i + 1} [m]"], f"x{i + 1}")
    # without sub-steps the thesis's explicit scheme diverges here: refused with the stable step
    with pytest.raises(bumpsim.InputError, match="taylor1"):
        bumpsim.simulate(car, table["time [s]"], table["force [N]"], method="taylor1")
    with pytest.raises(bumpsim.InputError, match="substeps 0"):
        bumpsim.simulate(car, table["time [s]"], table["force [N]"], method="taylor1", substeps=0)
