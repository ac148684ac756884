"""Shared fixtures of the stljit pytest suite: paths to the example and test programs."""

from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[2]
PROGRAMS = HERE / "programs"
EXAMPLES = REPO / "examples"


@pytest.fixture(params=["jit", "interp"])
def engine(request: pytest.FixtureRequest) -> str:
    """Every test that takes ``engine`` runs on both engines."""
    return request.param
