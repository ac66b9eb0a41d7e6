"""rigid on Ray: batches of inverse dynamics in Ray tasks and in an actor.

    pip install ray ./crates/rigid-py
    python examples/python/ray_batch.py                       # a local Ray with 2 CPUs
    python examples/python/ray_batch.py --address auto        # an existing cluster

Three patterns:

1. The model goes into Ray's object store once (``ray.put(model)``: a ``rigid.Model`` pickles
   through its JSON form, bit for bit); every task gets the reference, and Ray deserialises it
   once per worker process and object, not once per state.
2. Each task asks Ray for ``num_cpus`` CPUs and passes the same number to the batch verb as
   ``threads=``: without it, rayon inside the task would start one thread per core of the
   machine, whatever Ray reserved. The states also go into the object store once; a task reads
   its rows as a read-only numpy view (zero-copy), which the batch verbs accept.
3. An actor loads its model from a file itself (for a model that a worker should read from a
   shared disk rather than receive), and serves batches.

The results are checked against one local ``rigid.rnea_batch`` call, bit for bit, and the
throughputs printed. On a cluster the same code runs with ``--address`` (``ray.init(address=)``):
the model file of pattern 3 must then be readable by the workers.
"""

import argparse
import os
import sys
import time
import warnings

import numpy as np
import ray

import rigid

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def default_model():
    """TALOS on a free-flyer from example-robot-data, or the repository's test robot."""
    import glob
    import site

    for root in [sys.prefix] + site.getsitepackages():
        pattern = "cmeel.prefix/share/example-robot-data/robots/talos_data/robots/talos_reduced.urdf"
        for path in glob.glob(os.path.join(root, pattern)):
            return path
    return os.path.join(ROOT, "crates", "rigid", "tests", "pinocchio", "all_joints.urdf")


def load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return rigid.Model.from_urdf(path, floating=True)


@ray.remote
def rnea_rows(model, Q, V, A, start, stop, threads):
    """Inverse dynamics of rows start..stop, on `threads` threads (= the task's num_cpus)."""
    # Q, V, A: read-only numpy arrays mapped from the object store (no copy)
    return rigid.rnea_batch(model, Q[start:stop], V[start:stop], A[start:stop], threads=threads)


@ray.remote
class Dynamics:
    """An actor that reads its model from a file and serves batches."""

    def __init__(self, path, threads):
        self.model = load(path)
        self.threads = threads

    def rnea(self, Q, V, A):
        return rigid.rnea_batch(self.model, Q, V, A, threads=self.threads)

    def threads_used(self):
        """The size of the thread pool the batch verbs run on here (rayon's count)."""
        return rigid._pool_threads(self.threads)[0]


def states(model, n, seed=0):
    rigid.seed(seed)
    rng = np.random.default_rng(seed)
    Q = np.array([rigid.random_configuration(model) for _ in range(n)])
    return Q, rng.uniform(-1, 1, (n, model.nv)), rng.uniform(-1, 1, (n, model.nv))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", default=default_model(), help="a URDF file (floating base)")
    ap.add_argument("--states", type=int, default=20000)
    ap.add_argument("--tasks", type=int, default=8, help="tasks the states are cut into")
    ap.add_argument("--cpus", type=int, default=2, help="CPUs of the local Ray")
    ap.add_argument("--task-cpus", type=int, default=1, help="num_cpus (= threads) per task")
    ap.add_argument("--address", default=None, help="an existing Ray cluster (e.g. auto)")
    args = ap.parse_args(argv)

    if args.address:
        ray.init(address=args.address)
    else:
        ray.init(num_cpus=args.cpus, include_dashboard=False, log_to_driver=False)
    try:
        model = load(args.model)
        Q, V, A = states(model, args.states)
        t0 = time.perf_counter()
        local = rigid.rnea_batch(model, Q, V, A)
        t_local = time.perf_counter() - t0

        # 1 + 2: the model and the states in the object store once; tasks of task_cpus CPUs
        t0 = time.perf_counter()
        model_ref = ray.put(model)
        Q_ref, V_ref, A_ref = ray.put(Q), ray.put(V), ray.put(A)
        cuts = np.linspace(0, len(Q), args.tasks + 1).astype(int)
        task = rnea_rows.options(num_cpus=args.task_cpus)
        futures = [task.remote(model_ref, Q_ref, V_ref, A_ref, int(a), int(b), args.task_cpus)
                   for a, b in zip(cuts[:-1], cuts[1:])]
        tau = np.concatenate(ray.get(futures))
        t_tasks = time.perf_counter() - t0
        assert tau.tobytes() == local.tobytes(), "tasks differ from the local batch"

        # 3: an actor that loads the model from the file
        actor = Dynamics.options(num_cpus=args.task_cpus).remote(args.model, args.task_cpus)
        pool = ray.get(actor.threads_used.remote())
        assert pool == args.task_cpus, f"the actor's pool has {pool} threads"
        t0 = time.perf_counter()
        tau_actor = ray.get(actor.rnea.remote(Q_ref, V_ref, A_ref))
        t_actor = time.perf_counter() - t0
        assert tau_actor.tobytes() == local.tobytes(), "the actor differs from the local batch"

        n = len(Q)
        print(f"model {os.path.basename(args.model)}: nq = {model.nq}, nv = {model.nv}; "
              f"{n} states")
        print(f"local rnea_batch (all cores)        : {n / t_local:12.0f} states/s")
        print(f"{args.tasks} Ray tasks x {args.task_cpus} CPU (threads={args.task_cpus}): "
              f"{n / t_tasks:12.0f} states/s (first call: workers start, model shipped)")
        print(f"actor (model from the file)         : {n / t_actor:12.0f} states/s, "
              f"pool of {pool} thread(s)")
        print("tasks and actor equal the local batch bit for bit")
        return 0
    finally:
        ray.shutdown()


if __name__ == "__main__":
    sys.exit(main())
