"""Shared fixtures: random inputs and the `chasles` command-line tool for cross-checks.

The CLI is found through $CHASLES_BIN, else in the cargo target folder
($CARGO_TARGET_DIR, else the repository's target/) as release/chasles or debug/chasles,
else on PATH. Tests that need it skip, saying how to build it, when it is not there;
.ci/run builds it, so they run in CI.
"""

import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


def find_cli():
    env = os.environ.get("CHASLES_BIN")
    if env:
        return pathlib.Path(env) if pathlib.Path(env).exists() else None
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    for profile in ("release", "debug"):
        p = target / profile / "chasles"
        if p.exists():
            return p
    found = shutil.which("chasles")
    return pathlib.Path(found) if found else None


class Cli:
    """Runs `chasles ARGS…` and returns its standard output."""

    def __init__(self, path):
        self.path = path

    def __call__(self, *args, stdin=None):
        r = subprocess.run(
            [str(self.path), *map(str, args)], input=stdin, capture_output=True, text=True
        )
        if r.returncode != 0:
            raise AssertionError(f"chasles {' '.join(map(str, args))} failed:\n{r.stderr}")
        return r.stdout

    def json(self, *args, stdin=None):
        return json.loads(self(*args, stdin=stdin))


@pytest.fixture(scope="session")
def cli():
    p = find_cli()
    if p is None:
        pytest.skip(
            "the chasles CLI binary was not found: build it with "
            "`cargo build --release -p chasles-cli` (or set CHASLES_BIN)"
        )
    return Cli(p)


@pytest.fixture
def rng():
    return np.random.default_rng(2006)


def unit_quats(rng, *shape):
    q = rng.normal(size=(*shape, 4))
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def same_rotation(a, b):
    """The largest difference between quaternions up to sign, item by item."""
    a, b = np.asarray(a), np.asarray(b)
    d1 = np.abs(a - b).max(axis=-1)
    d2 = np.abs(a + b).max(axis=-1)
    return float(np.minimum(d1, d2).max())
