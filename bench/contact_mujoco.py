"""Simulation speed with ground contact: `rigid simulate MODEL.xml` against MuJoCo's `mj_step` on
the same MJCF file (gymnasium's humanoid and ant, dm_control's walker, falling from their qpos0
onto their floor and coming to rest; a heap of 27 free primitives the script writes, dropped onto
a floor), and Solo-12 from its URDF, standing and dropped with straight legs.

Both step 3 s at dt = 1 ms with no control: MuJoCo with the file's own options (Euler, its
default solver and pyramidal cones, the file's floor plane and every geom pair it collides, the
timestep set to 1 ms); rigid with its time-stepping scheme (semi-implicit, PGS on the exact
Coulomb cone, the file's own floor and every geom pair MuJoCo collides; `--ground-flag` runs a
rigid built before issue 47 with `--ground`: the ground `z = 0` against the model's geoms, no
self-contact). The two solve
different contact models (MuJoCo's soft convex one, rigid's hard complementarity one), so the
ratio compares the cost of a step, not identical trajectories; the contacts at the end are
printed for both. Reported: steps per second of the stepping loop (rigid's from its own summary
line, which excludes loading and, without --csv, writes nothing), the median of --rounds runs.

Solo-12 standing (also run by default; `--only solo` for it alone): example-robot-data's URDF compiled by MuJoCo
(`MjSpec.from_file` with `<compiler discardvisual="true"/>`, meshes as convex hulls as in rigid,
a free joint added to the base, a floor plane, self-contact off as in rigid), started at rigid's
set-down stance (the first row of `rigid simulate solo12 --floating --ground --controller pd
--target STANCE --csv`) and held for 3 s by MuJoCo position servos on the 12 joints (kp 20
N·m/rad, kv 0.5 N·m·s/rad; rigid: its stance controller, PD plus the contact feedforward). The
base height at the end is printed for both. Needs `pip install example-robot-data` in this
Python (or `EXAMPLE_ROBOT_DATA`; rigid must find the same files, e.g. `RIGID_PYTHON` set to it).

    python3 bench/contact_mujoco.py [--rigid target/release/rigid] [--rounds 5] [--only solo|mjcf]

Needs `pip install mujoco gymnasium` and a release build (`cargo build --release -p rigid-cli`).
"""

import argparse
import pathlib
import re
import statistics
import subprocess
import time

import mujoco

MODELS = ["humanoid.xml", "ant.xml", "walker.xml", "heap.xml"]
SECONDS, DT = 3.0, 1e-3


def assets():
    import gymnasium

    return pathlib.Path(gymnasium.__file__).parent / "envs/mujoco/assets"


def walker(tmp):
    """dm_control's walker.xml with the files it includes: from an installed dm_control, else
    from its wheel (`pip download dm_control --no-deps`, unpacked into `tmp`)."""
    try:
        import dm_control

        return pathlib.Path(dm_control.__file__).parent / "suite/walker.xml"
    except ImportError:
        import sys
        import zipfile

        subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--no-deps", "-d",
                        str(tmp), "dm_control==1.0.50"], check=True)
        with zipfile.ZipFile(next(tmp.glob("dm_control-*.whl"))) as z:
            for name in z.namelist():
                if name.startswith("dm_control/suite/walker.xml") or \
                        name.startswith("dm_control/suite/common/"):
                    z.extract(name, tmp)
        return tmp / "dm_control/suite/walker.xml"


def heap(tmp):
    """27 free primitives (boxes, spheres, capsules, cylinders in turn), a 3 x 3 x 3 grid 16 cm
    apart at random orientations, dropped onto a floor into a heap: every geom pair collides."""
    import random

    rng = random.Random(48)
    sizes = {"box": "0.06 0.05 0.04", "sphere": "0.05", "capsule": "0.03 0.05",
             "cylinder": "0.04 0.04"}
    kinds = list(sizes)
    bodies = []
    for n in range(27):
        i, j, k = n // 9, n // 3 % 3, n % 3
        x, y = [(c - 1) * 0.16 + rng.uniform(-0.02, 0.02) for c in (i, j)]
        euler = " ".join(f"{rng.uniform(-40, 40):.1f}" for _ in range(3))
        kind = kinds[n % 4]
        bodies.append(f'<body name="b{n}" pos="{x:.3f} {y:.3f} {0.12 + 0.16 * k:.3f}" '
                      f'euler="{euler}"><freejoint/><geom type="{kind}" size="{sizes[kind]}"/>'
                      f'</body>')
    path = tmp / "heap.xml"
    path.write_text('<mujoco model="heap of 27 primitives"><worldbody>'
                    '<geom name="floor" type="plane" size="0 0 1"/>'
                    + "".join(bodies) + "</worldbody></mujoco>\n")
    return path


def mjcf_path(name, tmp):
    if name == "walker.xml":
        return walker(tmp)
    if name == "heap.xml":
        return heap(tmp)
    return assets() / name


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
        [rigid, "simulate", str(path), *RIGID_GROUND, *RIGID_FLAGS, "--duration", str(SECONDS),
         "--dt", str(DT)],
        capture_output=True, text=True, check=True,
    ).stdout
    rate = float(re.search(r"\(([0-9.]+) steps/s\)", out).group(1))
    active = int(re.search(r"contacts at the end: (\d+) active", out).group(1))
    return rate, active


# rigid reads the file's own floor and collides every geom pair MuJoCo does (since issue 47);
# `--ground-flag` restores the older call for rigid builds before it (the ground z = 0 against
# the geoms, no self-contact)
RIGID_GROUND = []

# `--rigid-flag`: more options for every `rigid simulate` (`--no-polish`, `--contact-solver admm`)
RIGID_FLAGS = []

STANCE = [0, 0, 0.3, 0, 0, 0, 1, 0.1, 0.8, -1.6, -0.1, 0.8, -1.6, 0.1, -0.8, 1.6, -0.1, -0.8, 1.6]


def solo_args(seconds):
    return ["solo12", "--floating", "--ground", "--controller", "pd", "--target",
            ",".join(map(str, STANCE)), "--duration", str(seconds), "--dt", str(DT)]


def solo_start(rigid, tmp):
    """rigid's set-down stance: the first row of its CSV (q, rigid's layout, x-y-z-w)."""
    csv = tmp / "solo.csv"
    subprocess.run([rigid, "simulate", *solo_args(DT), "--csv", str(csv)], check=True,
                   capture_output=True)
    header, first = csv.read_text().splitlines()[:2]
    cols = dict(zip(header.split(","), map(float, first.split(","))))
    return [v for k, v in cols.items() if k.startswith("q_")]


def robots_dir():
    """example-robot-data's robots/ folder: $EXAMPLE_ROBOT_DATA, else where pip puts it under
    this Python's site-packages (two of the places rigid looks)."""
    import os
    import site
    import sysconfig

    if os.environ.get("EXAMPLE_ROBOT_DATA"):
        return pathlib.Path(os.environ["EXAMPLE_ROBOT_DATA"])
    for sp in site.getsitepackages() + [sysconfig.get_paths()["purelib"]]:
        p = pathlib.Path(sp) / "cmeel.prefix/share/example-robot-data/robots"
        if p.is_dir():
            return p
    raise SystemExit("no example-robot-data: pip install example-robot-data")


def solo_model(tmp, servos=True):
    robots = robots_dir()
    text = (robots / "solo_description/robots/solo12.urdf").read_text()
    text = text.replace("package://example-robot-data/robots/", str(robots) + "/")
    text = re.sub(r"(<robot[^>]*>)", r'\1<mujoco><compiler discardvisual="true" '
                  r'strippath="false"/></mujoco>', text, count=1)
    path = tmp / "solo12.urdf"
    path.write_text(text)
    spec = mujoco.MjSpec.from_file(str(path))
    spec.worldbody.first_body().add_freejoint()
    for g in spec.geoms:
        g.contype, g.conaffinity = 1, 0  # the robot touches the floor, not itself (as rigid)
    spec.worldbody.add_geom(type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1], contype=0,
                            conaffinity=1)
    for j in spec.joints if servos else []:
        if j.type == mujoco.mjtJoint.mjJNT_HINGE:
            a = spec.add_actuator(name=j.name, target=j.name, trntype=mujoco.mjtTrn.mjTRN_JOINT)
            a.set_to_position(kp=20.0, kv=0.5)
    return spec.compile()


def solo_mujoco_rate(m, start):
    m.opt.timestep = DT
    d = mujoco.MjData(m)
    x, y, z, qx, qy, qz, qw = start[:7]
    d.qpos[:] = [x, y, z, qw, qx, qy, qz, *start[7:]]
    if m.nu:
        d.ctrl[:] = start[7:]
    mujoco.mj_forward(m, d)
    n = round(SECONDS / DT)
    t0 = time.perf_counter()
    for _ in range(n):
        mujoco.mj_step(m, d)
    return n / (time.perf_counter() - t0), d.ncon, d.qpos[2]


# dropped from 40 cm with straight legs, no control on either side
DROP = [0, 0, 0.4, 0, 0, 0, 1] + [0] * 12


def solo_rigid_rate(rigid, dropped=False):
    args = solo_args(SECONDS) if not dropped else [
        "solo12", "--floating", "--ground", "--q0", ",".join(map(str, DROP)),
        "--duration", str(SECONDS), "--dt", str(DT)]
    out = subprocess.run([rigid, "simulate", *args, *RIGID_FLAGS], capture_output=True,
                         text=True, check=True).stdout
    rate = float(re.search(r"\(([0-9.]+) steps/s\)", out).group(1))
    active = int(re.search(r"contacts at the end: (\d+) active", out).group(1))
    z = float(re.search(r"root_joint=[^,]+,[^,]+,([^,]+),", out).group(1))
    return rate, active, z


def solo(args):
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        start = solo_start(args.rigid, tmp)
        cases = [("solo12.urdf standing (nv 18)", False, solo_model(tmp), start),
                 ("solo12.urdf dropped, straight legs (nv 18)", True,
                  solo_model(tmp, servos=False), DROP)]
        for label, dropped, m, q0 in cases:
            r, mj = [], []
            for k in range(args.rounds):
                pair = [lambda: solo_rigid_rate(args.rigid, dropped),
                        lambda: solo_mujoco_rate(m, q0)]
                res = [f() for f in (pair if k % 2 == 0 else pair[::-1])]
                rr, mm = res if k % 2 == 0 else res[::-1]
                r.append(rr)
                mj.append(mm)
            rr = statistics.median(x[0] for x in r)
            mm = statistics.median(x[0] for x in mj)
            print(f"| {label} | {rr:.0f} | {mm:.0f} | {mm / rr:.2f} | "
                  f"{r[-1][1]}, {mj[-1][1]} |")
            print(f"  base height: start {q0[2]:.4f} m, end rigid {r[-1][2]:.4f} m, "
                  f"MuJoCo {mj[-1][2]:.4f} m")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--rigid", default="target/release/rigid")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--only", choices=["solo", "mjcf"])
    ap.add_argument("--ground-flag", action="store_true",
                    help="pass --ground to rigid for the MJCF models (builds before issue 47)")
    ap.add_argument("--rigid-flag", action="append", default=[], metavar="FLAG",
                    help="an option for every rigid simulate (repeatable), e.g. --rigid-flag=--no-polish")
    args = ap.parse_args()
    RIGID_FLAGS.extend(args.rigid_flag)
    if args.ground_flag:
        RIGID_GROUND.append("--ground")
    print(f"mujoco {mujoco.__version__}; {SECONDS} s at dt = {DT} s; median of {args.rounds}")
    print("| model | rigid steps/s | MuJoCo steps/s | rigid / MuJoCo time | contacts at the end (rigid, MuJoCo) |")
    print("| --- | --- | --- | --- | --- |")
    import tempfile

    tmp = pathlib.Path(tempfile.mkdtemp())
    for name in MODELS if args.only != "solo" else []:
        path = mjcf_path(name, tmp)
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
    if args.only != "mjcf":
        solo(args)


if __name__ == "__main__":
    main()
