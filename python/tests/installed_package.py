"""The installed Python package (cmake --install) runs from the prefix: it is imported from
there, finds walkgen's data in <prefix>/share/walkgen (not the source tree), and works.
Run by the ctest packaging_python_installed (python/CMakeLists.txt) with
PYTHONPATH=<prefix>/<python dir>; not a pytest module (it needs the installed prefix)."""

import os
import sys

prefix = os.path.realpath(sys.argv[1])
os.environ.pop("WALKGEN_DATA_DIR", None)
import walkgen  # noqa: E402

assert os.path.realpath(walkgen.__file__).startswith(prefix), walkgen.__file__
robot = walkgen.RobotDescription.find("walkgen_humanoid")
assert os.path.realpath(robot.urdf_path).startswith(prefix), robot.urdf_path
assert os.path.realpath(os.environ["WALKGEN_DATA_DIR"]) == os.path.join(prefix, "share/walkgen")
tree = walkgen.KinematicTree.from_description(robot)
com = tree.forward_kinematics(tree.stand_configuration(robot)).center_of_mass()
mpc = walkgen.WalkingMpc(walkgen.WalkingSettings.load(
    os.path.join(os.environ["WALKGEN_DATA_DIR"], "configs", "hrp2.yaml")))
mpc.set_command(0.2)
assert mpc.solve().ok
print(f"installed walkgen {walkgen.__version__} from {os.path.dirname(walkgen.__file__)}: "
      f"{robot.name} with {tree.num_joints} joints, CoM height {com[2]:.3f} m; NMPC solved")
