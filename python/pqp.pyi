"""Type stubs of the `pqp` extension module (proximity queries between triangle meshes)."""

from typing import Any, Literal, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
# A pose: None (identity), a 4x4 homogeneous matrix, or an (R, T) pair.
Pose = Union[None, npt.ArrayLike, Tuple[npt.ArrayLike, npt.ArrayLike]]
# Where a model goes: a Model, a (vertices, faces) pair, or a mesh with `vertices` and `faces`
# attributes (a trimesh.Trimesh), built for the call.
ModelLike = Union["Model", Tuple[npt.ArrayLike, npt.ArrayLike], Any]
F64 = npt.NDArray[np.float64]
I64 = npt.NDArray[np.int64]

class Model:
    """A triangle mesh or a solid primitive, built and ready for queries."""

    def __init__(self, vertices: Any, faces: Optional[npt.ArrayLike] = None, *, threads: int = 0) -> None: ...
    @staticmethod
    def sphere(radius: float) -> "Model": ...
    @staticmethod
    def capsule(radius: float, length: float) -> "Model": ...
    @staticmethod
    def box(x: float, y: float, z: float) -> "Model": ...
    def refit(self, vertices: npt.ArrayLike) -> None: ...
    @property
    def vertices(self) -> F64: ...
    @property
    def faces(self) -> I64: ...
    @property
    def num_triangles(self) -> int: ...
    @property
    def kind(self) -> Literal["mesh", "sphere", "capsule", "box"]: ...
    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]: ...

def collide(m1: ModelLike, pose1: Pose, m2: ModelLike, pose2: Pose, first: bool = False) -> I64: ...
def distance(
    m1: ModelLike, pose1: Pose, m2: ModelLike, pose2: Pose, rel_err: float = 0.0, abs_err: float = 0.0
) -> Tuple[float, F64, F64]: ...
def tolerance(m1: ModelLike, pose1: Pose, m2: ModelLike, pose2: Pose, tolerance: float) -> bool: ...
def within_distance(m1: ModelLike, pose1: Pose, m2: ModelLike, pose2: Pose, d: float) -> Tuple[I64, F64]: ...
def closest_point(
    model: ModelLike, pose: Pose, points: npt.ArrayLike, max_distance: float = ..., threads: int = 0
) -> Tuple[F64, F64, I64]: ...
def signed_distance(model: ModelLike, pose: Pose, points: npt.ArrayLike, threads: int = 0) -> F64: ...
def ray_cast(
    model: ModelLike,
    pose: Pose,
    origins: npt.ArrayLike,
    directions: npt.ArrayLike,
    max_t: float = ...,
    threads: int = 0,
) -> Tuple[F64, I64]: ...
def collide_batch(
    m1: ModelLike, poses1: Pose, m2: ModelLike, poses2: Pose, threads: int = 0
) -> npt.NDArray[np.bool_]: ...
def distance_batch(
    m1: ModelLike,
    poses1: Pose,
    m2: ModelLike,
    poses2: Pose,
    threads: int = 0,
    rel_err: float = 0.0,
    abs_err: float = 0.0,
) -> F64: ...
