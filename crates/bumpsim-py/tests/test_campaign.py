"""Issue 38: the campaign API (init, run, status, collect, abort) on
bumpsim-campaign, the CLI's library: a campaign run from Python writes the
table the CLI writes, byte for byte. The solver is a shell script copying its
input (a campaign of 4 points runs in about a second)."""

import json
import pickle

import pytest

import bumpsim

SPEC = """name = "fake"
[design]
kind = "full"
factors = [{{ name = "a", low = 1, high = 2, unit = "m" }}, {{ name = "b", low = 0, high = 1, unit = "m" }}]
centre = 1
[derived]
y = "2 * a + b"
[template]
file = "in.tmpl"
deck = "in.csv"
[solver]
command = ["{solver}"]
[[response]]
name = "y_max"
reader = "csv"
file = "out.csv"
quantity = "y"
unit = "m"
[executor]
kind = "local"
slots = 2
retries = 0
poll_seconds = 0.1
"""


def spec(folder):
    """The campaign file of a 2² design + centre whose solver copies its input."""
    folder.mkdir()
    solver = folder / "solver.sh"
    solver.write_text("#!/bin/sh\ncp in.csv out.csv\n")
    solver.chmod(0o755)
    (folder / "in.tmpl").write_text("time [s],y [m]\n0,0\n1,{{y}}\n")
    path = folder / "campaign.toml"
    path.write_text(SPEC.format(solver=solver))
    return path


def test_a_campaign_from_python_gives_the_cli_table(run, tmp_path):
    cli_spec = spec(tmp_path / "cli")
    run("campaign", "init", cli_spec, "-o", tmp_path / "cli" / "c")
    run("campaign", "run", tmp_path / "cli" / "c")
    run("campaign", "collect", tmp_path / "cli" / "c")
    cli_status = json.loads(run("campaign", "status", tmp_path / "cli" / "c", "--json"))

    campaign = bumpsim.Campaign.init(spec(tmp_path / "py"), tmp_path / "py" / "c")
    assert campaign.folder == tmp_path / "py" / "c"
    before = campaign.status()
    assert before.counts["pending"] == 5 and before.points == 5
    summary = campaign.run()
    assert summary["done"] == 5 and summary["failed"] == []
    status = campaign.status()
    assert status.counts == cli_status["counts"] and status.campaign == "fake"
    assert [r["status"] for r in status.runs] == [r["status"] for r in cli_status["runs"]]
    collected = campaign.collect()

    theirs = (tmp_path / "cli" / "c" / "results" / "table.csv").read_bytes()
    ours = (tmp_path / "py" / "c" / "results" / "table.csv").read_bytes()
    assert ours == theirs
    assert collected.table.encode() == theirs
    assert collected.rows == 5 and collected.missing == []
    frame = collected.to_pandas() if _pandas() else None
    if frame is not None:
        assert frame.index.name == "run" and "y_max [m]" in frame.columns
        assert list(frame["y_max [m]"]) == [2 * a + b for a, b in zip(frame["a [m]"], frame["b [m]"])]
        assert status.to_pandas().index.name == "run"
    assert campaign.abort() == 0
    for x in (campaign, status, collected):
        assert pickle.loads(pickle.dumps(x)) == x
        assert repr(x).startswith(type(x).__name__ + "(")


def test_campaign_errors_are_python_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        bumpsim.Campaign(tmp_path / "nothing").status()
    bad = tmp_path / "bad.toml"
    bad.write_text("name = 'x'\n[design]\nkind = 'full'\n")
    with pytest.raises(ValueError, match="bad.toml"):
        bumpsim.Campaign.init(bad)
    path = spec(tmp_path / "c")
    with pytest.raises(ValueError, match="slots"):
        bumpsim.Campaign.init(path).run(slots=-1)


def _pandas():
    try:
        import pandas  # noqa: F401
    except ImportError:
        return False
    return True
