"""Scripts written for Pinocchio (pinocchio_scripts/, in the style of Pinocchio's examples:
overview, inverse dynamics, inverse kinematics, derivatives, centroidal terms, RobotWrapper) run
unchanged under `python -m rigid.pinocchio`, and every number they compute equals Pinocchio's on
the same inputs to 1e-9 (script_harness.py); so do Pinocchio's own examples of dynamics and
kinematics (pinocchio_examples/, copied unchanged); skipped without Pinocchio."""

import os
import subprocess
import sys

import pytest

pytest.importorskip("pinocchio")
from conftest import robot_path  # noqa: E402
from script_harness import TOL, compare  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SCRIPTS = os.path.join(HERE, "pinocchio_scripts")


def urdf(name):
    return robot_path(name)[0]


def meshes():
    """The folder that holds `example-robot-data/robots/...` (package:// paths)."""
    return os.path.dirname(os.path.dirname(robot_path("ur5")[0].split("/robots/")[0] + "/robots"))


CASES = [
    ("overview_sample.py", []),
    ("overview_urdf.py", ["ur5"]),
    ("overview_urdf.py", ["talos"]),
    ("inverse_dynamics.py", ["panda", "MESHES"]),
    ("inverse_dynamics.py", ["solo12", "MESHES"]),
    ("inverse_kinematics.py", []),
    ("inverse_kinematics_3d.py", ["ur5"]),
    ("derivatives.py", []),
    ("centroidal.py", ["talos"]),
    ("centroidal.py", ["solo12"]),
    ("robot_wrapper.py", ["ur5", "MESHES"]),
]


def args_of(args):
    return [meshes() if a == "MESHES" else urdf(a) for a in args]


@pytest.mark.parametrize("script,args", CASES, ids=[f"{s}-{'-'.join(a)}" for s, a in CASES])
def test_script_numbers_equal_pinocchio(script, args):
    diffs, _ = compare(os.path.join(SCRIPTS, script), args_of(args))
    assert diffs, "no numbers compared"
    bad = {k: e for k, e in diffs.items() if not e <= TOL}
    assert not bad, f"{script}: " + ", ".join(f"{k} {e:.2e}" for k, e in bad.items())


EXAMPLES = os.path.join(HERE, "pinocchio_examples")
PINOCCHIO_EXAMPLES = sorted(f for f in os.listdir(EXAMPLES) if f.endswith(".py"))


@pytest.fixture(scope="module")
def examples_tree(tmp_path_factory):
    """Pinocchio's source layout: examples/ beside models/example-robot-data (the installed one)."""
    import shutil

    root = tmp_path_factory.mktemp("pinocchio")
    shutil.copytree(EXAMPLES, root / "examples")
    robots = robot_path("ur5")[0].split("/robots/")[0]
    (root / "models").mkdir()
    (root / "models" / "example-robot-data").symlink_to(robots)
    return root / "examples"


@pytest.mark.parametrize("script", PINOCCHIO_EXAMPLES)
def test_pinocchios_own_examples_equal_pinocchio(script, examples_tree):
    """Pinocchio's own examples (pinocchio_examples/README.md), unchanged: every number within
    1e-9 of Pinocchio's."""
    diffs, _ = compare(str(examples_tree / script), [])
    assert len(diffs) >= 2, f"{script}: only {sorted(diffs)} compared"
    bad = {k: e for k, e in diffs.items() if not e <= TOL}
    assert not bad, f"{script}: " + ", ".join(f"{k} {e:.2e}" for k, e in bad.items())


def test_the_runner_runs_a_script_unchanged_with_its_arguments():
    out = subprocess.run([sys.executable, "-m", "rigid.pinocchio",
                          os.path.join(SCRIPTS, "overview_urdf.py"), urdf("ur5")],
                         capture_output=True, text=True, check=True).stdout
    assert out.startswith("model name: ur5")
    assert "shoulder_pan_joint" in out and "tool0" in out


def test_the_runner_resolves_pinocchio_submodules_and_never_imports_pinocchio(tmp_path):
    script = tmp_path / "probe.py"
    script.write_text(
        "import sys\n"
        "import pinocchio as pin\n"
        "from pinocchio import SE3, rnea\n"
        "from pinocchio.utils import zero\n"
        "from pinocchio.robot_wrapper import RobotWrapper\n"
        "import pinocchio.visualize\n"
        "assert pin.__name__ == 'rigid.pinocchio', pin.__name__\n"
        "files = [getattr(m, '__file__', None) or '' for m in list(sys.modules.values())]\n"
        "assert not any('pinocchio_pywrap' in f or '/site-packages/pinocchio/' in f\n"
        "               for f in files), 'Pinocchio itself was imported'\n"
        "try:\n"
        "    pinocchio.visualize.MeshcatVisualizer()\n"
        "except NotImplementedError as e:\n"
        "    print('NotImplementedError:', e)\n"
        "print(sys.argv[1:])\n")
    out = subprocess.run([sys.executable, "-m", "rigid.pinocchio", str(script), "a", "b"],
                         capture_output=True, text=True, check=True).stdout
    assert "NotImplementedError: pinocchio.visualize.MeshcatVisualizer: rigid.pinocchio has no " \
           "viewer" in out
    assert "['a', 'b']" in out
