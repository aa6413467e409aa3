"""Every blending method against `chasles blend` on the same cases; matrices and dual
quaternions; options; batches, dtypes and bad weights."""

import json

import numpy as np
import pytest

import chasles
from conftest import unit_quats

METHODS = ["lin", "dec", "log", "log-iter", "qlb", "sclerp", "dlb", "dib"]


def random_dqs(rng, *shape, spread=1.0):
    q = unit_quats(rng, *shape)
    t = rng.normal(size=(*shape, 3)) * spread
    return chasles.dq_from_rt(q, t)


@pytest.mark.parametrize("method", METHODS)
def test_every_method_equals_the_cli(method, cli, tmp_path, rng):
    n = 2 if method == "sclerp" else 3
    x = random_dqs(rng, 12, n)
    w = rng.uniform(0.1, 1.0, size=(12, n))
    opts = {"center": [0.5, -1.0, 2.0]} if method in ("dec", "qlb") else {}
    cases = [
        {"transforms": [{"dq": list(d)} for d in xi], "weights": list(wi), **opts}
        for xi, wi in zip(x, w)
    ]
    path = tmp_path / "cases.json"
    path.write_text(json.dumps(cases))
    out = json.loads(cli("blend", "--method", method, "--input", path))
    theirs = np.array([o["dq"] for o in out])
    ours, rigid, iters = chasles.blend(x, w, method, full_output=True, **opts)
    assert ours.shape == (12, 8)
    assert np.abs(ours - theirs).max() < 1e-12, method
    assert list(rigid) == [o["rigid"] for o in out]
    assert list(iters) == [o.get("iterations", -1) for o in out]
    # The same transforms as matrices: the CLI's matrices.
    m = chasles.dq_to_matrix(x)
    mats = chasles.blend(m, w, method, **opts)
    assert mats.shape == (12, 4, 4)
    assert np.abs(mats - np.array([o["matrix"] for o in out])).max() < 1e-9, method


def test_sclerp_equals_the_cli_form(cli, tmp_path, rng):
    a, b = random_dqs(rng, 10), random_dqs(rng, 10)
    t = rng.uniform(size=10)
    cases = [{"from": {"dq": list(p)}, "to": {"dq": list(q)}, "t": s} for p, q, s in zip(a, b, t)]
    path = tmp_path / "sclerp.json"
    path.write_text(json.dumps(cases))
    theirs = np.array([o["dq"] for o in json.loads(cli("blend", "--method", "sclerp", "--input", path))])
    assert np.abs(chasles.sclerp(a, b, t) - theirs).max() < 1e-12
    assert np.abs(chasles.blend(np.stack([a, b], axis=1), np.stack([1 - t, t], axis=1), "sclerp") - theirs).max() < 1e-12


def test_options_reach_the_library(cli, tmp_path, rng):
    x = random_dqs(rng, 4, spread=3.0)
    w = [0.1, 0.2, 0.3, 0.4]
    case = {"transforms": [{"dq": list(d)} for d in x], "weights": w, "precision": 1e-3, "max_iterations": 2}
    path = tmp_path / "case.json"
    path.write_text(json.dumps(case))
    out = json.loads(cli("blend", "--method", "dib", "--input", path))[0]
    d, _, it = chasles.blend(x, w, "dib", precision=1e-3, max_iterations=2, full_output=True)
    assert np.abs(d - out["dq"]).max() < 1e-12 and it == out["iterations"]


def test_batches_broadcast_and_keep_dtypes(rng):
    x = random_dqs(rng, 5, 4)
    w = rng.uniform(size=4)
    b = chasles.blend(x, w)
    for i in range(5):
        assert np.array_equal(b[i], chasles.blend(x[i], w))
    b32 = chasles.blend(x.astype(np.float32), w.astype(np.float32), "dib")
    assert b32.dtype == np.float32 and b32.shape == (5, 8)
    # Weights scale to sum to 1.
    assert np.array_equal(chasles.blend(x, 2 * w), chasles.blend(x, w)) or np.abs(chasles.blend(x, 2 * w) - b).max() < 1e-15
    # Many transforms (past the stack buffer) and one.
    many = random_dqs(rng, 40)
    assert np.abs(chasles.blend(many, np.ones(40)) - chasles.blend(many, np.ones(40), "dib", max_iterations=0)).max() < 1e-12
    assert np.abs(chasles.blend(many[:1], [1.0]) - many[0]).max() < 1e-15


def test_bad_weights_and_shapes_raise_value_error(rng):
    x = random_dqs(rng, 3)
    with pytest.raises(ValueError, match="weight 1 is -1: weights must be finite and non-negative"):
        chasles.blend(x, [1.0, -1.0, 1.0])
    with pytest.raises(ValueError, match="weight 0 is NaN"):
        chasles.blend(x, [np.nan, 1.0, 1.0], "dib")
    with pytest.raises(ValueError, match="the weights sum to 0"):
        chasles.blend(x, [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="at index \\(1,\\): the weights sum to 0"):
        chasles.blend(x, [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]])
    with pytest.raises(ValueError, match="ScLERP blends exactly two transforms, got 3"):
        chasles.blend(x, [1.0, 1.0, 1.0], "sclerp")
    with pytest.raises(ValueError, match="unknown method 'avg'"):
        chasles.blend(x, [1.0, 1.0, 1.0], "avg")
    with pytest.raises(ValueError, match=r"weights must have shape \(\.\.\., 3\), got \(2,\)"):
        chasles.blend(x, [1.0, 1.0])
    with pytest.raises(ValueError, match=r"transforms must have shape \(\.\.\., n, 8\)"):
        chasles.blend(np.ones((3, 7)), [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="not a rigid"):
        chasles.blend(np.stack([np.eye(4), 2 * np.eye(4)]), [1.0, 1.0], "lin")
    with pytest.raises(ValueError, match="max_iterations must be at most 10000"):
        chasles.blend(x, [1.0, 1.0, 1.0], "dib", max_iterations=10**5)
    with pytest.raises(ValueError, match="precision must be positive"):
        chasles.blend(x, [1.0, 1.0, 1.0], "dib", precision=0.0)
    with pytest.raises(ValueError, match="zero length"):
        chasles.sclerp(np.zeros(8), x[0], 0.5)


@pytest.mark.parametrize("n", [1, 2, 3, 4, 5, 8, 9])
@pytest.mark.parametrize("dtype", [np.float32, np.float64])
def test_dlb_batches_are_the_same_in_every_build_and_layout(rng, n, dtype):
    # DLB of up to 8 transforms runs through the library's dlb_batch (dlb bit for bit); the
    # AVX2 and baseline builds, scalar-last order, full_output, broadcast weights and one
    # blend at a time all give the same bits.
    from test_convert import both_builds

    x = random_dqs(rng, 3001, n).astype(dtype)
    x[::7] *= -1
    w = rng.uniform(0.0, 1.0, size=(3001, n)).astype(dtype)
    w[:, 0] += 0.01
    wide, base = both_builds(chasles.blend, x, w, "dlb")
    assert wide.dtype == dtype and wide.shape == (3001, 8)
    assert np.array_equal(wide, base)
    assert np.array_equal(chasles.blend(x[2999], w[2999], "dlb"), wide[2999])
    b, rigid, iters = chasles.blend(x, w, "dlb", full_output=True)
    assert np.array_equal(b, wide) and rigid.all() and (iters == -1).all()
    xyzw = np.concatenate([np.roll(x[..., :4], -1, axis=-1), np.roll(x[..., 4:], -1, axis=-1)], axis=-1)
    sl = chasles.blend(xyzw, w, "dlb", scalar_first=False)
    assert np.array_equal(np.concatenate([np.roll(sl[:, :4], 1, axis=-1), np.roll(sl[:, 4:], 1, axis=-1)], axis=-1), wide)
    same = chasles.blend(x, w[0], "dlb")
    assert np.array_equal(same[5], chasles.blend(x[5], w[0], "dlb"))
    if dtype == np.float64:
        # A real value: the numpy DLB of bench/bench.py (the same antipodality fix).
        s = w / w.sum(axis=1, keepdims=True)
        pivot = x[np.arange(3001), np.argmax(s, axis=1), :4]
        s = np.where(np.einsum("nkj,nj->nk", x[..., :4], pivot) < 0, -s, s)
        sb = np.einsum("nk,nkj->nj", s, x)
        r = sb[:, :4] / np.linalg.norm(sb[:, :4], axis=1, keepdims=True)
        d = sb[:, 4:] / np.linalg.norm(sb[:, :4], axis=1, keepdims=True)
        d = d - r * np.sum(r * d, axis=1, keepdims=True)
        assert np.abs(wide - np.concatenate([r, d], axis=1)).max() < 1e-12


def test_dlb_batches_report_the_first_bad_blend(rng):
    x = random_dqs(rng, 20000, 4)
    w = rng.uniform(0.1, 1.0, size=(20000, 4))
    w[12345, 2] = -1.0
    w[19000] = 0.0
    with pytest.raises(ValueError, match=r"at index \(12345,\): weight 2 is -1"):
        chasles.blend(x, w, "dlb")
    w[12345, 2] = 1.0
    with pytest.raises(ValueError, match=r"at index \(19000,\): the weights sum to 0"):
        chasles.blend(x, w, "dlb", scalar_first=False, full_output=True)
    w[19000] = 1.0
    x[15000, 1, 5] = np.inf
    with pytest.raises(ValueError, match=r"at index \(15000,\): dual quaternion is not finite"):
        chasles.blend(x, w, "dlb")
    # Finite input whose blend is not: the real part's norm tiny, the dual part huge.
    x[15000, 1, 5] = 0.0
    x[16000] = [1e-150, 0, 0, 0, 1e300, 0, 0, 0]
    with pytest.raises(ValueError, match=r"at index \(16000,\): the blend \(the input is beyond"):
        chasles.blend(x, w, "dlb")
    with pytest.raises(ValueError, match=r"at index \(16000,\): the blend \(the input is beyond"):
        chasles.blend(x, w, "dlb", full_output=True)
