"""Shared fixtures of the prism module's tests (run by CTest: python/CMakeLists.txt).

The `backend` fixture runs a test once per backend found, and once per name
in PRISM_REQUIRE_BACKENDS: as in the C++ tests (tests/support), a backend
that cannot run here is skipped unless it is required, and then it fails.
"""
import functools
import os
import pathlib
import subprocess

import pytest

import prism

SOURCE_DIR = pathlib.Path(os.environ.get("PRISM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BUILD_DIR = pathlib.Path(os.environ.get("PRISM_BUILD_DIR", SOURCE_DIR / "build"))
CLI = os.environ.get("PRISM_CLI", str(BUILD_DIR / "bin" / "prism"))
SHOWCASE = SOURCE_DIR / "scenes" / "showcase.json"

_engine = prism.Engine()


@functools.cache
def found_backends():
    """Every backend found, by name (probing a GPU takes a while: once per process)."""
    return {b.name: b for b in _engine.backends()}


def required_backends():
    names = os.environ.get("PRISM_REQUIRE_BACKENDS", "").split(",")
    return sorted({n.strip() for n in names if n.strip()})


def _backend_names():
    return sorted(set(found_backends()) | set(required_backends()))


def pytest_generate_tests(metafunc):
    if "backend" in metafunc.fixturenames:
        metafunc.parametrize("backend", _backend_names(), indirect=True)


@pytest.fixture(scope="session")
def engine():
    return _engine


@pytest.fixture
def backend(request):
    """A backend's name when it can run here; skips (or fails when required) otherwise."""
    name = request.param
    info = found_backends().get(name)
    why = "is not found" if info is None else None if info.available else info.reason
    if why is None:
        return name
    required = name in required_backends()
    if required or (info is not None and info.reason.startswith("failed to load")):
        pytest.fail(f"backend '{name}' {why}" + (" (it is in PRISM_REQUIRE_BACKENDS)" if required else ""))
    pytest.skip(f"backend '{name}' cannot run here: {why}")


def run_cli(*args):
    """Runs the `prism` command; fails the test with its stderr when it fails."""
    done = subprocess.run([CLI, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, f"prism {' '.join(map(str, args))} exited {done.returncode}:\n{done.stderr}"
    return done.stdout
