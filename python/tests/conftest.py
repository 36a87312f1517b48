"""Shared fixtures of the Python module's tests: the repository root, the command line (DEM2D_EXE, set by
ctest), a scratch folder. `import dem2d` comes from PYTHONPATH=build/python (python/CMakeLists.txt)."""
import os
import pathlib
import shutil

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def exe():
    path = os.environ.get("DEM2D_EXE") or str(ROOT / "build" / "app" / "dem2d")
    assert os.path.exists(path), f"the command line {path} is not built (DEM2D_EXE)"
    return path


@pytest.fixture
def scratch(request):
    """A folder of this test's own under build/ (DEM2D_TMP), emptied first."""
    base = pathlib.Path(os.environ.get("DEM2D_TMP") or ROOT / "build" / "python" / "tmp")
    d = base / request.node.name
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    return d


def write_case(folder, name, source, replace=None, append=""):
    """A copy of a case file with one text planted (replace = (old, new)) or appended."""
    text = pathlib.Path(source).read_text()
    if replace:
        assert replace[0] in text, f"{replace[0]!r} is not in {source}"
        text = text.replace(replace[0], replace[1], 1)
    path = pathlib.Path(folder) / name
    path.write_text(text + append)
    return path
