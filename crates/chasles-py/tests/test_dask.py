"""The Dask recipe: a LocalCluster of 2 worker processes skins and re-times a set of clips,
one task each, and the results equal the serial run bit for bit (rigs pickle to the
workers; the functions are chasles' own, pickled by reference)."""

import numpy as np
import pytest

import chasles
from conftest import unit_quats

distributed = pytest.importorskip("distributed", reason="dask.distributed is not installed")


def test_a_local_cluster_skins_and_retimes_clips_as_the_serial_run(rng):
    rigs = [chasles.Rig.model("Fox"), chasles.Rig.model("CesiumMan")]
    jobs = [(r, clip) for r in rigs for clip in r.clips]
    keys = [unit_quats(rng, 6) for _ in range(4)]
    retime = dict(key_weight=1.3)  # the converged Spring

    serial_skins = [rig.skin_clip(clip, fps=10, method="dqs") for rig, clip in jobs]
    serial_curves = [chasles.spring(k, 120, **retime) for k in keys]

    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        scattered = {r.name: client.scatter(r, broadcast=True) for r in rigs}
        skins = [
            client.submit(chasles.Rig.skin_clip, scattered[rig.name], clip, fps=10, method="dqs", pure=False)
            for rig, clip in jobs
        ]
        curves = [client.submit(chasles.spring, k, 120, pure=False, **retime) for k in keys]
        skins, curves = client.gather(skins), client.gather(curves)
        assert len(client.scheduler_info()["workers"]) == 2

    assert len(skins) == len(jobs) == 4
    for (p, n), (sp, sn) in zip(skins, serial_skins):
        assert p.dtype == np.float32 and np.array_equal(p, sp) and np.array_equal(n, sn)
    for c, s in zip(curves, serial_curves):
        assert np.array_equal(c, s)
