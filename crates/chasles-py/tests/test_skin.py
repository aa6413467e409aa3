"""Skinning through Python equals `chasles skin` (CesiumMan, every method, one pose and a
whole clip, bit for bit); users' own arrays; pickling of rigs and poses; bad inputs."""

import json
import pickle

import numpy as np
import pytest

import chasles

SKIN_METHODS = ["lbs", "dqs", "dib", "log", "qlb", "sbs"]


@pytest.fixture(scope="module")
def cesium_path(tmp_path_factory):
    p = tmp_path_factory.mktemp("models") / "CesiumMan.glb"
    p.write_bytes(chasles.model_bytes("CesiumMan"))
    return p


@pytest.fixture(scope="module")
def cesium(cesium_path):
    return chasles.Rig.load(cesium_path)


@pytest.mark.parametrize("method", SKIN_METHODS)
def test_one_pose_equals_the_cli(method, cesium, cesium_path, cli, tmp_path):
    out = tmp_path / "pose.json"
    cli("skin", "--rig", cesium_path, "--anim", "0", "--time", "0.7", "--method", method, "--device", "cpu", "--out", out)
    d = json.loads(out.read_text())
    pos, nrm = cesium.skin(clip=0, time=0.7, method=method)
    assert pos.dtype == np.float32 and pos.shape == (3273, 3)
    assert np.array_equal(pos, np.array(d["positions"], dtype=np.float32))
    assert np.array_equal(nrm, np.array(d["normals"], dtype=np.float32))
    assert np.array_equal(cesium.triangles, np.array(d["triangles"]))


def read_obj(path):
    v, vn = [], []
    for line in path.read_text().splitlines():
        if line.startswith("v "):
            v.append([float(x) for x in line.split()[1:]])
        elif line.startswith("vn "):
            vn.append([float(x) for x in line.split()[1:]])
    return np.array(v, dtype=np.float32), np.array(vn, dtype=np.float32)


@pytest.mark.parametrize("method", ["dqs", "sbs"])
def test_a_whole_clip_equals_the_cli(method, cesium, cesium_path, cli, tmp_path):
    out = tmp_path / "frames"
    cli("skin", "--rig", cesium_path, "--all-frames", "--fps", "24", "--method", method, "--device", "cpu", "--out", out)
    pos, nrm = cesium.skin_clip(0, fps=24, method=method)
    files = sorted(out.glob("frame_*.obj"))
    assert pos.shape == (len(files), 3273, 3) == nrm.shape
    for f, path in enumerate(files):
        p, n = read_obj(path)
        assert np.array_equal(pos[f], p) and np.array_equal(nrm[f], n), (method, f)


def gpu_or_skip(rig):
    try:
        return rig.skinning_device("dqs", "gpu")
    except ValueError as e:
        pytest.skip(f"no GPU adapter (not even Mesa's lavapipe): {e}")


@pytest.mark.parametrize("method", ["lbs", "dqs", "dib"])
def test_the_gpu_skins_as_the_cpu(method, cesium):
    adapter = gpu_or_skip(cesium)
    assert adapter != "cpu"
    cpu, cpu_n = cesium.skin(clip=0, time=0.7, method=method)
    gpu, gpu_n = cesium.skin(clip=0, time=0.7, method=method, device="gpu")
    assert gpu.dtype == np.float32 and gpu.shape == cpu.shape
    # f32 on both, different operation orders (and the GPU's fused multiply-adds): the
    # mesh is about 1.8 units tall, so 1e-5 is a few ulp of its coordinates. DIB: the
    # CPU's SIMD kernel takes a second-order step and the shader the paper's, to the same
    # fixed point under the same stopping rule (update below 1e-5), so the two stop at
    # different points within the rule's reach of the exact blend: 2e-5 × (1 + 2 × the
    # lever, under 1.8 here), below 1e-4.
    tol = 1e-4 if method == "dib" else 1e-5
    assert np.abs(gpu - cpu).max() < tol, (method, adapter)
    assert np.abs(gpu_n - cpu_n).max() < 1e-4
    clip, _ = cesium.skin_clip(0, fps=10, method=method, device="gpu")
    ref, _ = cesium.skin_clip(0, fps=10, method=method)
    assert clip.shape == ref.shape and np.abs(clip - ref).max() < tol
    # auto takes a hardware GPU only; a software one (lavapipe) is no faster than the CPU.
    assert cesium.skinning_device("sbs", "auto") == "cpu"
    assert cesium.skinning_device(method, "cpu") == "cpu"


STRIP = {
    # A bar along x from 0 to 2, the joint "tip" at x = 1 turning the outer half.
    "positions": [[x, y, 0.0] for x in (0.0, 0.5, 1.0, 1.5, 2.0) for y in (-0.1, 0.1)],
    "triangles": [[2 * i + a, 2 * i + b, 2 * i + c] for i in range(4) for a, b, c in ((0, 2, 1), (1, 2, 3))],
    "joints": [{"name": "root", "parent": None}, {"name": "tip", "parent": 0, "translation": [1.0, 0.0, 0.0]}],
    "influences": [[[0, 1.0]]] * 4 + [[[0, 0.5], [1, 0.5]]] * 2 + [[[1, 1.0]]] * 4,
}


def test_a_json_rig_loads_and_skins_as_the_cli(cli, tmp_path):
    path = tmp_path / "strip.json"
    path.write_text(json.dumps(STRIP))
    rig = chasles.Rig.load(path)
    assert rig.vertex_count == 10 and rig.joint_names == ["root", "tip"]
    assert chasles.Rig.from_bytes(path.read_bytes(), "strip.json").vertex_count == 10
    # The tip turned 90° about z: the outer vertices (weight 1 on tip) turn exactly about
    # (1, 0, 0); the middle ones, half on each joint, by DQS are turned 45°.
    quarter = chasles.quat_from_axis_angle([0.0, 0.0, 1.0], np.pi / 2)
    rest = rig.pose()
    rotations = np.array(rest.rotations)
    rotations[1] = quarter
    pose = chasles.Pose(rest.translations, rotations, rest.scales)
    pos, _ = rig.skin(pose, "dqs")
    expect = np.array([[1.0 - y, x - 1.0, 0.0] for x, y, _ in STRIP["positions"][6:]])
    assert np.abs(pos[6:] - expect).max() < 1e-6
    assert np.array_equal(pos[:4], np.array(STRIP["positions"][:4], dtype=np.float32))
    mid = pos[4]  # (1, -0.1) turned 45° about (1, 0)
    assert np.abs(mid - [1 + 0.1 * np.sin(np.pi / 4), -0.1 * np.cos(np.pi / 4), 0]).max() < 1e-6
    posefile = tmp_path / "pose.json"
    posefile.write_text(json.dumps({"joints": {"tip": {"rotation": list(quarter)}}}))
    for method in SKIN_METHODS:
        out = tmp_path / f"{method}.json"
        cli("skin", "--rig", path, "--pose", posefile, "--method", method, "--device", "cpu", "--out", out)
        d = json.loads(out.read_text())
        p, n = rig.skin(pose, method)
        assert np.array_equal(p, np.array(d["positions"], dtype=np.float32)), method
        assert np.array_equal(n, np.array(d["normals"], dtype=np.float32)), method


def test_clip_frames_are_single_poses(cesium):
    times = np.array([0.0, 0.25, 1.5], dtype=np.float32)
    pos, nrm = cesium.skin_clip("0", times=times, method="log")
    for f, t in enumerate(times):
        p, n = cesium.skin(cesium.pose(0, float(t)), "log")
        assert np.array_equal(pos[f], p) and np.array_equal(nrm[f], n)


def test_own_arrays_match_the_rig_and_numpy(cesium):
    pose = cesium.pose(0, 0.4)
    mats = cesium.skinning_matrices(pose)
    joints, weights = cesium.influences()
    for method in SKIN_METHODS:
        ours = chasles.skin(cesium.positions, cesium.normals, joints, weights, mats, method,
                            centres=np.linalg.inv(cesium.inverse_bind)[:, :3, 3])
        rig = cesium.skin(pose, method)
        assert np.abs(ours[0] - rig[0]).max() < 1e-5, method
    # LBS is the weighted sum of the joints' matrices.
    blended = np.einsum("vk,vkij->vij", weights, mats[joints])
    lbs = np.einsum("vij,vj->vi", blended[:, :3, :3], cesium.positions) + blended[:, :3, 3]
    pos, _ = chasles.skin(cesium.positions, cesium.normals, joints, weights, mats, "lbs")
    assert np.abs(pos - lbs).max() < 1e-5
    # A batch of poses at once, frame by frame the same.
    batch = np.stack([mats, cesium.skinning_matrices(cesium.pose(0, 1.0))])
    pb, nb = chasles.skin(cesium.positions, cesium.normals, joints, weights, batch, "dqs")
    assert pb.shape == (2, 3273, 3)
    one = chasles.skin(cesium.positions, cesium.normals, joints, weights, batch[1], "dqs")
    assert np.array_equal(pb[1], one[0]) and np.array_equal(nb[1], one[1])


def test_a_rig_of_arrays_made_once_skins_as_the_free_function(cesium, rng):
    joints, weights = cesium.influences()
    centres = np.linalg.inv(cesium.inverse_bind)[:, :3, 3]
    own = chasles.Rig.from_arrays(cesium.positions, cesium.normals, joints, weights,
                                  centres=centres, name="mine")
    assert own.name == "mine" and own.joint_count == 19 and own.vertex_count == 3273
    assert own.clips == [] and own.triangles.shape == (0, 3)
    batch = np.stack([cesium.skinning_matrices(cesium.pose(0, t)) for t in (0.3, 1.1, 1.7)])
    for method in SKIN_METHODS:
        free = chasles.skin(cesium.positions, cesium.normals, joints, weights, batch, method,
                            centres=centres)
        mine = own.skin_with(batch, method)
        assert mine[0].shape == (3, 3273, 3) and mine[0].dtype == np.float32
        assert np.array_equal(mine[0], free[0]) and np.array_equal(mine[1], free[1]), method
        # One pose alone is that frame of the batch.
        one = own.skin_with(batch[2], method)
        assert np.array_equal(one[0], mine[0][2]) and np.array_equal(one[1], mine[1][2])
        # A loaded rig skinned by its own pose's matrices is that pose skinned.
        loaded = cesium.skin_with(batch[0], method)
        posed = cesium.skin(clip=0, time=0.3, method=method)
        assert np.array_equal(loaded[0], posed[0]) and np.array_equal(loaded[1], posed[1])
    # LBS is the weighted sum of the joints' matrices (numpy, independently).
    blended = np.einsum("vk,vkij->vij", weights, batch[1][joints])
    lbs = np.einsum("vij,vj->vi", blended[:, :3, :3], cesium.positions) + blended[:, :3, 3]
    assert np.abs(own.skin_with(batch[1], "lbs")[0] - lbs).max() < 1e-5
    # It pickles as any rig, and skins the same after.
    back = pickle.loads(pickle.dumps(own))
    assert np.array_equal(back.skin_with(batch, "sbs")[0], own.skin_with(batch, "sbs")[0])
    # The joint count: the largest index plus one, the centres' count, or as given.
    p, n = rng.normal(size=(3, 3)), np.tile([0.0, 0.0, 1.0], (3, 1))
    j, w = [[0, 1], [1, 2], [2, 0]], [[0.5, 0.5], [1.0, 0.0], [0.3, 0.7]]
    assert chasles.Rig.from_arrays(p, n, j, w).joint_count == 3
    assert chasles.Rig.from_arrays(p, n, j, w, centres=np.zeros((5, 3))).joint_count == 5
    assert chasles.Rig.from_arrays(p, n, j, w, joint_count=4).joint_count == 4
    # An index of weight 0 is padding: it does not count (nor need it exist).
    padded = chasles.Rig.from_arrays(p, n, [[0, 1], [1, 65535], [2, 0]], w)
    assert padded.joint_count == 3
    # More than eight influences: the reference path, as the free function takes it.
    many = rng.uniform(0.1, 1.0, size=(3, 12))
    wide = chasles.Rig.from_arrays(p, n, np.tile(np.arange(12), (3, 1)), many)
    mats = np.tile(np.eye(4), (12, 1, 1))
    mats[:, :3, 3] = rng.normal(size=(12, 3))
    expected = p + (many / many.sum(1, keepdims=True)) @ mats[:, :3, 3]
    assert np.abs(wide.skin_with(mats, "lbs")[0] - expected).max() < 1e-5


def test_bad_arrays_for_a_rig_raise(cesium, rng):
    p, n = rng.normal(size=(3, 3)), np.tile([0.0, 0.0, 1.0], (3, 1))
    j, w = [[0, 1], [1, 2], [2, 0]], [[0.5, 0.5], [1.0, 0.0], [0.3, 0.7]]
    # Vertex 1's joint 2 has weight 0 and is dropped; vertex 2's is not.
    with pytest.raises(ValueError, match="vertex 2: joint index 2 out of range"):
        chasles.Rig.from_arrays(p, n, j, w, joint_count=2)
    with pytest.raises(ValueError, match=r"centres must have shape \(4, 3\), one per joint"):
        chasles.Rig.from_arrays(p, n, j, w, centres=np.zeros((3, 3)), joint_count=4)
    with pytest.raises(ValueError, match="joint index -2 is negative"):
        chasles.Rig.from_arrays(p, n, [[0, 1], [1, -2], [2, 0]], w)
    with pytest.raises(ValueError, match="joint_count must be 0 or more, got -3"):
        chasles.Rig.from_arrays(p, n, j, w, joint_count=-3)
    # The rig's name is in the messages of the checks it goes through.
    with pytest.raises(ValueError, match="mine"):
        chasles.Rig.from_arrays(np.full((3, 3), np.inf), n, j, w, name="mine")
    with pytest.raises(ValueError, match=r"normals must have shape \(3, 3\) like positions"):
        chasles.Rig.from_arrays(p, n[:2], j, w)
    with pytest.raises(ValueError, match="vertex 2: weight NaN for joint 2 is negative or not finite"):
        chasles.Rig.from_arrays(p, n, j, [[0.5, 0.5], [1.0, 0.0], [np.nan, 0.7]])
    with pytest.raises(ValueError, match="joints must be integers"):
        chasles.Rig.from_arrays(p, n, np.array(j, dtype=float), w)
    own = chasles.Rig.from_arrays(p, n, j, w)
    with pytest.raises(ValueError, match=r"joint_matrices must have shape \(\.\.\., 3, 4, 4\)"):
        own.skin_with(np.tile(np.eye(4), (2, 1, 1)))
    with pytest.raises(ValueError, match=r"joint_matrices must have shape \(\.\.\., 19, 4, 4\)"):
        cesium.skin_with(np.eye(4))
    with pytest.raises(ValueError, match="unknown method 'bbw'"):
        own.skin_with(np.tile(np.eye(4), (3, 1, 1)), "bbw")
    bad = np.tile(np.eye(4), (2, 3, 1, 1))
    bad[1, 2, 0, 3] = np.inf
    with pytest.raises(ValueError, match="not finite"):
        own.skin_with(bad)


def test_more_than_eight_influences_take_the_reference_path(rng):
    v, j = 50, 12
    p = rng.normal(size=(v, 3))
    n = np.tile([0.0, 0.0, 1.0], (v, 1))
    joints = np.tile(np.arange(j), (v, 1))
    w = rng.uniform(0.1, 1.0, size=(v, j))
    mats = np.tile(np.eye(4), (j, 1, 1))
    mats[:, :3, 3] = rng.normal(size=(j, 3))
    pos, _ = chasles.skin(p, n, joints, w, mats, "lbs")
    expected = p + (w / w.sum(1, keepdims=True)) @ mats[:, :3, 3]
    assert np.abs(pos - expected).max() < 1e-5


def test_rigs_and_poses_pickle(cesium):
    again = pickle.loads(pickle.dumps(cesium))
    assert again.name == cesium.name and again.clips == cesium.clips
    assert np.array_equal(again.positions, cesium.positions)
    a = cesium.skin_clip(0, fps=10, method="sbs")
    b = again.skin_clip(0, fps=10, method="sbs")
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
    pose = cesium.pose(0, 0.9)
    p2 = pickle.loads(pickle.dumps(pose))
    assert p2 == pose and np.array_equal(p2.rotations, pose.rotations)
    assert np.array_equal(cesium.skin(p2)[0], cesium.skin(pose)[0])
    for name in chasles.models():
        r = chasles.Rig.model(name)
        assert pickle.loads(pickle.dumps(r)).node_names == r.node_names
    with pytest.raises(ValueError, match="not a pickled chasles rig"):
        chasles.Rig._from_state(b"nonsense")
    with pytest.raises(ValueError, match="truncated"):
        chasles.Rig._from_state(cesium.__reduce__()[1][0][:100])


def test_bad_skinning_inputs_raise(cesium, tmp_path, rng):
    with pytest.raises(ValueError, match="unknown method 'bbw'"):
        cesium.skin(method="bbw")
    with pytest.raises(ValueError, match="device='gpu': sbs has no GPU path"):
        cesium.skin(method="sbs", device="gpu")
    with pytest.raises(ValueError, match="unknown device 'tpu': cpu, gpu or auto"):
        cesium.skin(device="tpu")
    with pytest.raises(ValueError, match="no animation 'Dance'; there are: 0"):
        cesium.pose("Dance", 0.0)
    with pytest.raises(ValueError, match="no animation 3"):
        cesium.skin_clip(3)
    with pytest.raises(ValueError, match="give either pose or clip/time"):
        cesium.skin(cesium.pose(), clip=0)
    with pytest.raises(ValueError, match="the time NaN in clip 0 is not finite"):
        cesium.pose(0, float("nan"))
    with pytest.raises(ValueError, match="more than max_frames=5"):
        cesium.skin_clip(0, fps=30, max_frames=5)
    with pytest.raises(ValueError, match="fps must be in"):
        cesium.skin_clip(0, fps=0.0)
    other = chasles.Rig.model("RiggedSimple")
    with pytest.raises(ValueError, match="node transforms in the pose"):
        cesium.skin(other.pose())
    with pytest.raises(ValueError, match="rotation is zero"):
        chasles.Pose(np.zeros((2, 3)), np.zeros((2, 4)))
    with pytest.raises(ValueError, match=r"rotations must have shape \(2, 4\)"):
        chasles.Pose(np.zeros((2, 3)), np.zeros((3, 4)))
    with pytest.raises(OSError, match="nothing.glb"):
        chasles.Rig.load(tmp_path / "nothing.glb")
    bad = tmp_path / "bad.glb"
    bad.write_bytes(b"not a model")
    with pytest.raises(ValueError, match="bad.glb"):
        chasles.Rig.load(bad)
    with pytest.raises(ValueError, match="no built-in model 'Bob'"):
        chasles.Rig.model("Bob")
    p, n = np.zeros((2, 3)), np.tile([0.0, 0.0, 1.0], (2, 1))
    eye = np.tile(np.eye(4), (2, 1, 1))
    with pytest.raises(ValueError, match="vertex 1: joint index 5 out of range"):
        chasles.skin(p, n, [[0], [5]], [[1.0], [1.0]], eye)
    with pytest.raises(ValueError, match="vertex 0: weight -1 for joint 0"):
        chasles.skin(p, n, [[0], [1]], [[-1.0], [1.0]], eye)
    with pytest.raises(ValueError, match="vertex 1: the weights sum to zero"):
        chasles.skin(p, n, [[0], [1]], [[1.0], [0.0]], eye)
    with pytest.raises(ValueError, match="joint index -1 is negative"):
        chasles.skin(p, n, [[0], [-1]], [[1.0], [1.0]], eye)
    with pytest.raises(ValueError, match="joints must be integers"):
        chasles.skin(p, n, [[0.0], [1.0]], [[1.0], [1.0]], eye)
    with pytest.raises(ValueError, match=r"joint_matrices must have shape \(\.\.\., J, 4, 4\)"):
        chasles.skin(p, n, [[0], [1]], [[1.0], [1.0]], np.eye(3))
    # Matrices laid out (4, 4, J): the shape is named, before any joint index is checked.
    with pytest.raises(ValueError, match=r"joint_matrices must have shape \(\.\.\., J, 4, 4\), got \(4, 4, 2\)"):
        chasles.skin(p, n, [[0], [1]], [[1.0], [1.0]], np.zeros((4, 4, 2)))
    with pytest.raises(ValueError, match=r"weights must have shape \(2, 1\)"):
        chasles.skin(p, n, [[0], [1]], [[1.0, 2.0], [1.0, 1.0]], eye)
    with pytest.raises(ValueError, match="not finite"):
        bad_m = eye.copy()
        bad_m[1, 0, 3] = np.nan
        chasles.skin(p, n, [[0], [1]], [[1.0], [1.0]], bad_m)


@pytest.mark.parametrize("name", ["Fox", "CesiumMan", "RiggedFigure"])
def test_a_rig_reordered_by_influence_count_skins_to_the_same_bits(name):
    rig = chasles.Rig.model(name)
    n = rig.vertex_count
    order = rig.vertex_order()
    assert order.dtype == np.int64 and order.shape == (n,)
    assert np.array_equal(np.sort(order), np.arange(n))
    # Every vertex stays in its window of 256; within it the influence counts (1, 2, 3,
    # 4, ...) rise in even windows and fall in odd ones.
    j, w = rig.influences()
    kind = (w > 0).sum(axis=1)
    for start in range(0, n, 256):
        win = order[start : start + 256]
        assert np.all(win // 256 == start // 256)
        step = np.diff(kind[win])
        assert np.all(step >= 0) if (start // 256) % 2 == 0 else np.all(step <= 0)
    grouped = rig.reordered(order)
    assert np.array_equal(grouped.positions, rig.positions[order])
    assert np.array_equal(grouped.normals, rig.normals[order])
    gj, gw = grouped.influences()
    assert np.array_equal(gw, w[order]) and np.array_equal(gj, j[order])
    # The triangles name the same points.
    assert np.array_equal(grouped.positions[grouped.triangles], rig.positions[rig.triangles])
    # Skinned by every method, each vertex gets the same bits at its new index; a uint32
    # order (as the Rust API gives it) is taken alike.
    again = rig.reordered(order.astype(np.uint32))
    for method in SKIN_METHODS:
        p, nr = rig.skin(method=method, time=0.4)
        for r in (grouped, again):
            q, qn = r.skin(method=method, time=0.4)
            assert np.array_equal(q, p[order]) and np.array_equal(qn, nr[order]), method
    # A reordered rig pickles as any rig.
    back = pickle.loads(pickle.dumps(grouped))
    assert np.array_equal(back.positions, grouped.positions)


def test_bad_vertex_orders_raise():
    rig = chasles.Rig.model("Fox")
    n = rig.vertex_count
    order = rig.vertex_order()
    with pytest.raises(ValueError, match=f"{n - 1} vertices, expected {n}"):
        rig.reordered(order[:-1])
    bad = order.copy()
    bad[3] = -1
    with pytest.raises(ValueError, match="entry 3 is -1, not a vertex index"):
        rig.reordered(bad)
    bad[3] = n
    with pytest.raises(ValueError, match=f"entry 3 names vertex {n} out of range"):
        rig.reordered(bad)
    bad[3] = bad[4]
    with pytest.raises(ValueError, match="at positions 3 and 4"):
        rig.reordered(bad)
    with pytest.raises(ValueError, match=r"order must have shape \(V,\)"):
        rig.reordered(order.reshape(-1, 2))
    # Only integers name vertices: strings, and floats (which numpy would truncate), are
    # refused as the skinning functions' joint indices are.
    with pytest.raises(ValueError, match="order must be integers, got str"):
        rig.reordered(["a", "b"])
    with pytest.raises(ValueError, match="order must be integers, got float64"):
        rig.reordered(order + 0.25)
