"""Slerp against scipy to 1e-12; every method of `chasles interp` against the CLI on the
same keys; batches, dtypes and bad inputs."""

import json

import numpy as np
import pytest

import chasles
from conftest import same_rotation, unit_quats

transform = pytest.importorskip("scipy.spatial.transform")
Rotation, Slerp = transform.Rotation, transform.Slerp


def test_slerp_agrees_with_scipy(rng):
    t = np.linspace(0.0, 1.0, 17)
    q0, q1 = unit_quats(rng, 60), unit_quats(rng, 60)
    ours = chasles.slerp(q0[:, None], q1[:, None], t)
    assert ours.shape == (60, 17, 4)
    for i in range(60):
        r = Rotation.from_quat(np.stack([q0[i], q1[i]]), scalar_first=True)
        theirs = Slerp([0.0, 1.0], r)(t).as_quat(scalar_first=True)
        assert same_rotation(ours[i], theirs) < 1e-12
    # Nearly equal keys: exact, no 0/0.
    a = chasles.quat_from_axis_angle([1.0, 2.0, 3.0], 1e-9)
    assert np.abs(chasles.slerp([1, 0, 0, 0], a, 0.5) - chasles.quat_from_axis_angle([1.0, 2.0, 3.0], 5e-10)).max() < 1e-16


def test_slerp_long_way_and_extrapolation():
    q1 = chasles.quat_from_axis_angle([0, 0, 1], np.pi / 2)
    short = chasles.slerp([1, 0, 0, 0], -q1, 0.5)
    along = chasles.slerp([1, 0, 0, 0], -q1, 0.5, shortest=False)
    assert np.degrees(chasles.quat_angle([1, 0, 0, 0], short)) == pytest.approx(45.0, abs=1e-9)
    assert np.degrees(chasles.quat_angle([1, 0, 0, 0], along)) == pytest.approx(135.0, abs=1e-9)
    far = chasles.slerp([1, 0, 0, 0], q1, 2.0)
    assert np.degrees(chasles.quat_angle([1, 0, 0, 0], far)) == pytest.approx(180.0, abs=1e-9)


PIECEWISE = ["lineuler", "linmat", "lerp", "slerp", "squad", "tcb", "catmull-rom", "bezier", "c2"]
SPRING = {"spring", "slerpsvupti", "squadsvupti", "justdoit"}
DESCENT = dict(iterations=[15, 15, 15], levels=[17, 30, 60], key_weight=1.2)
CASES = [(m, {}) for m in PIECEWISE] + [
    ("tcb", dict(tension=0.3, continuity=-0.2, bias=0.1)),
    ("spring", {}),  # the converged solver, spring's default
    ("spring", dict(width="angle", key_weight=1.5, tolerance=1e-9)),
    ("spring", dict(solver="report", **DESCENT)),
    ("justdoit", DESCENT),
    ("slerpsvupti", dict(levels=[60], iterations=[15], key_weight=1.2)),
    ("squadsvupti", dict(levels=[60], iterations=[15], solver="report")),
    ("squadsvupti", dict(solver="converged", start="squad")),
]


def flags(kw):
    """The keywords of chasles.interpolate as chasles interp's flags."""
    out = []
    for k, v in kw.items():
        out += ["--" + k.replace("_", "-"), ",".join(map(str, v)) if isinstance(v, list) else str(v)]
    return out


@pytest.mark.parametrize("method,kw", CASES, ids=[f"{m}-{'-'.join(kw) or 'default'}" for m, kw in CASES])
def test_every_method_equals_the_cli(method, kw, cli, tmp_path, rng):
    keys = unit_quats(rng, 5)
    keyfile = tmp_path / "keys.json"
    keyfile.write_text(json.dumps({"keys": [{"quat": list(k)} for k in keys]}))
    frames = 60
    cli("interp", "--method", method, "--keys", keyfile, "--frames", frames, "--out", tmp_path / "out.json", *flags(kw))
    rows = json.loads((tmp_path / "out.json").read_text())
    theirs = np.array([[r["w"], r["x"], r["y"], r["z"]] for r in rows])
    q, t, key = chasles.interpolate(keys, method, frames, full_output=True, **kw)
    assert q.shape == (frames, 4)
    # Bit for bit: the key file's numbers are read back exactly (serde_json's
    # float_roundtrip), so even the converged Spring stops at the same step.
    assert np.array_equal(q, theirs), (method, np.abs(q - theirs).max())
    assert np.array_equal(t, [r["t"] for r in rows])
    assert list(key) == [-1 if r["key"] is None else r["key"] for r in rows]
    if method == "squad":
        assert np.array_equal(chasles.squad(keys, frames), q)
    if method in SPRING:
        assert np.array_equal(chasles.spring(keys, frames, preset=method, **kw), q)


def test_a_camera_path_keeps_its_horizon(cli, tmp_path, rng):
    # Cameras looking along x with z up and no roll: yaw and pitch only (intrinsic ZYX).
    yaw_pitch = np.column_stack([rng.uniform(-3, 3, 6), rng.uniform(-1.2, 1.2, 6), np.zeros(6)])
    keys = chasles.quat_from_euler(yaw_pitch, "ZYX")
    keyfile = tmp_path / "keys.json"
    keyfile.write_text(json.dumps({"keys": [{"quat": list(k)} for k in keys]}))
    for method in ["squad", "spring", "c2"]:
        q = chasles.interpolate(keys, method, 80, horizon="Z")
        roll = chasles.quat_to_euler(q, "ZYX")[:, 2]
        assert np.abs(roll).max() < 1e-12, method
        unlevelled = chasles.quat_to_euler(chasles.interpolate(keys, method, 80), "ZYX")[:, 2]
        assert np.abs(unlevelled).max() > 1e-3, method
        cli("interp", "--method", method, "--keys", keyfile, "--frames", 80, "--horizon", "Z", "--out", tmp_path / "out.json")
        rows = json.loads((tmp_path / "out.json").read_text())
        assert np.abs(q - [[r["w"], r["x"], r["y"], r["z"]] for r in rows]).max() < 1e-12
    rolled = chasles.quat_from_euler([[0, 0, 0], [1.0, 0.2, 0.3]], "ZYX")
    with pytest.raises(ValueError, match="roll"):
        chasles.interpolate(rolled, "slerp", 10, horizon="Z")
    with pytest.raises(ValueError, match="horizon must be 'Z' or 'Y'"):
        chasles.interpolate(keys, "slerp", 10, horizon="X")


def test_tcb_parameters_and_spring_solvers_are_checked(rng):
    keys = unit_quats(rng, 4)
    # Tension, continuity and bias at 0 are Catmull-Rom.
    assert np.abs(chasles.interpolate(keys, "tcb", 30) - chasles.interpolate(keys, "catmull-rom", 30)).max() < 1e-14
    with pytest.raises(ValueError, match=r"tension must be a finite number in \[-1, 1\], got 2"):
        chasles.interpolate(keys, "tcb", 30, tension=2.0)
    with pytest.raises(ValueError, match="bias is a Kochanek-Bartels control: it applies to tcb, not slerp"):
        chasles.interpolate(keys, "slerp", 30, bias=0.5)
    with pytest.raises(ValueError, match="iterations is a control of the report's gradient descent"):
        chasles.spring(keys, 30, iterations=[5, 5, 5])
    with pytest.raises(ValueError, match="tolerance is a control of the converged solver"):
        chasles.spring(keys, 30, preset="justdoit", tolerance=1e-8)
    with pytest.raises(ValueError, match="unknown solver 'newton'"):
        chasles.spring(keys, 30, solver="newton")
    with pytest.raises(ValueError, match="tolerance"):
        chasles.spring(keys, 30, tolerance=2.0)
    with pytest.raises(ValueError, match="unknown method 'nurbs'.*catmull-rom, bezier or c2"):
        chasles.interpolate(keys, "nurbs", 30)


def test_times_timing_and_batches(rng):
    keys = unit_quats(rng, 3, 4)
    batch = chasles.interpolate(keys, "squad", 30, timing="uniform", times=[0.0, 1.0, 3.0, 4.0])
    for i in range(3):
        one = chasles.interpolate(keys[i], "squad", 30, timing="uniform", times=[0.0, 1.0, 3.0, 4.0])
        assert np.array_equal(batch[i], one)
    _, t, key = chasles.interpolate(keys[0], "slerp", 13, timing="uniform", times=[0.0, 1.0, 3.0, 4.0], full_output=True)
    assert t[0] == 0.0 and t[-1] == 4.0 and list(key[key >= 0]) == [0, 1, 2, 3]
    s32 = chasles.spring(keys.astype(np.float32), 20, solver="report", iterations=[5, 5, 5])
    assert s32.dtype == np.float32 and s32.shape == (3, 20, 4)


def test_bad_curves_raise_value_error(rng):
    keys = unit_quats(rng, 4)
    with pytest.raises(ValueError, match="at least 2 key frames"):
        chasles.squad(keys[:1], 10)
    with pytest.raises(ValueError, match="3 frames cannot hold 4 key frames"):
        chasles.interpolate(keys, "slerp", 3)
    with pytest.raises(ValueError, match="key frame 1: quaternion has zero length"):
        chasles.squad(np.array([keys[0], [0, 0, 0, 0], keys[1]]), 10)
    with pytest.raises(ValueError, match="step is a Spring control"):
        chasles.interpolate(keys, "slerp", 20, step="fixed:0.1")
    with pytest.raises(ValueError, match="unknown step rule 'slow'"):
        chasles.spring(keys, 20, solver="report", step="slow:0.1")
    with pytest.raises(ValueError, match="levels ends at 30 frames but frames is 20"):
        chasles.spring(keys, 20, solver="report", levels=[13, 30], iterations=[1, 1])
    with pytest.raises(ValueError, match="unknown method 'cubic'"):
        chasles.interpolate(keys, "cubic")
    with pytest.raises(ValueError, match="timing must be"):
        chasles.squad(keys, 20, timing="fast")
    with pytest.raises(ValueError, match="more than max_frames"):
        chasles.squad(keys, 10**7)
    with pytest.raises(ValueError, match=r"keys must have shape \(\.\.\., K, 4\)"):
        chasles.squad(np.ones((4, 3)), 10)
    with pytest.raises(ValueError, match="key time 2"):
        chasles.interpolate(keys, "slerp", 20, timing="uniform", times=[0, 1, 1, 2])
    with pytest.raises(ValueError, match=r"times must have shape \(\.\.\., 4\)"):
        chasles.interpolate(keys, "slerp", 20, times=[0, 1, 2])
