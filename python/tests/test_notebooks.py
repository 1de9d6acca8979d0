"""examples/notebooks/*.ipynb executed from top to bottom (nbclient, the python3 kernel, matplotlib's inline backend,
which draws with Agg into PNG outputs), so that they never rot: each notebook asserts its numbers against closed
forms, and a failing cell fails here."""
import nbclient  # python3-nbclient, python3-nbformat, python3-ipykernel, python3-matplotlib (scripts/setup-debian.sh)
import nbformat
import pytest

from conftest import SOURCE_DIR

NOTEBOOKS = sorted((SOURCE_DIR / "examples" / "notebooks").glob("*.ipynb"))


def test_there_are_notebooks():
    assert len(NOTEBOOKS) >= 2


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.name)
def test_notebook_runs(path, monkeypatch):
    nb = nbformat.read(path, as_version=4)
    for cell in nb.cells:  # committed without outputs (no build outputs in the repository)
        if cell.cell_type == "code":
            assert cell.outputs == [] and cell.execution_count is None, f"{path.name}: strip the outputs"
    # The kernel inherits the environment (PYTHONPATH: the module); no GUI backend whatever the user's setting.
    monkeypatch.setenv("MPLBACKEND", "module://matplotlib_inline.backend_inline")
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger: no frozen-modules warning
    client = nbclient.NotebookClient(nb, timeout=120, kernel_name="python3",
                                     resources={"metadata": {"path": str(path.parent)}})
    client.execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if o.output_type == "error"]
    assert not errors
    images = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs if "image/png" in o.get("data", {})]
    assert images, f"{path.name} drew no figure"
