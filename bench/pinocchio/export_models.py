#!/usr/bin/env python3
"""Parse the benchmark robots with Pinocchio's Python module and save them as
a plain joint-tree text file (see write_plain) for the C++ timing program.

Why: the C++ program never calls the wheel's prebuilt URDF parser, so it can be
built with any flags (-march=native included) without the Eigen-layout clash
between our build and the wheel's shared libraries.

Usage:
  export_models.py prefix              print the wheel's cmeel.prefix folder
  export_models.py robots              print example-robot-data's robots/ folder
  export_models.py export OUT_DIR      write OUT_DIR/NAME.model and OUT_DIR/manifest.tsv
"""
import math
import os
import site
import sys
import sysconfig

HERE = os.path.dirname(os.path.abspath(__file__))
MODELS_TSV = os.path.join(os.path.dirname(HERE), "models.tsv")


def cmeel_prefix():
    """The site-packages/cmeel.prefix folder that holds include/pinocchio."""
    candidates = []
    for key in ("purelib", "platlib"):
        candidates.append(sysconfig.get_paths()[key])
    try:
        candidates += site.getsitepackages()
    except AttributeError:
        pass
    candidates.append(site.getusersitepackages())
    for sp in candidates:
        p = os.path.join(sp, "cmeel.prefix")
        if os.path.isdir(os.path.join(p, "include", "pinocchio")):
            return p
    sys.exit("cmeel.prefix with include/pinocchio not found in " + ", ".join(candidates))


def robots_dir():
    return os.path.join(cmeel_prefix(), "share", "example-robot-data", "robots")


def read_models():
    rows = []
    with open(MODELS_TSV) as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            name, urdf, floating = line.split("\t")
            rows.append((name, urdf, floating == "1"))
    return rows


def puma560(pin):
    """PUMA 560 from standard DH parameters (Corke's Robotics Toolbox values:
    Armstrong/Khatib/Burdick 1986 kinematics, Armstrong's link masses, inertias
    and centres of mass). Each link frame i is the DH frame i; joint i rotates
    about z of frame i-1, i.e. joint i's frame = DH frame i-1 and the body
    attached to it is link i expressed in DH frame i."""
    import numpy as np

    # a, alpha, d (standard DH), and the link's mass, com (in DH frame i), inertia diag (at com)
    dh = [
        (0.0, math.pi / 2, 0.0),
        (0.4318, 0.0, 0.0),
        (0.0203, -math.pi / 2, 0.15005),
        (0.0, math.pi / 2, 0.4318),
        (0.0, -math.pi / 2, 0.0),
        (0.0, 0.0, 0.0),
    ]
    mass = [0.0, 17.4, 4.8, 0.82, 0.34, 0.09]
    com = [
        (0.0, 0.0, 0.0),
        (-0.3638, 0.006, 0.2275),
        (-0.0203, -0.0141, 0.070),
        (0.0, 0.019, 0.0),
        (0.0, 0.0, 0.0),
        (0.0, 0.0, 0.032),
    ]
    inertia = [
        (0.0, 0.35, 0.0),
        (0.13, 0.524, 0.539),
        (0.066, 0.086, 0.0125),
        (1.8e-3, 1.3e-3, 1.8e-3),
        (0.3e-3, 0.4e-3, 0.3e-3),
        (0.15e-3, 0.15e-3, 0.04e-3),
    ]

    def dh_transform(a, alpha, d):
        # standard DH, joint angle 0: Rz(0) Tz(d) Tx(a) Rx(alpha)
        ca, sa = math.cos(alpha), math.sin(alpha)
        R = np.array([[1, 0, 0], [0, ca, -sa], [0, sa, ca]])
        return pin.SE3(R, np.array([a, 0.0, d]))

    model = pin.Model()
    model.name = "puma560"
    parent = 0
    placement = pin.SE3.Identity()  # placement of joint i's frame (DH frame i-1) in parent joint frame
    for i in range(6):
        jid = model.addJoint(parent, pin.JointModelRZ(), placement, "joint%d" % (i + 1))
        # body i lives in DH frame i = (joint frame) * DH(a, alpha, d)
        T = dh_transform(*dh[i])
        I_c = np.diag(inertia[i])
        body_in_dh = pin.Inertia(mass[i], np.array(com[i]), I_c)
        model.appendBodyToJoint(jid, T.act(body_in_dh), pin.SE3.Identity())
        parent = jid
        placement = T
    model.lowerPositionLimit = np.full(6, -math.pi)
    model.upperPositionLimit = np.full(6, math.pi)
    return model


JOINT_TYPES = {
    "JointModelRX": "RX", "JointModelRY": "RY", "JointModelRZ": "RZ",
    "JointModelPX": "PX", "JointModelPY": "PY", "JointModelPZ": "PZ",
    "JointModelRevoluteUnaligned": "RU", "JointModelPrismaticUnaligned": "PU",
    "JointModelFreeFlyer": "FF",
}


def write_plain(pin, model, path):
    """A plain-text joint tree that timings.cpp rebuilds with Model::addJoint and
    Model::appendBodyToJoint: per joint its type (and axis), parent, placement in
    the parent joint frame, the joint's total (already merged) spatial inertia and
    its position limits. This is the same Model Pinocchio's URDF parser builds
    (same joints, placements, inertias), without compiling Pinocchio's
    boost::serialization code into the timing program (that alone costs minutes
    of compile time). A last line holds one state and Pinocchio's RNEA torque on
    it, which timings.cpp checks after loading."""
    import numpy as np

    def fmt(xs):
        return " ".join("%.17g" % float(x) for x in xs)

    lines = ["%d %d %d" % (model.nq, model.nv, model.njoints)]
    for j in range(1, model.njoints):
        jm = model.joints[j]
        kind = JOINT_TYPES.get(jm.shortname())
        if kind is None:
            sys.exit("unsupported joint type %s in %s" % (jm.shortname(), model.name))
        axis = np.zeros(3)
        if kind in ("RU", "PU"):
            axis = np.array(jm.extract().axis)
        M = model.jointPlacements[j]
        Y = model.inertias[j]
        I = Y.inertia
        lo = model.lowerPositionLimit[jm.idx_q:jm.idx_q + jm.nq]
        hi = model.upperPositionLimit[jm.idx_q:jm.idx_q + jm.nq]
        lines.append(" ".join([
            kind, str(model.parents[j]), fmt(axis),
            fmt(M.rotation.reshape(-1)), fmt(M.translation),
            fmt([Y.mass]), fmt(Y.lever),
            fmt([I[0, 0], I[0, 1], I[1, 1], I[0, 2], I[1, 2], I[2, 2]]),
            fmt(lo), fmt(hi),
        ]))
    # reference state for the load check
    rng = np.random.default_rng(7)
    q = pin.randomConfiguration(model)
    v = rng.uniform(-1, 1, model.nv)
    a = rng.uniform(-1, 1, model.nv)
    tau = pin.rnea(model, model.createData(), q, v, a)
    lines.append("check " + " ".join(fmt(x) for x in (q, v, a, tau)))
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def export(out_dir):
    import numpy as np
    import pinocchio as pin

    os.makedirs(out_dir, exist_ok=True)
    rob = robots_dir()
    manifest = []
    for name, urdf, floating in read_models():
        if urdf.startswith("builtin:"):
            if urdf != "builtin:puma560":
                sys.exit("unknown builtin model " + urdf)
            model = puma560(pin)
            path = urdf
        else:
            path = os.path.join(rob, urdf)
            if floating:
                model = pin.buildModelFromUrdf(path, pin.JointModelFreeFlyer())
            else:
                model = pin.buildModelFromUrdf(path)
        if floating:
            # finite bounds for randomConfiguration: base position in [-1, 1]^3,
            # quaternion components in [-1, 1] (the sample is normalised anyway)
            lo = model.lowerPositionLimit.copy()
            hi = model.upperPositionLimit.copy()
            lo[:7] = -1.0
            hi[:7] = 1.0
            model.lowerPositionLimit = lo
            model.upperPositionLimit = hi
        lo, hi = model.lowerPositionLimit, model.upperPositionLimit
        if not (np.all(np.isfinite(lo)) and np.all(np.isfinite(hi))):
            # clamp any remaining unbounded joint to [-pi, pi]
            lo = np.where(np.isfinite(lo) & (np.abs(lo) < 1e100), lo, -math.pi)
            hi = np.where(np.isfinite(hi) & (np.abs(hi) < 1e100), hi, math.pi)
            model.lowerPositionLimit, model.upperPositionLimit = lo, hi
        out = os.path.join(out_dir, name + ".model")
        write_plain(pin, model, out)
        manifest.append((name, model.nq, model.nv, int(floating), path, out))
    with open(os.path.join(out_dir, "manifest.tsv"), "w") as f:
        for row in manifest:
            f.write("\t".join(str(x) for x in row) + "\n")
    for row in manifest:
        print("%-12s nq=%-3d nv=%-3d floating=%d  %s" % row[:5], file=sys.stderr)


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "prefix":
        print(cmeel_prefix())
    elif cmd == "robots":
        print(robots_dir())
    elif cmd == "export" and len(sys.argv) == 3:
        export(sys.argv[2])
    else:
        sys.exit(__doc__)
