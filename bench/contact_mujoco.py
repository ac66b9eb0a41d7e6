"""Simulation speed with ground contact: `rigid simulate MODEL.xml --ground` against MuJoCo's
`mj_step` on the same MJCF file (gymnasium's humanoid and ant, falling from their qpos0 onto the
ground and coming to rest).

Both step 3 s at dt = 1 ms with no control: MuJoCo with the file's own options (Euler, its
default solver and pyramidal cones, the file's floor plane and every geom pair it collides, the
timestep set to 1 ms); rigid with its time-stepping scheme (semi-implicit, PGS on the exact
Coulomb cone, the ground `z = 0` against the model's geoms, no self-contact). The two solve
different contact models (MuJoCo's soft convex one, rigid's hard complementarity one), so the
ratio compares the cost of a step, not identical trajectories; the contacts at the end are
printed for both. Reported: steps per second of the stepping loop (rigid's from its own summary
line, which excludes loading and, without --csv, writes nothing), the median of --rounds runs.

    python3 bench/contact_mujoco.py [--rigid target/release/rigid] [--rounds 5]

Needs `pip install mujoco gymnasium` and a release build (`cargo build --release -p rigid-cli`).
"""

import argparse
import pathlib
import re
import statistics
import subprocess
import time

import mujoco

MODELS = ["humanoid.xml", "ant.xml"]
SECONDS, DT = 3.0, 1e-3


def assets():
    import gymnasium

    return pathlib.Path(gymnasium.__file__).parent / "envs/mujoco/assets"


def mujoco_rate(path):
    m = mujoco.MjModel.from_xml_path(str(path))
    m.opt.timestep = DT
    d = mujoco.MjData(m)
    mujoco.mj_forward(m, d)
    n = round(SECONDS / DT)
    start = time.perf_counter()
    for _ in range(n):
        mujoco.mj_step(m, d)
    return n / (time.perf_counter() - start), d.ncon


def rigid_rate(rigid, path):
    out = subprocess.run(
        [rigid, "simulate", str(path), "--ground", "--duration", str(SECONDS), "--dt", str(DT)],
        capture_output=True, text=True, check=True,
    ).stdout
    rate = float(re.search(r"\(([0-9.]+) steps/s\)", out).group(1))
    active = int(re.search(r"contacts at the end: (\d+) active", out).group(1))
    return rate, active


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rigid", default="target/release/rigid")
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args()
    print(f"mujoco {mujoco.__version__}; {SECONDS} s at dt = {DT} s; median of {args.rounds}")
    print("| model | rigid steps/s | MuJoCo steps/s | rigid / MuJoCo time | contacts at the end (rigid, MuJoCo) |")
    print("| --- | --- | --- | --- | --- |")
    for name in MODELS:
        path = assets() / name
        r, mj = [], []
        for k in range(args.rounds):
            # alternate which side goes first, so that noise hits both alike
            pair = [lambda: rigid_rate(args.rigid, path), lambda: mujoco_rate(path)]
            order = pair if k % 2 == 0 else pair[::-1]
            res = [f() for f in order]
            rr, mm = (res if k % 2 == 0 else res[::-1])
            r.append(rr)
            mj.append(mm)
        rr = statistics.median(x[0] for x in r)
        mm = statistics.median(x[0] for x in mj)
        print(f"| {name} | {rr:.0f} | {mm:.0f} | {mm / rr:.2f} | {r[-1][1]}, {mj[-1][1]} |")


if __name__ == "__main__":
    main()
