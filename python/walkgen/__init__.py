"""walkgen: NMPC walking pattern generation for humanoid robots, from Python.

The C++ core (walkgen._core, built with pybind11) does the work; this package re-exports it.
docs/python.md is the guide. A first plan:

    import walkgen
    mpc = walkgen.WalkingMpc(walkgen.WalkingSettings.hrp2())
    mpc.set_command(0.2)            # 0.2 m/s forward
    for _ in range(60):
        result = mpc.solve()        # one NMPC tick
        mpc.advance()               # 0.1 s along the plan
    print(mpc.state().com_x)        # the CoM has walked about 1 m
"""

import os as _os

try:  # an installed package (cmake --install) knows where walkgen's data went
    from ._install import DATA_DIR as _DATA_DIR
except ImportError:  # the build tree: the data of the source tree it was built from
    _DATA_DIR = None
if _DATA_DIR is not None and not _os.environ.get("WALKGEN_DATA_DIR"):
    _data = _os.path.normpath(_os.path.join(_os.path.dirname(__file__), _DATA_DIR))
    if _os.path.isdir(_data):  # read by the C++ side's walkgen::data_dir()
        _os.environ["WALKGEN_DATA_DIR"] = _data

from ._core import (  # noqa: F401,E402 (re-exported)
    CircleObstacle,
    CommandStatus,
    DenseQp,
    KinematicTree,
    Kinematics,
    Foot,
    FootPose,
    MpcResult,
    MpcStatus,
    QpResult,
    QpSettings,
    QpStatus,
    RobotDescription,
    SoftConstraintWeights,
    WalkingMpc,
    WalkingSettings,
    WalkingState,
    __version__,
    features,
    trajectory_columns,
)
from ._core import EpisodeEnd, NmpcGoalSettings, PointGoalSettings  # noqa: F401,E402
from . import envs  # noqa: F401,E402 (the Gymnasium-shaped environments)

__all__ = [
    "CircleObstacle",
    "CommandStatus",
    "DenseQp",
    "KinematicTree",
    "Kinematics",
    "EpisodeEnd",
    "Foot",
    "FootPose",
    "MpcResult",
    "MpcStatus",
    "NmpcGoalSettings",
    "PointGoalSettings",
    "QpResult",
    "QpSettings",
    "QpStatus",
    "RobotDescription",
    "SoftConstraintWeights",
    "WalkingMpc",
    "WalkingSettings",
    "WalkingState",
    "__version__",
    "envs",
    "features",
    "trajectory_columns",
]

# Parts built only with their adapters (walkgen.features says which).
if features.get("ik"):  # Ceres
    from ._core import IkResult, IkStatus, InverseKinematics  # noqa: E402

    __all__ += ["IkResult", "IkStatus", "InverseKinematics"]
if features.get("simulation"):  # MuJoCo and Ceres
    from ._core import LoopMode, LoopStatus, LoopTick, Simulation, StopReason  # noqa: E402

    __all__ += ["LoopMode", "LoopStatus", "LoopTick", "Simulation", "StopReason"]
