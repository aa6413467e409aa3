# Type stubs of the Rust extension (src/*.rs); the docstrings there have the details and an
# example each. tests/test_docs.py checks these against the module's own signatures.
from os import PathLike
from typing import Optional, Sequence, Tuple, Union

import numpy as np
from numpy.typing import ArrayLike, NDArray

__version__: str

Array = NDArray[np.floating]

# Conversions (src/convert.rs)
def quat_from_euler(angles: ArrayLike, order: str, *, scalar_first: bool = True) -> Array:
    """Unit quaternions (..., 4) of Euler angles (..., 3) in one of the 24 conventions."""
def quat_to_euler(q: ArrayLike, order: str, *, scalar_first: bool = True) -> Array:
    """Euler angles (..., 3) of quaternions (..., 4)."""
def quat_from_matrix(m: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Unit quaternions of (..., 3, 3) or (..., 4, 4) rotation matrices (checked)."""
def quat_to_matrix(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Rotation matrices (..., 3, 3) of quaternions."""
def quat_from_rotvec(rotvec: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Unit quaternions of rotation vectors (..., 3)."""
def quat_to_rotvec(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Rotation vectors (..., 3) of quaternions, angle in [0, π]."""
def quat_from_axis_angle(axis: ArrayLike, angle: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Unit quaternions rotating by angle (...) about axis (..., 3)."""
def quat_to_axis_angle(q: ArrayLike, *, scalar_first: bool = True) -> Tuple[Array, Array]:
    """Unit axes (..., 3) and angles (...) in [0, 2π] of quaternions."""

# Quaternion algebra (src/quat.rs)
def quat_mul(a: ArrayLike, b: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The Hamilton product a b."""
def quat_conj(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The conjugate."""
def quat_inv(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The inverse q* / |q|²."""
def quat_normalize(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """q / |q|."""
def quat_log(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The logarithm of any non-zero quaternion."""
def quat_exp(q: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The exponential of any quaternion."""
def quat_pow(q: ArrayLike, t: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Real powers q^t."""
def quat_angle(a: ArrayLike, b: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The angle in [0, π] of the rotation taking a to b."""
def rotate(q: ArrayLike, v: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Vectors (..., 3) rotated by quaternions."""

# Dual quaternions (src/dualquat.rs)
def dq_from_rt(q: ArrayLike, t: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Unit dual quaternions (..., 8) of a rotation then a translation."""
def dq_to_rt(dq: ArrayLike, *, scalar_first: bool = True) -> Tuple[Array, Array]:
    """Rotations (..., 4) and translations (..., 3) of dual quaternions."""
def dq_from_matrix(m: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Unit dual quaternions of rigid 4×4 matrices (checked)."""
def dq_to_matrix(dq: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Rigid 4×4 matrices of dual quaternions."""
def dq_transform(dq: ArrayLike, points: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Points (..., 3) moved by rigid motions."""
def dq_mul(a: ArrayLike, b: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The product a b (b first)."""
def dq_inv(dq: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The inverse."""
def dq_normalize(dq: ArrayLike, *, scalar_first: bool = True) -> Array:
    """The nearest unit dual quaternions."""
def dq_pow(dq: ArrayLike, t: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Real powers (the screw motion scaled by t)."""
def screw(dq: ArrayLike, *, scalar_first: bool = True) -> Tuple[Array, Array, Array, Array]:
    """Screw parameters (axis, point, angle, translation)."""
def dq_from_screw(
    axis: ArrayLike, point: ArrayLike, angle: ArrayLike, translation: ArrayLike, *, scalar_first: bool = True
) -> Array:
    """Unit dual quaternions of screws."""

# Interpolation (src/interp.rs, src/spring.rs)
def slerp(q0: ArrayLike, q1: ArrayLike, t: ArrayLike, *, shortest: bool = True, scalar_first: bool = True) -> Array:
    """Spherical linear interpolation, broadcast over q0, q1 and t."""
def interpolate(
    keys: ArrayLike,
    method: str = "slerp",
    frames: Optional[int] = None,
    *,
    timing: str = "angle",
    times: Optional[ArrayLike] = None,
    keep_signs: bool = False,
    order: str = "xyz",
    full_output: bool = False,
    scalar_first: bool = True,
    max_frames: int = 1000000,
    solver: Optional[str] = None,
    tolerance: Optional[float] = None,
    levels: Optional[Sequence[int]] = None,
    iterations: Optional[Sequence[int]] = None,
    step: Optional[str] = None,
    penalty: Optional[float] = None,
    width: Optional[str] = None,
    key_weight: Optional[float] = None,
    velocity_weight: Optional[float] = None,
    start: Optional[str] = None,
    tension: Optional[float] = None,
    continuity: Optional[float] = None,
    bias: Optional[float] = None,
    horizon: Optional[str] = None,
) -> Union[Array, Tuple[Array, Array, NDArray[np.int64]]]:
    """A curve through key frames by any method of `chasles interp`."""
def squad(
    keys: ArrayLike,
    frames: int,
    *,
    timing: str = "angle",
    times: Optional[ArrayLike] = None,
    keep_signs: bool = False,
    full_output: bool = False,
    scalar_first: bool = True,
    max_frames: int = 1000000,
) -> Union[Array, Tuple[Array, Array, NDArray[np.int64]]]:
    """Squad through key frames."""
def spring(
    keys: ArrayLike,
    frames: Optional[int] = None,
    *,
    preset: str = "spring",
    timing: str = "angle",
    times: Optional[ArrayLike] = None,
    keep_signs: bool = False,
    full_output: bool = False,
    scalar_first: bool = True,
    max_frames: int = 1000000,
    solver: Optional[str] = None,
    tolerance: Optional[float] = None,
    levels: Optional[Sequence[int]] = None,
    iterations: Optional[Sequence[int]] = None,
    step: Optional[str] = None,
    penalty: Optional[float] = None,
    width: Optional[str] = None,
    key_weight: Optional[float] = None,
    velocity_weight: Optional[float] = None,
    start: Optional[str] = None,
) -> Union[Array, Tuple[Array, Array, NDArray[np.int64]]]:
    """Spring: the curve of least curvature through key frames."""

# Blending (src/blend.rs)
def blend(
    transforms: ArrayLike,
    weights: ArrayLike,
    method: str = "dlb",
    *,
    center: Optional[Sequence[float]] = None,
    precision: Optional[float] = None,
    max_iterations: Optional[int] = None,
    full_output: bool = False,
    scalar_first: bool = True,
) -> Union[Array, Tuple[Array, NDArray[np.bool_], NDArray[np.int64]]]:
    """Blends of (..., n, 8) dual quaternions or (..., n, 4, 4) matrices with weights (..., n)."""
def sclerp(a: ArrayLike, b: ArrayLike, t: ArrayLike, *, scalar_first: bool = True) -> Array:
    """Screw linear interpolation."""
def interpolate_rigid(
    keys: ArrayLike,
    method: str = "sclerp",
    frames: int = 200,
    *,
    times: Optional[ArrayLike] = None,
    energy: str = "split",
    length_scale: float = 1.0,
    tolerance: Optional[float] = None,
    max_iterations: Optional[int] = None,
    full_output: bool = False,
    scalar_first: bool = True,
    max_frames: int = 1_000_000,
) -> Union[Array, Tuple[Array, Array, NDArray[np.int64]]]:
    """A curve of rigid poses (..., frames, 8) through keys (..., K, 8): sclerp, squad or spring."""
def average(
    poses: ArrayLike,
    weights: Optional[ArrayLike] = None,
    loss: Optional[str] = None,
    *,
    tuning: Optional[float] = None,
    scale: Optional[float] = None,
    length_scale: float = 1.0,
    precision: Optional[float] = None,
    max_iterations: Optional[int] = None,
    full_output: bool = False,
    scalar_first: bool = True,
) -> Union[Array, Tuple[Array, Array, Array, Array, NDArray[np.int64], NDArray[np.bool_]]]:
    """The rigid (or Huber's / Tukey's robust) mean of (..., n, 8) unit dual quaternions."""

# Skinning (src/skin.rs, src/rig.rs)
def skin(
    positions: ArrayLike,
    normals: ArrayLike,
    joints: ArrayLike,
    weights: ArrayLike,
    joint_matrices: ArrayLike,
    method: str = "dqs",
    *,
    centres: Optional[ArrayLike] = None,
) -> Tuple[NDArray[np.float32], NDArray[np.float32]]:
    """Skins your own arrays by joint matrices (..., J, 4, 4)."""
def models() -> list[str]:
    """The names of the built-in models."""
def model_bytes(name: str) -> bytes:
    """The file bytes of a built-in model."""

class Pose:
    """The local transform of every node of a rig."""
    def __init__(
        self, translations: ArrayLike, rotations: ArrayLike, scales: Optional[ArrayLike] = None, *, scalar_first: bool = True
    ) -> None: ...
    @property
    def translations(self) -> NDArray[np.float32]: ...
    @property
    def rotations(self) -> NDArray[np.float32]: ...
    @property
    def scales(self) -> NDArray[np.float32]: ...
    def __len__(self) -> int: ...

class Rig:
    """A rigged mesh: bind pose, skin, influences and clips."""
    @classmethod
    def load(cls, path: Union[str, PathLike[str]]) -> "Rig": ...
    @classmethod
    def model(cls, name: str) -> "Rig": ...
    @classmethod
    def from_bytes(cls, data: bytes, name: str = "rig.glb") -> "Rig": ...
    @classmethod
    def from_arrays(
        cls,
        positions: ArrayLike,
        normals: ArrayLike,
        joints: ArrayLike,
        weights: ArrayLike,
        *,
        centres: Optional[ArrayLike] = None,
        joint_count: Optional[int] = None,
        name: str = "arrays",
    ) -> "Rig": ...
    @property
    def name(self) -> str: ...
    @property
    def clips(self) -> list[str]: ...
    @property
    def joint_names(self) -> list[str]: ...
    @property
    def node_names(self) -> list[str]: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def joint_count(self) -> int: ...
    @property
    def positions(self) -> NDArray[np.float32]: ...
    @property
    def normals(self) -> NDArray[np.float32]: ...
    @property
    def triangles(self) -> NDArray[np.uint32]: ...
    @property
    def inverse_bind(self) -> NDArray[np.float32]: ...
    def influences(self) -> Tuple[NDArray[np.int64], NDArray[np.float32]]: ...
    def vertex_order(self) -> NDArray[np.int64]: ...
    def reordered(self, order: ArrayLike) -> "Rig": ...
    def duration(self, clip: Union[int, str, None] = None) -> float: ...
    def pose(self, clip: Union[int, str, None] = None, time: Optional[float] = None) -> Pose: ...
    def skinning_matrices(self, pose: Pose) -> NDArray[np.float32]: ...
    def skinning_device(self, method: str = "dqs", device: str = "auto") -> str: ...
    def skin(
        self,
        pose: Optional[Pose] = None,
        method: str = "dqs",
        device: str = "cpu",
        *,
        clip: Union[int, str, None] = None,
        time: Optional[float] = None,
    ) -> Tuple[NDArray[np.float32], NDArray[np.float32]]: ...
    def skin_with(
        self, joint_matrices: ArrayLike, method: str = "dqs"
    ) -> Tuple[NDArray[np.float32], NDArray[np.float32]]: ...
    def skin_clip(
        self,
        clip: Union[int, str, None] = None,
        fps: float = 30.0,
        method: str = "dqs",
        *,
        times: Optional[ArrayLike] = None,
        device: str = "cpu",
        max_frames: int = 10000,
    ) -> Tuple[NDArray[np.float32], NDArray[np.float32]]: ...
