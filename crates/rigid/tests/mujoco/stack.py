"""MuJoCo's side of the stacked scene (crates/rigid/tests/it/contact/world.rs): the MJCF file
given, 5 s at its own timestep, no control; prints, for each free body in the file's order, the
largest displacement of its origin (its CoM) from where it starts (m). MuJoCo's contacts are
soft: a loaded stack sinks into itself by a fraction of a millimetre, and a capsule lying on a
face creeps sideways (4.8 mm in 5 s on stack.xml), while rigid's hard contacts hold both to
round-off."""
import sys

import mujoco
import numpy as np

model = mujoco.MjModel.from_xml_path(sys.argv[1])
data = mujoco.MjData(model)
mujoco.mj_forward(model, data)
free = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
adr = [model.jnt_qposadr[j] for j in free]
start = np.array([data.qpos[a:a + 3] for a in adr])
worst = np.zeros(len(adr))
for _ in range(int(round(5.0 / model.opt.timestep))):
    mujoco.mj_step(model, data)
    now = np.array([data.qpos[a:a + 3] for a in adr])
    worst = np.maximum(worst, np.linalg.norm(now - start, axis=1))
print(" ".join(repr(float(w)) for w in worst))
