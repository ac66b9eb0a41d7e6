"""The Ray example (examples/python/ray_batch.py) on a local Ray with two CPUs, bounded in time:
tasks with the model in the object store and threads= = num_cpus, and an actor that loads its
model from a file, all equal to the local batch bit for bit. Skipped without ray."""

import os
import subprocess
import sys

import pytest

pytest.importorskip("ray")

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "..", "examples", "python",
                                        "ray_batch.py"))


def test_ray_example_runs_on_a_local_ray_with_two_cpus():
    out = subprocess.run([sys.executable, EXAMPLE, "--cpus", "2", "--states", "4000",
                          "--tasks", "4"], capture_output=True, text=True, timeout=240,
                         env={**os.environ, "RAY_USAGE_STATS_ENABLED": "0"})
    assert out.returncode == 0, out.stdout + out.stderr
    assert "equal the local batch bit for bit" in out.stdout
    assert "pool of 1 thread(s)" in out.stdout
