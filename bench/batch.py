#!/usr/bin/env python3
"""rigid's SIMD batch against Pinocchio's single call, side by side, in one run (BENCHMARKS.md).

    python3 bench/batch.py                         # 7 rounds, one core, ur5 panda solo12 talos
    python3 bench/batch.py --rounds 3 --models ur5,talos

Each round runs, back to back on one pinned core (the order alternating between rounds):
  - `rigid bench MODEL [--floating] --batch --threads 1 --json` (release build): states per
    second of the loop of single calls and of the SIMD batch on one thread, for RNEA, ABA, CRBA
    (the full matrices), CRBA's packed lower triangles and the RNEA derivatives;
  - Pinocchio's timing program (bench/pinocchio, the fastest of its build variants per
    algorithm): ns per single call of rnea, aba, crba, computeRNEADerivatives (which also fills
    M's upper triangle).
It prints, per model and algorithm, the median over rounds of:
  - batch / Pinocchio: rigid's batch time per state over Pinocchio's time per call (the issue's
    bar: at most 0.25). Pinocchio's `crba` computes M's upper triangle only, as the issue's CRBA
    kernel computes the lower one: `crba_lower` is the like-for-like column, and `crba` (the
    full symmetric matrices, nv² numbers per state against nv (nv + 1) / 2) does more;
  - batch / loop: rigid's batch states per second over its own loop of single calls (bar: 2).
The batch writes every state's result to a row-major output (nv numbers, or nv² for CRBA, or
nv (nv + 1) / 2 for the lower triangle); Pinocchio's call leaves it in its Data.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import compare  # noqa: E402  (the model manifest, Pinocchio's runner, core pinning)

# (rigid's batch key, Pinocchio's single-call key); Pinocchio's computeRNEADerivatives also
# fills M's upper triangle, which rigid's batch derivatives do not compute
ALGOS = [("rnea", "rnea"), ("aba", "aba"), ("crba", "crba"), ("crba_lower", "crba"),
         ("rnea_derivatives", "rnea_derivatives")]


def run_rigid_batch(model, states, reps):
    cmd = [os.path.join(ROOT, "target", "release", "rigid"), "bench", compare.rigid_model_arg(model),
           "--batch", "--threads", "1", "--json", "--states", str(states), "--repetitions", str(reps)]
    if model["floating"]:
        cmd.insert(3, "--floating")
    p = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    if p.returncode != 0:
        sys.exit("`%s` failed: %s" % (" ".join(cmd), p.stderr.strip()[-500:]))
    return json.loads(p.stdout)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--models", default="ur5,panda,solo12,talos")
    ap.add_argument("--states", type=int, default=1000)
    ap.add_argument("--reps", type=int, default=7, help="passes over the states per round (both sides)")
    ap.add_argument("--variants", default=os.environ.get("VARIANTS", "header lib"))
    ap.add_argument("--cpu", default="auto")
    ap.add_argument("--digits", type=int, default=2, help="decimals of the ratios printed")
    args = ap.parse_args()
    variants = args.variants.split()
    env = dict(os.environ, VARIANTS=" ".join(variants))
    if subprocess.run(["bash", os.path.join(HERE, "pinocchio", "run.sh"), "--build-only"], env=env).returncode:
        sys.exit("building Pinocchio's timing program failed")
    if subprocess.run(["cargo", "build", "--release", "-q", "-p", "rigid-cli"], cwd=ROOT).returncode:
        sys.exit("cargo build --release -p rigid-cli failed")
    models = compare.read_manifest(set(args.models.split(",")))
    pinned = compare.pin_to_core(args.cpu)
    vs_pin = {(m["name"], a): [] for m in models for a, _ in ALGOS}
    vs_loop = {(m["name"], a): [] for m in models for a, _ in ALGOS}
    lanes = None
    for r in range(args.rounds):
        for m in models:
            compare.log("[batch] round %d/%d %s" % (r + 1, args.rounds, m["name"]))
            sides = ["rigid", "pin"] if r % 2 == 0 else ["pin", "rigid"]
            pin = {}
            for side in sides:
                if side == "rigid":
                    rb = run_rigid_batch(m, args.states, args.reps)
                else:
                    for v in variants:
                        res = compare.run_pinocchio(v, m, args.reps, args.states)
                        if res:
                            for k, x in res["ns_per_call"].items():
                                pin[k] = min(pin.get(k, float("inf")), x)
            lanes = rb["lanes"]
            for a, pk in ALGOS:
                row = rb["states_per_second"][a]
                vs_pin[(m["name"], a)].append(1e9 / row["threads_1"] / pin[pk])
                vs_loop[(m["name"], a)].append(row["threads_1_vs_loop"])
    med = statistics.median
    print("rigid's SIMD batch (%d lanes, 1 thread) against Pinocchio %s (%s, fastest per algorithm); "
          "%d rounds, %d states, %d passes each, %s; load %s"
          % (lanes, compare.pin_version(), " / ".join(variants), args.rounds, args.states, args.reps, pinned,
             " ".join("%.2f" % x for x in os.getloadavg())))
    print()
    print("| model | nv | " + " | ".join("%s batch / Pinocchio" % a for a, _ in ALGOS) + " | "
          + " | ".join("%s batch / loop" % a for a, _ in ALGOS) + " |")
    print("|---|---:|" + "---:|" * (2 * len(ALGOS)))
    for m in models:
        f = "%%.%df" % args.digits
        cells = [(f + " (" + f + "–" + f + ")") % (med(x), min(x), max(x))
                 for x in (vs_pin[(m["name"], a)] for a, _ in ALGOS)]
        cells += ["%.2f" % med(vs_loop[(m["name"], a)]) for a, _ in ALGOS]
        print("| %s | %d | %s |" % (m["name"], m["nv"], " | ".join(cells)))


if __name__ == "__main__":
    main()
