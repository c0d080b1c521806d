"""The type stubs (__init__.pyi) describe exactly the module's public names,
and the package ships them with py.typed (PEP 561)."""

import ast
from pathlib import Path

import bumpsim


def stub_names(path: Path) -> set:
    tree = ast.parse(path.read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.ClassDef, ast.FunctionDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    return names


def test_stubs_cover_the_module_and_ship_with_the_package():
    folder = Path(bumpsim.__file__).parent
    assert (folder / "py.typed").is_file()
    stubs = stub_names(folder / "__init__.pyi")
    public = {n for n in dir(bumpsim._native) if not n.startswith("_")}
    assert public <= stubs, f"missing from the stubs: {sorted(public - stubs)}"
    assert stubs - {"__version__"} <= public, f"stubs of nothing: {sorted(stubs - public)}"


def test_classes_have_their_members_in_the_stubs():
    folder = Path(bumpsim.__file__).parent
    tree = ast.parse((folder / "__init__.pyi").read_text())
    for node in tree.body:
        if not isinstance(node, ast.ClassDef) or issubclass(getattr(bumpsim, node.name), Exception):
            continue
        stubbed = {
            n.name if isinstance(n, ast.FunctionDef) else n.target.id
            for n in node.body
            if isinstance(n, (ast.FunctionDef, ast.AnnAssign))
        }
        actual = {n for n in dir(getattr(bumpsim, node.name)) if not n.startswith("_")}
        assert actual <= stubbed, f"{node.name}: missing from the stubs: {sorted(actual - stubbed)}"


def test_mypy_strict_accepts_a_script_using_the_stubs(tmp_path):
    # the typed API of issue 38: paths for cars, DOF ranges, pandas frames,
    # campaigns, exceptions on Python's bases
    import subprocess
    import sys

    import pytest

    pytest.importorskip("mypy", reason="mypy is in requirements-test.txt")
    script = tmp_path / "use.py"
    script.write_text(
        "import pickle\n"
        "import numpy as np\n"
        "import bumpsim\n"
        "car = bumpsim.Car([1.0, 2.0], [3.0], [4.0])\n"
        "r = bumpsim.simulate('car.toml', np.arange(3) * 1.0, [0.0, 1.0, 0.0])\n"
        "frame = r.to_pandas()\n"
        "table = bumpsim.dof_table('study.toml', dofs='1..3')\n"
        "n: int = len(table)\n"
        "status: bumpsim.CampaignStatus = bumpsim.Campaign.init('c.toml').status()\n"
        "text: str = bumpsim.Campaign('c').collect().table\n"
        "try:\n"
        "    bumpsim.identify('s.toml', dof=0)\n"
        "except ValueError as e:\n"
        "    print(e)\n"
        "except FileNotFoundError as e:\n"
        "    print(e.filename)\n"
        "assert pickle.loads(pickle.dumps(car)) == car\n"
        "bad: str = car.dof\n"
    )
    done = subprocess.run(
        [sys.executable, "-m", "mypy", "--strict", "--cache-dir", str(tmp_path / "cache"), str(script)],
        capture_output=True, text=True,
    )
    # exactly the one planted error: the stubs type everything else
    assert "Found 1 error" in done.stdout, done.stdout + done.stderr
    assert 'use.py:18: error: Incompatible types in assignment (expression has type "int"' in done.stdout
