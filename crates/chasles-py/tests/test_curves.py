"""`chasles interp --method c2` (the CLI's C² spline) against SciPy's RotationSpline, which
builds the same curve: cubic rotation vectors with continuous angular rate and acceleration,
end rates clamped to the chords'. Needs only the CLI and SciPy, not the Python package."""

import json

import numpy as np
import pytest

from conftest import same_rotation, unit_quats

transform = pytest.importorskip("scipy.spatial.transform")
Rotation, RotationSpline = transform.Rotation, transform.RotationSpline


@pytest.mark.parametrize("n", [3, 5, 8])
def test_c2_spline_agrees_with_scipy(cli, tmp_path, rng, n):
    keys = unit_quats(rng, n)
    # Keys within 100° of each other (SciPy stops its iteration after 10 steps at 1e-9:
    # with turns near 180° between keys it has not settled yet).
    for i in range(1, n):
        step = Rotation.from_rotvec(rng.normal(size=3) * 0.6)
        keys[i] = (Rotation.from_quat(np.roll(keys[i - 1], -1)) * step).as_quat()[[3, 0, 1, 2]]
    times = np.cumsum(np.concatenate([[0.2], rng.uniform(0.3, 2.0, n - 1)]))
    keyfile = tmp_path / "keys.json"
    keyfile.write_text(json.dumps([{"quat": list(k), "time": float(t)} for k, t in zip(keys, times)]))
    out = tmp_path / "out.json"
    cli("interp", "--method", "c2", "--keys", keyfile, "--frames", 200, "--timing", "uniform", "--out", out)
    rows = json.loads(out.read_text())
    t = np.array([r["t"] for r in rows])
    ours = np.array([[r["w"], r["x"], r["y"], r["z"]] for r in rows])
    spline = RotationSpline(times, Rotation.from_quat(np.roll(keys, -1, axis=1)))
    theirs = np.roll(spline(t).as_quat(), 1, axis=1)
    assert same_rotation(ours, theirs) < 1e-9
