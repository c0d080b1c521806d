"""Issue 38: docs/python.md runs as written. Every ```python block runs, in
order, in one namespace, in a scratch folder holding the repository's
examples/ (so the files the tour writes land there, not in the checkout)."""

import os
import re


def test_every_python_block_of_the_docs_runs(root, tmp_path, monkeypatch):
    text = (root / "docs" / "python.md").read_text()
    blocks = re.findall(r"^```python\n(.*?)^```", text, flags=re.S | re.M)
    assert len(blocks) >= 6, "the tour's blocks"
    os.symlink(root / "examples", tmp_path / "examples")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__main__"}
    for number, block in enumerate(blocks, 1):
        code = compile(block, f"docs/python.md, python block {number}", "exec")
        exec(code, namespace)
    assert (tmp_path / "result.json").is_file()
    assert (tmp_path / "toy" / "campaign" / "results" / "table.csv").is_file()
