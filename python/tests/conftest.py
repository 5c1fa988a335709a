"""Shared fixtures of the package's tests: the checkout's root and a scratch folder."""
import os

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@pytest.fixture
def root():
    """The visco2d checkout these tests belong to."""
    return ROOT
