"""Crash-test signals against `bumpsim signal export` on the same files:
NHTSA test 10146 (EV5, from ../shared; skipped when absent) read and CFC 60
filtered must be bit-identical to the CLI's CSV; the bundled ISO-MME tests
(examples/identify) read the same; bad files raise the documented errors."""

import numpy as np
import pytest

import bumpsim
from conftest import nhtsa_10146, read_csv


def cli_export(run, tmp_path, path, channel, *steps):
    out = tmp_path / "export.csv"
    run("signal", "export", path, "--channel", channel, *steps, "-o", out)
    columns = read_csv(out)
    (time, *data) = columns.values()
    assert len(data) == 1
    return time, data[0], list(columns)[1]


@pytest.mark.parametrize("channel", ["93", "0-LC-*-XG"])
def test_nhtsa_10146_read_and_cfc60_bit_identical_to_the_cli(run, tmp_path, channel):
    path = nhtsa_10146()
    test = bumpsim.read_test(path)
    assert test.format == "NHTSA EV5"
    chosen = test.select(channel)[0]
    # the CLI exports the first channel the selector picks
    selector = str(next(e.number for e in test.entries if e.code == chosen.code))
    time, raw, header = cli_export(run, tmp_path, path, selector)
    assert header == f"{chosen.code} [{chosen.unit}]"
    assert np.array_equal(chosen.time, time)
    assert np.array_equal(chosen.data, raw)
    filtered = chosen.cfc(60)
    time, cli60, header = cli_export(run, tmp_path, path, selector, "--cfc", "60")
    assert header == f"{filtered.code} [{filtered.unit}]"
    assert np.array_equal(filtered.data, cli60), "CFC 60 differs from the CLI's"
    # the free function on numpy samples: same filter, the interval from fs
    free = bumpsim.cfc(chosen.data, 1.0 / chosen.step, 60)
    assert np.max(np.abs(free - cli60)) <= 1e-9 * np.max(np.abs(cli60))


def test_nhtsa_10146_metadata_and_invalid_channels():
    test = bumpsim.read_test(nhtsa_10146())
    assert test.speed == pytest.approx(57.09 / 3.6, rel=1e-3)
    invalid = [e for e in test.entries if e.invalid is not None]
    assert invalid, "test 10146 lists barrier cells marked 'No valid data'"
    # wildcard selections leave invalid and absent channels out
    usable = [e for e in test.entries if e.invalid is None and e.present]
    assert len(test.channels) == len(usable) < len(test.entries)


def test_iso_mme_read_equals_the_cli(run, tmp_path, root):
    folder = root / "examples" / "identify" / "P600"
    test = bumpsim.read_test(folder)
    assert test.format == "ISO-MME"
    first = test.channels[0]
    time, data, header = cli_export(run, tmp_path, folder, str(test.entries[0].number))
    assert header == f"{first.code} [{first.unit}]"
    assert np.array_equal(first.time, time)
    assert np.array_equal(first.data, data)
    assert len(first) == len(time)


def test_processing_steps_equal_the_cli(run, tmp_path, root):
    folder = root / "examples" / "identify" / "P600"
    test = bumpsim.read_test(folder)
    entry = next(e for e in test.entries if "ACX" in e.code)
    channel = test.channel(entry.number)
    processed = channel.bias().cfc(180).scale(-1.0).integrate(0.0)
    time, data, header = cli_export(
        run, tmp_path, folder, str(entry.number), "--bias", "--cfc", "180",
        "--scale", "-1", "--integrate", "0",
    )
    assert header == f"{processed.code} [{processed.unit}]"
    assert np.array_equal(processed.data, data)


def test_bad_test_files_raise_documented_errors(tmp_path):
    with pytest.raises(bumpsim.MissingFileError, match=r"missing\.EV5"):
        bumpsim.read_test(tmp_path / "missing.EV5")
    bad = tmp_path / "bad.csv"
    bad.write_text("time [s],force [kN]\n0,1\n0.001,x\n")
    with pytest.raises(bumpsim.InputError, match=r"bad\.csv:3"):
        bumpsim.read_test(bad)
    with pytest.raises(bumpsim.InputError, match=r"CFC class"):
        bumpsim.cfc(np.zeros(100), 1e4, -60)
    with pytest.raises(bumpsim.InputError, match=r"x: expected a 1-D numpy array of float64"):
        bumpsim.cfc(np.zeros((10, 10)), 1e4, 60)


def test_to_pandas_when_pandas_is_installed(root):
    pandas = pytest.importorskip("pandas", reason="pandas not installed (optional)")
    channel = bumpsim.read_test(root / "examples" / "identify" / "P600").channels[0]
    series = channel.to_pandas()
    assert isinstance(series, pandas.Series)
    assert np.array_equal(series.to_numpy(), channel.data)
    assert np.array_equal(series.index.to_numpy(), channel.time)


def test_pipeline_equals_the_cli(run, tmp_path, root):
    p600 = root / "examples" / "identify" / "P600"
    pipeline = tmp_path / "pipeline.toml"
    pipeline.write_text(f"""
[[signal]]
name = "force"
path = "{p600}"
channels = ["P0IMPA*"]
steps = [{{ pretrigger_bias = true }}, {{ cfc = 180 }}]

[[signal]]
name = "velocity"
path = "{p600}"
channels = ["10SIME*ACXP"]
combine = "mean"
steps = [{{ cfc = 180 }}, {{ integrate = 0.0 }}]
""")
    out = tmp_path / "out.csv"
    run("signal", "process", pipeline, "-o", out)
    table = read_csv(out)
    result = bumpsim.run_pipeline(pipeline)
    assert len(result.signals) == 2 and result.balance is None
    for signal in result.signals:
        assert np.array_equal(signal.data, table[f"{signal.code} [{signal.unit}]"])
    assert len(result.raw) >= 2


def test_trim_and_resample_equal_the_cli(run, tmp_path, root):
    folder = root / "examples" / "identify" / "P600"
    channel = bumpsim.read_test(folder).channel(1)
    processed = channel.cfc(60).trim(0.0, 0.1).resample(2e-4)
    time, data, header = cli_export(run, tmp_path, folder, "1", "--cfc", "60",
                                    "--trim", "0,0.1", "--resample", "2e-4")
    assert np.array_equal(processed.time, time)
    assert np.array_equal(processed.data, data)


def test_contact_window():
    # independent check: |F| first reaches 5 % of the peak at 2 and last is
    # at or above 2 % at 5 (the hysteresis keeps the dip at 4 inside)
    assert bumpsim.contact_window([0.0, 0.0, 1.0, 10.0, 0.5, 3.0, 0.1, 0.0]) == (2, 5)
    assert bumpsim.contact_window(-np.array([0.0, 0.0, 1.0, 10.0, 0.5, 3.0, 0.1, 0.0])) == (2, 5)
    with pytest.raises(bumpsim.InputError, match="zero everywhere"):
        bumpsim.contact_window(np.zeros(5))
    with pytest.raises(bumpsim.InputError, match="fall <= rise"):
        bumpsim.contact_window(np.ones(5), rise=0.01, fall=0.5)


def test_iso18571_rating_of_a_late_low_pulse():
    """The ISO/TS 18571 rating: identical signals rate 1; a late, low copy of
    a half-sine pulse rates below 1 in phase, magnitude and slope, and equals
    pyisomme's reference (objective_rating_metrics) within 1e-6 when present."""
    t = np.arange(1500) * 1e-4
    pulse = lambda delay, peak: np.where(  # noqa: E731
        (t >= delay) & (t < delay + 0.08), peak * np.sin(np.pi * (t - delay) / 0.08), 0.0
    )
    test, model = pulse(0.01, -300.0), pulse(0.013, -255.0)
    assert bumpsim.iso18571(test, test, 1e-4)["overall"] == 1.0
    rating = bumpsim.iso18571(test, model, 1e-4)
    assert set(rating) == {"overall", "corridor", "phase", "magnitude", "slope"}
    assert rating["phase"] < 1 and rating["magnitude"] < 1 and rating["slope"] < 1
    reference = pytest.importorskip("objective_rating_metrics.rating")
    iso = reference.ISO18571(np.vstack((t, test)).T, np.vstack((t, model)).T)
    assert rating["overall"] == pytest.approx(iso.overall_rating(ndigits=-1), abs=1e-6)
    assert rating["slope"] == pytest.approx(iso.slope_rating(ndigits=-1), abs=1e-6)
    with pytest.raises(bumpsim.InputError, match="finite"):
        bumpsim.iso18571(test, np.full_like(test, np.nan), 1e-4)
