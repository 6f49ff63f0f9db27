"""Shared fixtures of walkgen's Python tests (run by the ctest python_tests, label python)."""

import os
import pathlib

import pytest


@pytest.fixture
def source_dir():
    """The repository root (WALKGEN_SOURCE_DIR from ctest, else found from this file)."""
    return pathlib.Path(os.environ.get("WALKGEN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
