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
