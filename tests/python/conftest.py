"""Shared fixtures of the Python suite: where the test data and the CLI are (set by ctest)."""
import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("COULOMB_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
DATA_DIR = pathlib.Path(os.environ.get("COULOMB_TEST_DATA_DIR", SOURCE_DIR / "tests" / "data"))


@pytest.fixture
def data_dir():
    return DATA_DIR


@pytest.fixture
def fc3d_files():
    """The small Siconos problems of tests/data/fc3d (origin in its ORIGIN.md)."""
    return sorted((DATA_DIR / "fc3d").glob("*.fc3d"))


@pytest.fixture
def cli():
    path = os.environ.get("COULOMB_CLI", str(SOURCE_DIR / "build" / "bin" / "coulomb"))
    assert os.path.exists(path), f"the coulomb CLI is not built at {path}"
    return path
