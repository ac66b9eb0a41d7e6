#!/usr/bin/env python3
"""rigid vs MuJoCo on MJCF models, side by side, in one run (table in bench/MUJOCO.md).

    python3 bench/compare_mujoco.py                       # 7 rounds, humanoid, ant, panda, dog
    python3 bench/compare_mujoco.py --rounds 3 --models humanoid,dog

Both sides load the same MJCF file (rigid with its importer, whose mass matrix and bias equal
MuJoCo's to round-off) and time the same work per state, from the configuration up:

| key | rigid (`rigid bench MODEL --json --only rnea,crba`) | MuJoCo (`bench/mujoco/timings.c`, C, the wheel's libmujoco) |
| --- | --- | --- |
| RNEA | `rnea(q, v, a)`: `M a + c + g` | `mj_kinematics`, `mj_comPos`, `mj_comVel`, `mj_rne(flg_acc=1)`: `M a + c + g` |
| CRBA | `crba(q)`: the dense symmetric `M` | `mj_kinematics`, `mj_comPos`, `mj_crb`, `mj_fullM`: the dense `M` |
| CRBA (sparse) | | the same without `mj_fullM`: MuJoCo's own sparse `M`, which its solvers factor |

Each side draws 1000 random states once and reports the median over 21 passes of the time per
call (the method of `rigid bench`, which the C harness copies); MuJoCo is called from C, so no
interpreter overhead is in its numbers. The two sides take turns round by round (alternating who
goes first), pinned to the idlest core, and each reported number is the median over rounds; the
ratio is the median of the per-round ratios rigid / MuJoCo (below 1: rigid is faster).

Needs `pip install mujoco` (its wheel ships libmujoco and the headers), the description packages
of the models (`pip install --no-deps gymnasium robosuite dm-control`), a C compiler and cargo.
"""
import argparse
import json
import os
import platform
import statistics
import subprocess
import sys
import sysconfig
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SITE = sysconfig.get_paths()["purelib"]
MODELS = {
    "humanoid": "gymnasium/envs/mujoco/assets/humanoid.xml",
    "ant": "gymnasium/envs/mujoco/assets/ant.xml",
    "panda": "robosuite/models/assets/robots/panda/robot.xml",
    "dog": "dm_control/suite/dog.xml",
}


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def build():
    import mujoco

    lib = os.path.dirname(mujoco.__file__)
    so = [f for f in os.listdir(lib) if f.startswith("libmujoco.so")]
    if not so:
        sys.exit("no libmujoco.so in %s" % lib)
    out = os.path.join(HERE, "mujoco", "build")
    os.makedirs(out, exist_ok=True)
    exe = os.path.join(out, "timings")
    cmd = ["cc", "-O2", os.path.join(HERE, "mujoco", "timings.c"), "-I", os.path.join(lib, "include"),
           "-L", lib, "-l:" + sorted(so)[-1], "-Wl,-rpath," + lib, "-lm", "-o", exe]
    subprocess.run(cmd, check=True)
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "rigid-cli"], cwd=ROOT, check=True)
    return exe, os.path.join(ROOT, "target", "release", "rigid"), mujoco.__version__


def idlest_cpu(allowed, seconds=0.5):
    def idle():
        out = {}
        with open("/proc/stat") as f:
            for line in f:
                p = line.split()
                if p[0].startswith("cpu") and p[0] != "cpu":
                    out[int(p[0][3:])] = int(p[4]) + int(p[5])
        return out
    a = idle()
    time.sleep(seconds)
    b = idle()
    return max(sorted(allowed), key=lambda c: b.get(c, 0) - a.get(c, 0))


def run_mujoco(exe, path):
    out = subprocess.run([exe, path, "1000", "21", "7"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def run_rigid(exe, path):
    out = subprocess.run([exe, "bench", path, "--json", "--only", "rnea,crba", "--states", "1000",
                          "--repetitions", "21"], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)["ns_per_call"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--models", default=",".join(MODELS))
    args = ap.parse_args()
    names = args.models.split(",")
    paths = {n: os.path.join(SITE, MODELS[n]) for n in names}
    missing = [p for p in paths.values() if not os.path.isfile(p)]
    if missing:
        sys.exit("not installed: %s" % ", ".join(missing))
    mj_exe, rigid_exe, version = build()
    if hasattr(os, "sched_setaffinity"):
        cpu = idlest_cpu(os.sched_getaffinity(0))
        os.sched_setaffinity(0, {cpu})
        log("pinned to core %d" % cpu)
    raw = {n: {"mujoco": [], "rigid": []} for n in names}
    nv = {}
    for r in range(args.rounds):
        for n in names:
            first_rigid = (r % 2) == 0
            sides = ["rigid", "mujoco"] if first_rigid else ["mujoco", "rigid"]
            for side in sides:
                if side == "rigid":
                    raw[n]["rigid"].append(run_rigid(rigid_exe, paths[n]))
                else:
                    m = run_mujoco(mj_exe, paths[n])
                    nv[n] = m["nv"]
                    raw[n]["mujoco"].append(m)
            log("round %d/%d %s: rigid rnea %.0f crba %.0f | mujoco rnea %.0f crba %.0f ns" % (
                r + 1, args.rounds, n, raw[n]["rigid"][-1]["rnea"], raw[n]["rigid"][-1]["crba"],
                raw[n]["mujoco"][-1]["rnea"], raw[n]["mujoco"][-1]["crba"]))
    med = statistics.median
    print("MuJoCo %s (C, the pip wheel's libmujoco) vs rigid %s, %s, %s, %d rounds" % (
        version, subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                                capture_output=True, text=True).stdout.strip(),
        platform.processor() or platform.machine(), cpu_model(), args.rounds))
    print()
    print("| model | nv | RNEA rigid (ns) | RNEA MuJoCo (ns) | rigid / MuJoCo | CRBA rigid (ns) "
          "| CRBA MuJoCo, dense (ns) | rigid / MuJoCo | MuJoCo sparse M (ns) |")
    print("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    for n in names:
        rg, mj = raw[n]["rigid"], raw[n]["mujoco"]
        ratio = lambda k: med([a[k] / b[k] for a, b in zip(rg, mj)])
        print("| %s | %d | %.0f | %.0f | %.2f | %.0f | %.0f | %.2f | %.0f |" % (
            n, nv[n], med([a["rnea"] for a in rg]), med([b["rnea"] for b in mj]), ratio("rnea"),
            med([a["crba"] for a in rg]), med([b["crba"] for b in mj]), ratio("crba"),
            med([b["crba_sparse"] for b in mj])))


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown CPU"


if __name__ == "__main__":
    main()
