#!/usr/bin/env python3
"""Generate double_pendulum.json: SciPy's reference trajectory of the built-in double pendulum,
the fixture of the default (hermetic) run of crates/rigid/tests/it/simulation.rs
(`double_pendulum_matches_scipy_to_1e_8_over_5_s`).

    python3 -m venv /tmp/v && /tmp/v/bin/pip install -r scripts/requirements-test.txt
    /tmp/v/bin/python crates/rigid/tests/simulation/gen_double_pendulum.py

writes crates/rigid/tests/simulation/double_pendulum.json: the JSON that
`python3 double_pendulum.py 0.5 -0.3 0.2 0 5 50` prints (the closed-form equations integrated by
solve_ivp, DOP853 at rtol = atol = 1e-12: see double_pendulum.py), the arguments the test uses,
plus the arguments and the versions. The test compares rigid's RK4 run with it to 1e-8 (the
live run, RIGID_CROSSCHECK=1, also runs the script itself).
"""

import json
import os
import subprocess
import sys
from importlib import metadata

HERE = os.path.dirname(os.path.abspath(__file__))
ARGS = ["0.5", "-0.3", "0.2", "0", "5", "50"]


def main():
    out = subprocess.run([sys.executable, os.path.join(HERE, "double_pendulum.py"), *ARGS],
                         check=True, capture_output=True, text=True).stdout
    ref = json.loads(out)
    ref = dict(generator="crates/rigid/tests/simulation/gen_double_pendulum.py",
               args=ARGS, scipy_version=metadata.version("scipy"),
               numpy_version=metadata.version("numpy"), **ref)
    path = os.path.join(HERE, "double_pendulum.json")
    with open(path, "w") as f:
        json.dump(ref, f)
        f.write("\n")
    print(f"wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
