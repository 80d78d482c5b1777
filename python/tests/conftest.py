"""Shared fixtures: the module under test, its small scene, and the `mane` program to compare with."""

import os
import pathlib
import shutil

import pytest

HERE = pathlib.Path(__file__).resolve().parent


@pytest.fixture(scope="session")
def hair_ball():
    """A procedural ball with 64 guide strands of 16 particles that shakes: no asset files needed."""
    return HERE / "hair_ball.json"


@pytest.fixture(scope="session")
def mane_program():
    """The `mane` executable CTest names in MANE_EXECUTABLE (else the one on PATH)."""
    program = os.environ.get("MANE_EXECUTABLE") or shutil.which("mane")
    if not program or not os.path.exists(program):
        pytest.skip("the mane program is not built (MANE_EXECUTABLE unset)")
    return program
