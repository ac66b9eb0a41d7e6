"""MuJoCo's side of the stacked scene (crates/rigid/tests/it/contact/world.rs): the MJCF file
given, 5 s at its own timestep, no control; prints the largest displacement of any free body's
origin (its CoM) from where it starts (m)."""
import sys

import mujoco
import numpy as np

model = mujoco.MjModel.from_xml_path(sys.argv[1])
data = mujoco.MjData(model)
mujoco.mj_forward(model, data)
free = [j for j in range(model.njnt) if model.jnt_type[j] == mujoco.mjtJoint.mjJNT_FREE]
adr = [model.jnt_qposadr[j] for j in free]
start = np.array([data.qpos[a:a + 3] for a in adr])
worst = 0.0
for _ in range(int(round(5.0 / model.opt.timestep))):
    mujoco.mj_step(model, data)
    now = np.array([data.qpos[a:a + 3] for a in adr])
    worst = max(worst, float(np.max(np.linalg.norm(now - start, axis=1))))
print(worst)
