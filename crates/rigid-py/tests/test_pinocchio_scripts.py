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
from conftest import ROBOTS, robot_path, robots_dir  # noqa: E402
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
    ("geometry_placements.py", ["ur5", "MESHES"]),
    ("geometry_placements.py", ["talos", "MESHES"]),
    ("collision_pairs.py", ["ERD:romeo_description/urdf/romeo_small.urdf",
                            "ERD:romeo_description/srdf/romeo.srdf", "half_sitting", "MESHES"]),
    ("distances.py", []),
    ("model_surgery.py", ["ur5", "MESHES", "tool0", "panda"]),
    ("model_surgery.py", ["panda", "MESHES", "panda_link8", "ur5"]),
    ("contact_statics.py", ["solo12", "FL_FOOT", "FR_FOOT", "HL_FOOT", "HR_FOOT"]),
    ("parallel.py", ["talos"]),
    ("simulation.py", []),
]

# hpp-fcl's GJK stops at a distance tolerance of 1e-6 (m), parry's on round-off: distances
# between boxes, capsules and cylinders agree to that
TOLERANCE = {"distances.py": 2e-6}


def args_of(args):
    """Robot names as their URDF files, MESHES as the mesh folder, ERD:path as that file of
    example-robot-data's robots/, anything else as itself (a frame, a foot, a state's name)."""
    def one(a):
        if a == "MESHES":
            return meshes()
        if a.startswith("ERD:"):
            return os.path.join(robots_dir(), a[4:])
        return urdf(a) if a in ROBOTS else a
    return [one(a) for a in args]


@pytest.mark.parametrize("script,args", CASES, ids=[f"{s}-{'-'.join(a)}" for s, a in CASES])
def test_script_numbers_equal_pinocchio(script, args):
    diffs, _ = compare(os.path.join(SCRIPTS, script), args_of(args))
    assert diffs, "no numbers compared"
    bad = {k: e for k, e in diffs.items() if not e <= TOLERANCE.get(script, TOL)}
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


# Pinocchio's pool defaults to one model (its wheel's OpenMP aside), and the example asks for
# omp_get_max_threads() threads: "The pool is too small" with Pinocchio itself on 2 cores
EXAMPLE_ENV = {"run-algo-in-parallel.py": {"OMP_NUM_THREADS": "1"}}


@pytest.mark.parametrize("script", PINOCCHIO_EXAMPLES)
def test_pinocchios_own_examples_equal_pinocchio(script, examples_tree):
    """Pinocchio's own examples (pinocchio_examples/README.md), unchanged: every number within
    1e-9 of Pinocchio's."""
    env = {**os.environ, **EXAMPLE_ENV[script]} if script in EXAMPLE_ENV else None
    diffs, _ = compare(str(examples_tree / script), [], env=env)
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
        "               or '/site-packages/hppfcl/' in f or '/site-packages/coal/' in f\n"
        "               for f in files), 'Pinocchio or hpp-fcl itself was imported'\n"
        "import hppfcl, coal\n"
        "assert hppfcl.__name__ == coal.__name__ == 'rigid.pinocchio.fcl', hppfcl.__name__\n"
        "try:\n"
        "    pinocchio.visualize.MeshcatVisualizer()\n"
        "except ImportError as e:\n"
        "    print('ImportError:', e)\n"
        "print(sys.argv[1:])\n")
    out = subprocess.run([sys.executable, "-m", "rigid.pinocchio", str(script), "a", "b"],
                         capture_output=True, text=True, check=True).stdout
    assert "ImportError: Error while importing the viewer client." in out
    assert "rigid.pinocchio has no live viewer" in out
    assert "['a', 'b']" in out


# the examples beyond dynamics (pinocchio_examples/README.md)
BEYOND_DYNAMICS = ["append-urdf-model-with-another-model.py", "build-reduced-model.py",
                   "static-contact-dynamics.py", "collisions.py", "run-algo-in-parallel.py",
                   "simulation-contact-dynamics.py", "simulation-pendulum.py",
                   "simulation-inverted-pendulum.py", "geometry-models.py"]


@pytest.mark.parametrize("script", BEYOND_DYNAMICS)
def test_examples_run_where_pinocchio_and_hppfcl_cannot_be_imported(script, examples_tree,
                                                                    tmp_path):
    """`python -m rigid.pinocchio EXAMPLE` exits 0 in an environment where `import pinocchio`,
    `import hppfcl` and `import coal` would fail (packages of those names that raise, first on
    the path): the layer alone runs them."""
    for name in ("pinocchio", "hppfcl", "coal"):
        (tmp_path / name).mkdir()
        (tmp_path / name / "__init__.py").write_text(
            f"raise ImportError('{name} is not installed here')\n")
    env = {**os.environ, "PYTHONPATH": str(tmp_path), "OMP_NUM_THREADS": "1"}
    # from Pinocchio's source root, as its examples are run (they find models/ from there)
    p = subprocess.run([sys.executable, "-m", "rigid.pinocchio", f"examples/{script}"],
                       capture_output=True, text=True, env=env, cwd=examples_tree.parent,
                       timeout=600)
    assert p.returncode == 0, f"{script}:\n{p.stdout[-2000:]}\n{p.stderr[-2000:]}"
