"""Issue 39 item 2 in Python: the posterior of an identified chain
(bumpsim-ident's ensemble sampler), seeded, with its means, 90 % intervals,
diagnostics and draws as a read-only array and a pandas frame named with the
parameters' units. It is the CLI's (`identify --posterior --json`, same
seed and steps), and holds the library's properties: the intervals contain
the optimum, the same seed gives the same numbers, a posterior pickles whole."""

import json
import pickle

import numpy as np
import pytest

import bumpsim

STEPS = 400  # a quarter burnt: 300 kept steps of 32 walkers, a fraction of a second


@pytest.fixture(scope="module")
def identification():
    """A 2-mass chain identified from a synthetic pulse with a little noise
    (the library's own example, bumpsim_ident::posterior)."""
    truth = bumpsim.Car([30.0, 900.0], [3e3], [6e5])
    t = np.arange(300) * 5e-4
    f = np.maximum(2e4 * np.sin(40.0 * t), 0.0)
    x = bumpsim.simulate(truth, t, f).displacement[0] + 2e-5 * np.sin(1.7 * np.arange(300))
    case = bumpsim.LoadCase("flat", t, f, x)
    return bumpsim.identify_cases([case], dof=2, starts=4, seed=3)


@pytest.fixture(scope="module")
def posterior(identification):
    return identification.posterior(steps=STEPS)


def test_the_90_percent_intervals_contain_the_optimum(identification, posterior):
    optimum = [p["value"] for p in identification.parameters]
    assert posterior.names == ["m1", "m2", "c1", "k1"]
    assert posterior.units == ["kg", "kg", "Ns/m", "N/m"]
    for name, value, (low, high), mean in zip(posterior.names, optimum, posterior.ci90, posterior.mean):
        assert low < value < high, f"{name}: optimum {value} outside the 90 % interval {low} .. {high}"
        assert low < mean < high
    for (low90, high90), (low95, high95) in zip(posterior.ci90, posterior.ci95):
        assert low95 <= low90 < high90 <= high95
    assert posterior.ensemble == {"walkers": 32, "steps": STEPS, "burn": STEPS // 4, "seed": 3}
    assert set(posterior.diagnostics) >= {"autocorrelation_time", "r_hat", "acceptance", "converged"}
    assert posterior.converged == posterior.diagnostics["converged"]
    assert "90 %" in posterior.to_text() and "diagnostics" in posterior.to_text()


def test_the_same_seed_gives_the_same_numbers(identification, posterior):
    again = identification.posterior(steps=STEPS, seed=3)   # the identification's seed is the default
    assert again == posterior
    assert np.array_equal(again.samples, posterior.samples) and again.ci90 == posterior.ci90
    other = identification.posterior(steps=STEPS, seed=4)
    assert other != posterior and other.ci90 != posterior.ci90


def test_the_draws_are_a_read_only_array_and_a_frame_with_units(posterior):
    samples = posterior.samples
    assert samples.shape == (3200, 4) and samples.dtype == np.float64   # 9600 draws thinned by 3
    assert posterior.samples is samples
    with pytest.raises(ValueError, match="read-only"):
        samples[0, 0] = 1.0
    frame = posterior.to_pandas()
    assert list(frame.columns) == ["m1 [kg]", "m2 [kg]", "c1 [Ns/m]", "k1 [N/m]"]
    assert np.array_equal(frame.to_numpy(), samples)
    assert frame.attrs["ensemble"]["seed"] == 3
    # the draws' quantiles are the intervals (numpy's default interpolation)
    low, high = np.quantile(samples[:, 3], [0.05, 0.95])
    assert abs(low / posterior.ci90[3][0] - 1) < 0.01 and abs(high / posterior.ci90[3][1] - 1) < 0.01


def test_the_summary_sits_beside_the_local_intervals(identification, posterior):
    summary = posterior.summary_to_pandas()
    assert list(summary.index) == posterior.names
    assert list(summary["ci90_low"]) == [c[0] for c in posterior.ci90]
    assert list(summary["mean"]) == list(posterior.mean)
    local = [p["ci95"] for p in identification.parameters]
    assert list(summary["local_ci95_low"]) == [c[0] for c in local]
    assert list(summary["unit"]) == posterior.units


def test_pickles_compares_and_prints(posterior):
    copy = pickle.loads(pickle.dumps(posterior))
    assert copy == posterior and type(copy) is bumpsim.Posterior
    assert np.array_equal(copy.samples, posterior.samples)
    assert repr(posterior).startswith("Posterior(dof=2, 32 walkers")


def test_bad_runs_raise_value_errors(identification):
    for kwargs, words in [
        ({"steps": 5}, "steps"),
        ({"steps": -1}, "steps"),
        ({"seed": -1}, "seed"),
        ({"walkers": 1}, "walkers"),
    ]:
        with pytest.raises(ValueError, match=words) as caught:
            identification.posterior(**kwargs)
        assert isinstance(caught.value, bumpsim.InputError)


def test_the_clis_posterior_is_the_same_for_the_same_seed(root, run, tmp_path):
    """`bumpsim identify --posterior --steps N --seed S --json` and
    `identify(..., seed=S).posterior(steps=N)` sample the same chain."""
    study = root / "examples" / "identify" / "study.toml"
    out = tmp_path / "posterior.json"
    run("identify", study, "--dof", "2", "--starts", "4", "--seed", "1", "--posterior", "--steps", "200",
        "--quiet", "--json", out)
    cli = json.loads(out.read_text())["posterior"]
    post = bumpsim.identify(study, dof=2, starts=4, seed=1).posterior(steps=200)
    assert cli["ensemble"] == post.ensemble
    assert cli["mean"] == list(post.mean) and cli["median"] == list(post.median) and cli["sd"] == list(post.sd)
    assert cli["ci90"] == [list(c) for c in post.ci90] and cli["ci95"] == [list(c) for c in post.ci95]
    assert cli["diagnostics"] == post.diagnostics and cli["converged"] == post.converged
    assert cli["units"] == post.units and cli["names"] == post.names
    assert json.loads(post.to_json()) == cli
