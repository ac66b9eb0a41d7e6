"""Simulation speed of `rigid simulate` against MuJoCo's `mj_step` on the same URDF models.

For each robot of example-robot-data (UR5 fixed base, Talos on a free-flyer), both simulate 10 s
at dt = 1 ms with RK4 from the neutral configuration under gravity, with no controller and no
contact (the URDF's <visual> and <collision> elements are stripped before MuJoCo loads it, so
MuJoCo has no geometry to collide; rigid does not do contact). Reported: steps per second (wall
time of the stepping loop only; rigid's from its own summary line, which excludes loading).

    python3 bench/simulate_mujoco.py [--rigid target/release/rigid]

Needs `pip install mujoco example-robot-data` and a release build of rigid
(`cargo build --release -p rigid-cli`).
"""

import argparse
import pathlib
import re
import subprocess
import sys
import time

import mujoco

ROBOTS = {
    "ur5": ("ur_description/urdf/ur5_robot.urdf", False),
    "talos": ("talos_data/robots/talos_reduced.urdf", True),
}


def robots_dir():
    import sysconfig

    return pathlib.Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix/share/example-robot-data/robots"


def mujoco_model(path, floating):
    text = pathlib.Path(path).read_text()
    text = re.sub(r"<(visual|collision)\b.*?</\1>", "", text, flags=re.S)
    text = re.sub(r"<gazebo\b.*?</gazebo>", "", text, flags=re.S)
    text = re.sub(r"<transmission\b.*?</transmission>", "", text, flags=re.S)
    spec = mujoco.MjSpec.from_string(text)
    if floating:
        spec.worldbody.first_body().add_freejoint()
    m = spec.compile()
    m.opt.timestep = 1e-3
    m.opt.integrator = mujoco.mjtIntegrator.mjINT_RK4
    return m


def mujoco_rate(m, steps):
    d = mujoco.MjData(m)
    mujoco.mj_resetData(m, d)
    t0 = time.perf_counter()
    for _ in range(steps):
        mujoco.mj_step(m, d)
    return steps / (time.perf_counter() - t0)


def rigid_rate(exe, name, floating):
    args = [exe, "simulate", name, "--duration", "10", "--dt", "0.001", "--integrator", "rk4"]
    if floating:
        args.append("--floating")
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout
    return float(re.search(r"\(([0-9.]+) steps/s\)", out).group(1))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--rigid", default="target/release/rigid")
    p.add_argument("--steps", type=int, default=10000)
    a = p.parse_args()
    print("| robot | nv (rigid) | nv (MuJoCo) | rigid RK4 steps/s | MuJoCo mj_step RK4 steps/s | ratio |")
    print("| --- | --- | --- | --- | --- | --- |")
    for name, (rel, floating) in ROBOTS.items():
        m = mujoco_model(robots_dir() / rel, floating)
        mj = max(mujoco_rate(m, a.steps) for _ in range(3))
        rg = max(rigid_rate(a.rigid, name, floating) for _ in range(3))
        nv = subprocess.run([a.rigid, "model", name] + (["--floating"] if floating else []),
                            capture_output=True, text=True).stdout
        nv = re.search(r"nv\D*(\d+)", nv)
        print(f"| {name}{' (free-flyer)' if floating else ''} | {nv.group(1) if nv else '?'} | {m.nv} | {rg:,.0f} | {mj:,.0f} | {rg / mj:.2f} |")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
