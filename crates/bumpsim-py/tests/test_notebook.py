"""examples/python/identify.ipynb runs headless (nbclient, the venv's own
kernel) and produces its figure; the notebook file is left as committed."""

import nbformat
import pytest
from nbclient import NotebookClient


def test_identify_notebook_runs_and_draws_its_figure(root):
    path = root / "examples" / "python" / "identify.ipynb"
    notebook = nbformat.read(path, as_version=4)
    client = NotebookClient(
        notebook, timeout=600, kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
    )
    client.execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    figures = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(figures) == 1, "the notebook draws one matplotlib figure"
    text = "".join(o.get("text", "") for o in outputs if o.output_type == "stream")
    assert "overall fit" in text and "m1 =" in text
