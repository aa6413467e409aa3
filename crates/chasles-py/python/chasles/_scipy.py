"""Interop with scipy's ``Rotation`` and ``RigidTransform``; scipy is imported only here,
when one of these functions is called."""

import numpy as np


def from_scipy(obj, *, scalar_first=True):
    """Quaternions or dual quaternions of a scipy rotation or rigid transform.

    A ``scipy.spatial.transform.Rotation`` (one or many) gives its unit quaternions,
    (..., 4) ``[w, x, y, z]`` (``scalar_first=False``: ``[x, y, z, w]``); a
    ``RigidTransform`` (scipy ≥ 1.16) gives unit dual quaternions (..., 8) of its rotation
    followed by its translation. Anything else raises ``ValueError``.

    >>> import chasles
    >>> from scipy.spatial.transform import Rotation
    >>> chasles.from_scipy(Rotation.from_euler("z", 90, degrees=True)).round(6)
    array([0.707107, 0.      , 0.      , 0.707107])
    """
    from scipy.spatial import transform

    from ._chasles import dq_from_rt

    if isinstance(obj, transform.Rotation):
        q = np.roll(obj.as_quat(), 1, axis=-1)
        return q if scalar_first else np.roll(q, -1, axis=-1)
    rigid = getattr(transform, "RigidTransform", None)
    if rigid is not None and isinstance(obj, rigid):
        t, r = obj.as_components()
        return dq_from_rt(from_scipy(r), t, scalar_first=True) if scalar_first else dq_from_rt(
            from_scipy(r, scalar_first=False), t, scalar_first=False
        )
    raise ValueError(
        f"from_scipy takes a scipy.spatial.transform Rotation or RigidTransform, got {type(obj).__name__}"
    )


def to_scipy(x, *, scalar_first=True):
    """A scipy ``Rotation`` of quaternions (..., 4), or a ``RigidTransform`` (scipy ≥ 1.16)
    of dual quaternions (..., 8); ``scalar_first`` as everywhere in chasles. Zero or
    non-finite input raises ``ValueError``.

    >>> import chasles, numpy as np
    >>> r = chasles.to_scipy(chasles.quat_from_axis_angle([0, 0, 1], np.pi / 2))
    >>> r.as_rotvec().round(6)
    array([0.      , 0.      , 1.570796])
    """
    from scipy.spatial import transform

    from ._chasles import dq_to_rt, quat_normalize

    x = np.asarray(x, dtype=float)
    if x.shape[-1:] == (4,):
        q = quat_normalize(x, scalar_first=scalar_first)
        return transform.Rotation.from_quat(q if not scalar_first else np.roll(q, -1, axis=-1))
    if x.shape[-1:] == (8,):
        rigid = getattr(transform, "RigidTransform", None)
        if rigid is None:
            raise ValueError("dual quaternions need scipy >= 1.16 (RigidTransform)")
        q, t = dq_to_rt(x, scalar_first=scalar_first)
        r = to_scipy(q, scalar_first=scalar_first)
        return rigid.from_components(t, r)
    raise ValueError(f"x must have shape (..., 4) or (..., 8), got {x.shape}")
