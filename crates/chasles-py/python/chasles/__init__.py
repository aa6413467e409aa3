"""chasles — rotations and rigid motions on numpy arrays.

Quaternions are ``[w, x, y, z]`` on the last axis (``scalar_first=False``: scipy's
``[x, y, z, w]``); dual quaternions are 8 numbers ``[w, x, y, z, wε, xε, yε, zε]``.
Every function is batched over leading dimensions, keeps float32 and float64 as given,
releases the GIL and uses all cores for large batches. Errors raise ``ValueError`` with
the library's message.
"""

from ._chasles import (  # noqa: F401
    Pose,
    Rig,
    __version__,
    blend,
    dq_from_matrix,
    dq_from_rt,
    dq_from_screw,
    dq_inv,
    dq_mul,
    dq_normalize,
    dq_pow,
    dq_to_matrix,
    dq_to_rt,
    dq_transform,
    interpolate,
    model_bytes,
    models,
    quat_angle,
    quat_conj,
    quat_exp,
    quat_from_axis_angle,
    quat_from_euler,
    quat_from_matrix,
    quat_from_rotvec,
    quat_inv,
    quat_log,
    quat_mul,
    quat_normalize,
    quat_pow,
    quat_to_axis_angle,
    quat_to_euler,
    quat_to_matrix,
    quat_to_rotvec,
    rotate,
    sclerp,
    screw,
    skin,
    slerp,
    spring,
    squad,
)
