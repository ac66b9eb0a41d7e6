#!/usr/bin/env python3
"""What a fresh output array costs `rigid.rnea_batch`, and when (BENCHMARKS.md, issue 28).

    python3 bench/first_touch.py                     # TALOS, 10^5 states, 5 rounds
    python3 bench/first_touch.py --states 20000 --pause 8

Needs `pip install ./crates/rigid-py` and example-robot-data (scripts/requirements-test.txt).

A batch call without `out=` returns a new `(N, nv)` array that numpy allocates (40 MB for
10^5 TALOS states), and the batch's threads write its pages for the first time. On a virtual
machine whose balloon device reports free pages to the host (virtio-balloon's
`VIRTIO_BALLOON_F_REPORTING`, feature bit 5), the guest kernel hands memory that the process
freed back to the host a few seconds later, and the next first touch of such pages faults on
the host too. Each round times, on the same inputs:

  - `out=`: the call writing one array kept by the process (no first touch), right after the
    call before and after a pause of `--pause` seconds of sleep (the control: a pause alone);
  - `fresh, right after`: with rigid's output cache off (`rigid.set_output_cache(0)`), a
    fresh output just after the previous fresh output was freed;
  - `fresh, after a pause`: the same after `--pause` seconds of sleep;
  - `fresh, cache: ...`: the same two with the cache on (opted in, `set_output_cache(1 << 30)`): the fresh output is
    the array the call before returned and the script dropped, so nothing is touched first;
  - numpy alone: the first touch (`a[:] = 1`) of a new array of the same size, right after and
    after the pause, and the same write to an array already touched, right after and after the
    pause.

It prints the median ns per state of each, and whether the balloon device reports free pages.
"""
import argparse
import glob
import os
import statistics
import sys
import time

import numpy as np

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "crates", "rigid", "tests", "pinocchio"))
from reference import ROBOTS, robots_dir  # noqa: E402


def free_page_reporting():
    """Whether a virtio balloon device (id 5) offers free page reporting (feature bit 5)."""
    for d in glob.glob("/sys/bus/virtio/devices/*"):
        try:
            device = open(os.path.join(d, "device")).read().strip()
            features = open(os.path.join(d, "features")).read().strip()
        except OSError:
            continue
        if int(device, 16) == 5:
            return len(features) > 5 and features[5] == "1"
    return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--robot", default="talos", choices=sorted(ROBOTS))
    ap.add_argument("--states", type=int, default=100000)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--pause", type=float, default=6.0, help="seconds of sleep before a call")
    args = ap.parse_args()

    rel, floating = ROBOTS[args.robot]
    m = rigid.Model.from_urdf(os.path.join(robots_dir(), rel), floating=floating)
    n, nq, nv = args.states, m.nq, m.nv
    rng = np.random.default_rng(0)
    Q = rng.uniform(-1, 1, (n, nq))
    if floating:
        Q[:, 3:7] /= np.linalg.norm(Q[:, 3:7], axis=1)[:, None]
    V, A = rng.uniform(-1, 1, (n, nv)), rng.uniform(-1, 1, (n, nv))
    TAU = np.empty((n, nv))
    TAU[:] = 0.0

    def batch(out=None):
        t0 = time.perf_counter()
        rigid.rnea_batch(m, Q, V, A, out=out)
        return time.perf_counter() - t0

    def touch(a):
        t0 = time.perf_counter()
        a[:] = 1.0
        return time.perf_counter() - t0

    batch(TAU)
    times = {k: [] for k in ["out=", "out=, after a pause", "fresh, right after",
                             "fresh, after a pause", "fresh, cache: right after",
                             "fresh, cache: after a pause", "numpy: write to a touched array",
                             "numpy: the same, after a pause", "numpy: first touch, right after",
                             "numpy: first touch, after a pause"]}
    for _ in range(args.rounds):
        times["out="].append(batch(TAU))
        time.sleep(args.pause)
        times["out=, after a pause"].append(batch(TAU))
        rigid.set_output_cache(0)  # every fresh output a new array
        batch()
        times["fresh, right after"].append(batch())
        time.sleep(args.pause)
        times["fresh, after a pause"].append(batch())
        rigid.set_output_cache(1 << 30)  # a fresh output from the array the last call dropped
        batch()
        times["fresh, cache: right after"].append(batch())
        time.sleep(args.pause)
        times["fresh, cache: after a pause"].append(batch())
        times["numpy: write to a touched array"].append(touch(TAU))
        time.sleep(args.pause)
        times["numpy: the same, after a pause"].append(touch(TAU))
        touch(np.empty((n, nv)))
        times["numpy: first touch, right after"].append(touch(np.empty((n, nv))))
        time.sleep(args.pause)
        times["numpy: first touch, after a pause"].append(touch(np.empty((n, nv))))

    print(f"rigid.rnea_batch, {args.robot} (nq {nq}, nv {nv}), {n} states "
          f"({n * nv * 8 / 1e6:.0f} MB of output), {args.rounds} rounds, pause {args.pause} s")
    print(f"free page reporting by a virtio balloon: {free_page_reporting()}")
    for k, t in times.items():
        print(f"  {k:36} {statistics.median(t) / n * 1e9:7.1f} ns/state "
              f"({min(t) / n * 1e9:.1f}–{max(t) / n * 1e9:.1f})")


if __name__ == "__main__":
    main()
