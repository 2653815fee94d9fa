# Shared fixtures and helpers of the Python tests.
import os

import numpy as np
import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


@pytest.fixture
def rng():
    return np.random.default_rng(20261123)


def rel_err(got, want):
    """Relative error, equal infinities/NaNs exact, zero reference absolute."""
    got, want = float(got), float(want)
    if got == want or (np.isnan(got) and np.isnan(want)):
        return 0.0
    if not (np.isfinite(got) and np.isfinite(want)):
        return np.inf
    return abs(got - want) / abs(want) if want != 0 else abs(got)
