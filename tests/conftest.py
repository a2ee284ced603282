"""Shared fixtures and hypothesis settings."""

import math
import os

import pytest
from hypothesis import HealthCheck, settings

from ballcvt import Variator, load_builtin

# The default suite is reproducible: the same examples on every run and every machine,
# so CI fails only when the code changes. "thorough" draws new random examples.
settings.register_profile("default", max_examples=25, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("thorough", max_examples=300, deadline=None,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "default"))

RPM = math.pi / 30.0


@pytest.fixture(autouse=True)
def _slow_only_when_asked(request):
    """A test marked ``slow`` runs only under ``-m slow`` (pyproject.toml's marker)."""
    if request.node.get_closest_marker("slow") and "slow" not in (
        request.config.getoption("markexpr") or ""
    ):
        pytest.skip("slow: run with -m slow")


#: The paper's operating point of Figs. 7, 9-13.
PAPER = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


@pytest.fixture(scope="session")
def drive():
    return load_builtin()


@pytest.fixture(scope="session")
def double():
    return Variator(architecture="double")


@pytest.fixture(scope="session")
def single():
    return Variator(architecture="single")
