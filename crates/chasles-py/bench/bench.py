"""Speed of the Python package against scipy and numpy, side by side in one run.

    python crates/chasles-py/bench/bench.py [--n 1000000] [--repeat 5]

* conversions and Slerp on n quaternions (float64) against scipy's Rotation and Slerp;
* DLB of (n, 4) dual quaternions against a numpy-vectorized DLB (the same antipodality fix
  against the heaviest weight and the same normalization);
* skinning CesiumMan's whole clip (LBS) against a numpy einsum LBS given the same joint
  matrices, with and without the posing of each frame on our side, and a pose a call (the
  free `skin()`, which lays the rig out on every call, and `Rig.from_arrays` once with
  `skin_with`) against numpy a frame a call.

Each time is the best of --repeat runs; every pair of results is checked to agree first.
Targets (issue 19): at least 5x scipy on Slerp and conversions, at least 10x numpy on DLB
and skinning.
"""

import argparse
import os
import time

import numpy as np
from scipy.spatial.transform import Rotation, Slerp

import chasles


def best(f, repeat):
    f()
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def numpy_dlb(x, w):
    """DLB of x (N, k, 8) with weights (N, k), vectorized: flip each dual quaternion into the
    hemisphere of the heaviest one, sum, normalize (real part to unit length, dual part
    orthogonal to it)."""
    w = w / w.sum(axis=1, keepdims=True)
    n = np.arange(len(x))
    pivot = x[n, np.argmax(w, axis=1), :4]
    s = np.where(np.einsum("nkj,nj->nk", x[..., :4], pivot) < 0, -w, w)
    b = np.einsum("nk,nkj->nj", s, x)
    norm = np.linalg.norm(b[:, :4], axis=1, keepdims=True)
    r, d = b[:, :4] / norm, b[:, 4:] / norm
    d = d - r * np.sum(r * d, axis=1, keepdims=True)
    return np.concatenate([r, d], axis=1)


def numpy_lbs(mats, joints, weights, p, n):
    """LBS of every frame by einsum: blended matrices, positions, normals by the blended
    3x3 renormalized."""
    b = np.einsum("vk,fvkij->fvij", weights, mats[:, joints])
    pos = np.einsum("fvij,vj->fvi", b[..., :3, :3], p) + b[..., :3, 3]
    nrm = np.einsum("fvij,vj->fvi", b[..., :3, :3], n)
    nrm /= np.linalg.norm(nrm, axis=-1, keepdims=True)
    return pos, nrm


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--fps", type=float, default=120.0)
    a = ap.parse_args()
    n, rep = a.n, a.repeat
    load_before = os.getloadavg()
    rng = np.random.default_rng(19)
    q = rng.normal(size=(n + 1, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    xyzw = np.roll(q, -1, axis=1)
    angles = chasles.quat_to_euler(q[:n], "xyz")
    mats = chasles.quat_to_matrix(q[:n])
    v = rng.normal(size=(n, 3))
    t = rng.uniform(size=n)
    rows = []

    def row(name, ours, theirs, baseline, target, check):
        check()
        to, tt = best(ours, rep), best(theirs, rep)
        rows.append((name, to * 1e3, tt * 1e3, tt / to, baseline, target))

    def close(x, y, tol):
        d = np.abs(np.asarray(x) - np.asarray(y)).max()
        assert d < tol, d

    def close_sign(x, y, tol):
        d = np.minimum(np.abs(x - y).max(axis=-1), np.abs(x + y).max(axis=-1)).max()
        assert d < tol, d

    row("Euler -> quat (xyz)", lambda: chasles.quat_from_euler(angles, "xyz"),
        lambda: Rotation.from_euler("xyz", angles).as_quat(), "scipy", 5,
        lambda: close_sign(chasles.quat_from_euler(angles, "xyz"),
                           Rotation.from_euler("xyz", angles).as_quat(scalar_first=True), 1e-12))
    row("quat -> Euler (xyz)", lambda: chasles.quat_to_euler(q[:n], "xyz"),
        lambda: Rotation.from_quat(xyzw[:n]).as_euler("xyz"), "scipy", 5,
        lambda: close(chasles.quat_to_euler(q[:n], "xyz"), Rotation.from_quat(xyzw[:n]).as_euler("xyz"), 1e-12))
    row("quat -> matrix", lambda: chasles.quat_to_matrix(q[:n]),
        lambda: Rotation.from_quat(xyzw[:n]).as_matrix(), "scipy", 5,
        lambda: close(chasles.quat_to_matrix(q[:n]), Rotation.from_quat(xyzw[:n]).as_matrix(), 1e-12))
    row("matrix -> quat", lambda: chasles.quat_from_matrix(mats),
        lambda: Rotation.from_matrix(mats).as_quat(), "scipy", 5,
        lambda: close_sign(chasles.quat_from_matrix(mats), np.roll(Rotation.from_matrix(mats).as_quat(), 1, axis=1), 1e-12))
    row("rotate vectors", lambda: chasles.rotate(q[:n], v),
        lambda: Rotation.from_quat(xyzw[:n]).apply(v), "scipy", 5,
        lambda: close(chasles.rotate(q[:n], v), Rotation.from_quat(xyzw[:n]).apply(v), 1e-12))
    # Slerp: scipy's Slerp over n intervals of n + 1 keys at one time in each, against
    # chasles.slerp of the same n pairs (they agree to 1e-10 here: scipy goes through
    # rotation vectors, which lose digits for relative rotations near 180 degrees).
    times = np.arange(n) + t
    row("Slerp (n intervals)", lambda: chasles.slerp(q[:-1], q[1:], t),
        lambda: Slerp(np.arange(n + 1.0), Rotation.from_quat(xyzw))(times).as_quat(), "scipy", 5,
        lambda: close_sign(chasles.slerp(q[:-1], q[1:], t),
                           np.roll(Slerp(np.arange(n + 1.0), Rotation.from_quat(xyzw))(times).as_quat(), 1, axis=1), 1e-10))

    # DLB of (n, 4) transforms.
    x = chasles.dq_from_rt(rng.normal(size=(n, 4, 4)), rng.normal(size=(n, 4, 3)))
    w = rng.uniform(0.05, 1.0, size=(n, 4))
    row("DLB, (n, 4) transforms", lambda: chasles.blend(x, w, "dlb"), lambda: numpy_dlb(x, w), "numpy", 10,
        lambda: close(chasles.blend(x, w, "dlb"), numpy_dlb(x, w), 1e-12))

    # Skinning CesiumMan's whole clip.
    rig = chasles.Rig.model("CesiumMan")
    duration = rig.duration(0)
    frames = int(np.floor(duration * a.fps)) + 1
    ft = (np.arange(frames) / np.float32(a.fps)).astype(np.float32)
    jm = np.stack([rig.skinning_matrices(rig.pose(0, float(s))) for s in ft])
    j, wt = rig.influences()
    p, nn = rig.positions, rig.normals

    def check_skin():
        ours = chasles.skin(p, nn, j, wt, jm, "lbs")
        theirs = numpy_lbs(jm, j, wt, p, nn)
        close(ours[0], theirs[0], 1e-4)
        clip = rig.skin_clip(0, fps=a.fps, method="lbs")
        close(clip[0], theirs[0], 1e-4)

    label = f"LBS, CesiumMan clip ({frames} frames x {rig.vertex_count} vertices)"
    row(label + ", matrices given", lambda: chasles.skin(p, nn, j, wt, jm, "lbs"),
        lambda: numpy_lbs(jm, j, wt, p, nn), "numpy einsum", 10, check_skin)
    row(label + ", posed too", lambda: rig.skin_clip(0, fps=a.fps, method="lbs"),
        lambda: numpy_lbs(jm, j, wt, p, nn), "numpy einsum", 10, lambda: None)
    # A pose a call, as a loop over frames that come one at a time calls it: the free
    # function checks the arrays and lays the rig out on every call; Rig.from_arrays does it
    # once, and skin_with skins by each frame's matrices.
    own = chasles.Rig.from_arrays(p, nn, j, wt, joint_count=jm.shape[1])
    per_frame = lambda: [numpy_lbs(m[None], j, wt, p, nn) for m in jm]
    row(label + ", a pose a call, skin()", lambda: [chasles.skin(p, nn, j, wt, m, "lbs") for m in jm],
        per_frame, "numpy einsum", 10, lambda: None)
    row(label + ", a pose a call, Rig.from_arrays once, skin_with",
        lambda: [own.skin_with(m, "lbs") for m in jm], per_frame, "numpy einsum", 10,
        lambda: close(np.stack([own.skin_with(m, "lbs")[0] for m in jm]), numpy_lbs(jm, j, wt, p, nn)[0], 1e-4))
    row(f"DQS, CesiumMan clip, posed too", lambda: rig.skin_clip(0, fps=a.fps, method="dqs"),
        lambda: numpy_lbs(jm, j, wt, p, nn), "numpy einsum LBS", 10, lambda: None)

    print(f"n = {n}, best of {a.repeat}, {os.cpu_count()} CPUs, numpy {np.__version__}, "
          f"scipy {__import__('scipy').__version__}, chasles {chasles.__version__}; load average "
          f"{load_before[0]:.1f} before, {os.getloadavg()[0]:.1f} after (other processes share the "
          f"CPUs: compare ratios from one run, and runs at low load)")
    print("| task | chasles ms | baseline | baseline ms | speed-up | target |")
    print("|---|---|---|---|---|---|")
    for name, to, tt, ratio, base, target in rows:
        ok = "ok" if ratio >= target else "below"
        print(f"| {name} | {to:.1f} | {base} | {tt:.1f} | {ratio:.1f}x | >= {target}x ({ok}) |")


if __name__ == "__main__":
    main()
