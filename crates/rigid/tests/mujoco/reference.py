"""MuJoCo as the reference for rigid's MJCF importer and MuJoCo layout.

Two modes, run with an interpreter that has `mujoco` (pip) and numpy:

    python reference.py fixtures   # rewrite fixtures/*.json from the models in models/
    python reference.py live       # one JSON line per MJCF file of the installed packages

`fixtures` compiles every top-level model of `models/` (a file with a <worldbody>; the others are
included pieces) and writes, for a few random states in MuJoCo's coordinates, what MuJoCo computes:
the mass matrix `mj_fullM` (armature included), the bias `qfrc_bias` (Coriolis, centrifugal and
gravity forces; no springs, damping or gravity compensation), the gravity-only bias (`qvel = 0`),
the inverse dynamics `M qacc + qfrc_bias` and the forward dynamics `M⁻¹ (qfrc - qfrc_bias)`.
`crates/rigid/tests/mjcf.rs` checks rigid against them in every `cargo test`.

`live` does the same for every `.xml` file of the description packages installed next to
`mujoco` (gymnasium, dm_control, robosuite, brax, mujoco's mjx, metaworld, gymnasium_robotics,
installed with `pip install --no-deps`), printing for each file either MuJoCo's compile error or
the references; `tests/mjcf.rs` runs it when `RIGID_CROSSCHECK=1` (interpreter `RIGID_PYTHON`).
"""

import glob
import json
import os
import sys

import mujoco
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGES = [
    "gymnasium",
    "dm_control",
    "robosuite",
    "brax",
    "mujoco/mjx",
    "metaworld",
    "gymnasium_robotics",
]
FREE, BALL = 0, 1
MESH = 7


def random_states(m, n, seed):
    """`n` states `(qpos, qvel, qacc, qfrc)`: each hinge and slide within ±1 of `qpos0`, each ball
    and free joint a uniformly random orientation, free positions in ±1 m, velocities,
    accelerations and forces uniform in ±1."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        q = m.qpos0.copy()
        for j in range(m.njnt):
            a, t = m.jnt_qposadr[j], m.jnt_type[j]
            if t == FREE:
                q[a : a + 3] = rng.uniform(-1, 1, 3)
                x = rng.normal(size=4)
                q[a + 3 : a + 7] = x / np.linalg.norm(x)
            elif t == BALL:
                x = rng.normal(size=4)
                q[a : a + 4] = x / np.linalg.norm(x)
            else:
                q[a] += rng.uniform(-1, 1)
        v, acc, f = (rng.uniform(-1, 1, m.nv) for _ in range(3))
        out.append((q, v, acc, f))
    return out


def reference(m, qpos, qvel, qacc, qfrc):
    """MuJoCo's dynamics at one state."""
    d = mujoco.MjData(m)
    d.qpos[:] = qpos
    d.qvel[:] = qvel
    mujoco.mj_forward(m, d)
    M = np.zeros((m.nv, m.nv))
    mujoco.mj_fullM(m, d, M)
    bias = d.qfrc_bias.copy()
    d.qvel[:] = 0
    mujoco.mj_forward(m, d)
    gravity = d.qfrc_bias.copy()
    return {
        "qpos": list(qpos),
        "qvel": list(qvel),
        "qacc": list(qacc),
        "qfrc": list(qfrc),
        "mass_matrix": M.tolist(),
        "bias": list(bias),
        "gravity": list(gravity),
        "rnea": list(M @ qacc + bias),
        "aba": forward(M, qfrc - bias),
    }


def forward(M, rhs):
    """`M⁻¹ rhs`, or None when `M` is singular (MuJoCo loads a few such models)."""
    try:
        return list(np.linalg.solve(M, rhs)) if len(rhs) else []
    except np.linalg.LinAlgError:
        return None


def mesh_inertia(m):
    """Whether a mesh geom sits in a moving body (its inertia then carries float32 vertices)."""
    return any(
        m.geom_type[g] == MESH and m.body_weldid[m.geom_bodyid[g]] != 0 for g in range(m.ngeom)
    )


def model_data(m, path, seed, n):
    return {
        "file": path,
        "mujoco": mujoco.__version__,
        "nq": int(m.nq),
        "nv": int(m.nv),
        "joints": [mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, j) for j in range(m.njnt)],
        "qpos0": list(m.qpos0),
        "mesh_inertia": mesh_inertia(m),
        "total_mass": float(sum(m.body_mass[1:])),
        "states": [reference(m, *s) for s in random_states(m, n, seed)],
    }


def top_level(path):
    with open(path, encoding="utf-8") as f:
        return "<worldbody" in f.read()


def fixtures():
    models = os.path.join(HERE, "models")
    out = os.path.join(HERE, "fixtures")
    os.makedirs(out, exist_ok=True)
    for path in sorted(glob.glob(os.path.join(models, "*.xml"))):
        if not top_level(path):
            continue
        m = mujoco.MjModel.from_xml_path(path)
        name = os.path.splitext(os.path.basename(path))[0]
        data = model_data(m, "models/" + os.path.basename(path), seed=7, n=3)
        with open(os.path.join(out, name + ".json"), "w", encoding="utf-8") as f:
            json.dump(data, f, indent=None)
            f.write("\n")
        print(f"fixtures/{name}.json: nq = {m.nq}, nv = {m.nv}", file=sys.stderr)


def live():
    site = os.path.dirname(os.path.dirname(os.path.abspath(mujoco.__file__)))
    for package in PACKAGES:
        files = sorted(glob.glob(os.path.join(site, package, "**", "*.xml"), recursive=True))
        for path in files:
            row = {"package": package, "file": path}
            try:
                m = mujoco.MjModel.from_xml_path(path)
            except Exception as e:  # MuJoCo's compile error: the file is not a model it loads
                row["error"] = str(e).strip().split("\n")[0]
                print(json.dumps(row), flush=True)
                continue
            row.update(model_data(m, path, seed=0, n=3))
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    mode = sys.argv[1] if len(sys.argv) > 1 else ""
    if mode == "fixtures":
        fixtures()
    elif mode == "live":
        live()
    else:
        sys.exit(__doc__)
