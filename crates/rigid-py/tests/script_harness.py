#!/usr/bin/env python3
"""Runs a script written for Pinocchio twice, with Pinocchio and with rigid.pinocchio (through
`python -m rigid.pinocchio`'s own import hook, `rigid.pinocchio.__main__.main`), on the same
inputs, and compares every number the script leaves in its globals.

    python crates/rigid-py/tests/script_harness.py SCRIPT [ARGS...]

prints one line per global (name, shape, max relative difference) and the largest difference;
exit 1 if it exceeds 1e-9. The pytest suite (test_pinocchio_scripts.py) runs the scripts of
`pinocchio_scripts/` with it.

Also compared: a `Model`'s sizes, joint placements, bodies (not the universe's) and frames, and a
`GeometryModel`'s objects (placements, joints, frames, mesh scales and colours) and pairs.

Same inputs: each run starts with `numpy.random.seed(0)`; the configurations
`randomConfiguration` draws in the Pinocchio run are replayed, in order, in the rigid run (the
generators differ); a model of `buildSampleModelHumanoidRandom` (random placements and inertias)
is rebuilt in the rigid run from the Pinocchio run's, joint by joint with the layer's `addJoint`,
`appendBodyToJoint`, `addJointFrame` and `addBodyFrame`. Compared: every global that holds
numbers (floats, numpy arrays, SE3, Motion, Force, Inertia, and lists or tuples of them); the
difference is max |rigid - Pinocchio| / max(1, max |Pinocchio|).
"""

import json
import os
import pickle
import subprocess
import sys
import tempfile

import numpy as np

TOL = 1e-9


def _plain(x, depth=0):
    """The numbers of `x` as a float array, or None."""
    if depth > 3:
        return None
    if isinstance(x, bool):
        return None
    if isinstance(x, (int, float, np.floating, np.integer)):
        return np.array([float(x)])
    if isinstance(x, np.ndarray) and x.dtype.kind in "fiu":
        return np.asarray(x, dtype=float)
    for attr in ("homogeneous", "vector"):
        if type(x).__name__ in ("SE3", "Motion", "Force") and hasattr(x, attr):
            return np.asarray(getattr(x, attr), dtype=float)
    if type(x).__name__ == "Inertia":
        return np.asarray(x.matrix(), dtype=float)
    if type(x).__name__ == "Model" and hasattr(x, "jointPlacements"):
        # sizes, joint placements and bodies (not inertias[0], which rigid does not keep)
        parts = [np.array([x.nq, x.nv, x.njoints, x.nframes], dtype=float)]
        parts += [np.asarray(x.jointPlacements[i].homogeneous, float).ravel()
                  for i in range(x.njoints)]
        parts += [np.asarray(x.inertias[i].matrix(), float).ravel() for i in range(1, x.njoints)]
        parts += [np.asarray(f.placement.homogeneous, float).ravel() for f in x.frames]
        parts += [np.array([f.parentJoint for f in x.frames], dtype=float)]
        return np.concatenate(parts)
    if type(x).__name__ == "GeometryModel":
        g = x.geometryObjects
        return np.concatenate([np.array([x.ngeoms, len(x.collisionPairs)], dtype=float)]
                              + [np.asarray(o.placement.homogeneous, float).ravel() for o in g]
                              + [np.array([o.parentJoint for o in g], dtype=float),
                                 np.array([o.parentFrame for o in g], dtype=float)]
                              + [np.asarray(o.meshScale, float) for o in g]
                              + [np.asarray(o.meshColor, float) for o in g]
                              + [np.array([[p.first, p.second] for p in x.collisionPairs],
                                          dtype=float).reshape(-1)])
    if type(x).__name__.startswith("StdVec_"):  # Pinocchio's vectors of its objects
        x = list(x)
    if isinstance(x, (list, tuple)) and x:
        parts = [_plain(y, depth + 1) for y in x]
        if all(p is not None for p in parts):
            return np.concatenate([p.ravel() for p in parts])
    return None


def _model_description(model):
    """What the rigid run needs to rebuild a Pinocchio model joint by joint."""
    joints = []
    for i in range(1, model.njoints):
        j = model.joints[i]
        Y = model.inertias[i]
        iq, iv = j.idx_q, j.idx_v
        joints.append(dict(
            name=model.names[i], parent=int(model.parents[i]), type=j.shortname(),
            placement=model.jointPlacements[i].homogeneous.tolist(),
            inertia=[Y.mass, Y.lever.tolist(), Y.inertia.tolist()],
            lower=model.lowerPositionLimit[iq:iq + j.nq].tolist(),
            upper=model.upperPositionLimit[iq:iq + j.nq].tolist(),
            velocity=model.velocityLimit[iv:iv + j.nv].tolist(),
            effort=model.effortLimit[iv:iv + j.nv].tolist()))
    frames = [dict(name=f.name, parent=int(f.parentJoint), type=int(f.type),
                   placement=f.placement.homogeneous.tolist()) for f in model.frames[1:]]
    return dict(joints=joints, frames=frames)


def _rebuild(pin, desc):
    """The layer's model of a recorded description (joints, bodies, frames in order)."""
    m = pin.Model()
    for j in desc["joints"]:
        jm = getattr(pin, j["type"])()
        m.addJoint(j["parent"], jm, pin.SE3(np.array(j["placement"])), j["name"],
                   np.array(j["effort"]), np.array(j["velocity"]), np.array(j["lower"]),
                   np.array(j["upper"]))
    for i, j in enumerate(desc["joints"], start=1):
        mass, c, I = j["inertia"]
        m.appendBodyToJoint(i, pin.Inertia(mass, np.array(c), np.array(I)), pin.SE3.Identity())
    for f in desc["frames"]:
        m.addFrame(pin.Frame(f["name"], f["parent"], 0, pin.SE3(np.array(f["placement"])),
                             pin.FrameType(f["type"])))
    return m


def _exec(script, args):
    """Runs `script` as `__main__` with `args`; its globals, also when it ends by `sys.exit(0)`
    (Pinocchio's examples leave that way when no viewer is installed)."""
    sys.argv = [script] + args
    sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
    with open(script) as f:
        code = compile(f.read(), script, "exec")
    g = {"__name__": "__main__", "__file__": script, "__builtins__": __builtins__}
    try:
        exec(code, g)
    except SystemExit as e:
        if e.code not in (None, 0):
            raise
    return g


def _run(side, script, args, record_path):
    """In this process: `side` is "pinocchio" or "rigid"; writes the globals to `out`."""
    np.random.seed(0)
    if side == "pinocchio":
        import pinocchio as pin

        rec = {"configurations": [], "models": []}
        rc, hr = pin.randomConfiguration, pin.buildSampleModelHumanoidRandom

        def random_configuration(*a, **k):
            q = rc(*a, **k)
            rec["configurations"].append(np.asarray(q).tolist())
            return q

        def humanoid_random(*a, **k):
            m = hr(*a, **k)
            rec["models"].append(_model_description(m))
            return m

        pin.randomConfiguration = random_configuration
        pin.buildSampleModelHumanoidRandom = humanoid_random
        g = _exec(script, args)
        with open(record_path, "w") as f:
            json.dump(rec, f)
    else:
        import rigid.pinocchio as pin
        from rigid.pinocchio.__main__ import install

        with open(record_path) as f:
            rec = json.load(f)
        qs, models = list(rec["configurations"]), list(rec["models"])

        def random_configuration(*a, **k):
            return np.array(qs.pop(0))

        def humanoid_random(*a, **k):
            return _rebuild(pin, models.pop(0))

        pin.randomConfiguration = random_configuration
        pin.buildSampleModelHumanoidRandom = humanoid_random
        install()
        g = _exec(script, args)
        # the rigid run computed with the layer: `pinocchio` is rigid.pinocchio and Pinocchio's
        # own library (or hpp-fcl, coal) was never loaded (else equal numbers would prove nothing)
        assert sys.modules["pinocchio"] is pin, sys.modules["pinocchio"]
        loaded = [k for k, m in list(sys.modules.items()) if "pinocchio_pywrap" in k
                  or any(f"{os.sep}site-packages{os.sep}{p}{os.sep}"
                         in (getattr(m, "__file__", None) or "")
                         for p in ("pinocchio", "hppfcl", "coal"))]
        assert not loaded, f"Pinocchio's own modules were loaded in the rigid run: {loaded}"
    return {k: v for k, v in ((k, _plain(v)) for k, v in g.items() if not k.startswith("_"))
            if v is not None}


def compare(script, args=(), python=sys.executable, env=None):
    """Runs `script` with each library in a fresh interpreter; returns ({name: difference},
    stdout of the rigid run)."""
    args = list(args)
    with tempfile.TemporaryDirectory() as tmp:
        rec = os.path.join(tmp, "record.json")
        outs, stdout = {}, ""
        for side in ("pinocchio", "rigid"):
            out = os.path.join(tmp, f"{side}.pkl")
            code = ("import pickle, sys; sys.path.insert(0, %r); import script_harness as h; "
                    "g = h._run(%r, %r, %r, %r); pickle.dump(g, open(%r, 'wb'))"
                    % (os.path.dirname(os.path.abspath(__file__)), side, script, args, rec, out))
            p = subprocess.run([python, "-c", code], capture_output=True, text=True, env=env,
                               cwd=os.path.dirname(os.path.abspath(script)))
            if p.returncode != 0:
                raise RuntimeError(f"{script} with {side} failed:\n{p.stdout}\n{p.stderr}")
            stdout = p.stdout
            with open(out, "rb") as f:
                outs[side] = pickle.load(f)
    ref, got = outs["pinocchio"], outs["rigid"]
    diffs = {}
    for k in sorted(set(ref) | set(got)):
        if k not in ref or k not in got:
            diffs[k] = np.inf
            continue
        a, b = got[k], ref[k]
        if a.shape != b.shape:
            diffs[k] = np.inf
            continue
        diffs[k] = 0.0 if a.size == 0 else float(
            np.max(np.abs(a - b)) / max(1.0, float(np.max(np.abs(b)))))
    return diffs, stdout


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    diffs, _ = compare(sys.argv[1], sys.argv[2:])
    for k, e in diffs.items():
        print(f"  {k:<28} {e:.2e}")
    worst = max(diffs.values(), default=0.0)
    print(f"{os.path.basename(sys.argv[1])}: {len(diffs)} globals compared, largest relative "
          f"difference {worst:.2e}")
    return 0 if worst <= TOL else 1


if __name__ == "__main__":
    sys.exit(main())
