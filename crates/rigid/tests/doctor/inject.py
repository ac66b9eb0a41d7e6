#!/usr/bin/env python3
"""Fault-injection corpus for `rigid doctor` (crates/rigid/tests/it/doctor.rs).

Usage: python3 inject.py [--per-code N] [--seed S] > corpus.json

The committed corpus.json is this script's output with the defaults; the live run of the tests
(RIGID_CROSSCHECK=1) runs it again and compares, the numbers to 1e-9 relative (numpy may round
differently on another machine).

Takes the real URDF files of the robot-description packages of scripts/requirements-test.txt
(example-robot-data, icub-models, ...), picks links and injects into each one fault of the
doctor's list, written as a URDF would write it. Nothing here uses rigid: the faults are defined
independently of the code that must find them.

Prints one JSON object: {"seed", "faults": [{"package", "file", "link", "code", "variant",
"change", "inertial": {"mass", "xyz", "rpy", "ixx", "iyy", "izz", "ixy", "ixz", "iyz"}}]}, the
numbers as strings (as the faulted file would hold them). `file` is relative to the package's
folder; `change` is the relative change ||I_c' - I_c||_F / ||I_c||_F of the inertia about the
CoM in link axes (its materiality); `variant` says which form of the fault.

Which links: for every code but round_off and units_grams, a fault that changes the inertia about
the CoM by at least 30 % (MATERIAL; smaller changes are within the spread of CAD values); a link
with mass > 0, an inertia whose principal moments satisfy the strict
triangle inequality (the clean baseline; the test also requires the doctor to call it `ok`), and
at least one visual or collision shape. Links with the same numbers in several files (variants
of one robot) count once. At most 3 links per robot family and code, so that no robot dominates.

The faults (the doctor's codes):
- round_off: the link flattened to the plate nearest to it (the smallest eigenvalue of the second
  moment S_c = tr(I_c)/2 1 - I_c zero), computed with rounding: that eigenvalue at -4 ulps of
  tr(I about the link origin). The repair must not move the body by more than round-off.
- units_grams: mass x 1000.
- units_millimetres: CoM x 1000 and inertia x 1e6.
- about_link_origin: the inertia given about the link origin instead of the CoM (Steiner added),
  on links whose CoM is off the origin.
- product_sign: the three products of inertia negated, on links with products.
- rotation_lost: the inertia written in its principal axes with the rpy of those axes (the
  correct form), then either the rpy dropped ("dropped") or the link-axes matrix kept with the
  rpy ("applied_twice").
- digit_typo: one inertia entry x10, /10, or two different digits of its mantissa swapped.
- copied: the six inertia numbers of another (clean) link of the same robot whose mass differs by
  2x or more.
- zero_inertia: the six numbers zero.
"""

import glob
import json
import math
import os
import random
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "pinocchio"))
from packages import PACKAGES  # noqa: E402

# A fault counts when it changes the inertia about the CoM (link axes) by at least this much,
# relative (Frobenius norm): smaller changes are within the spread of CAD estimates.
MATERIAL = 0.3
CODES = ["round_off", "units_grams", "units_millimetres", "about_link_origin", "product_sign",
         "rotation_lost", "digit_typo", "copied", "zero_inertia"]
# Packages the corpus draws from (large sets of real links with meshes).
SOURCES = ["example-robot-data", "icub-models", "upkie-description", "jvrc-description",
           "gym-ignition-models", "cookie-description"]


def rpy_matrix(r, p, y):
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def matrix_rpy(R):
    # R = Rz(y) Ry(p) Rx(r)
    p = math.asin(max(-1.0, min(1.0, -R[2, 0])))
    if abs(math.cos(p)) > 1e-9:
        r = math.atan2(R[2, 1], R[2, 2])
        y = math.atan2(R[1, 0], R[0, 0])
    else:
        r = math.atan2(-R[1, 2], R[1, 1])
        y = 0.0
    return r, p, y


def fmt(x):
    return repr(float(x))


class Link:
    def __init__(self, package, root, path, el):
        self.package, self.file, self.name = package, os.path.relpath(path, root), el.get("name")
        self.family = self.file.split(os.sep)[0]
        ine = el.find("inertial")
        o = ine.find("origin") if ine is not None else None
        self.xyz = [float(v) for v in (o.get("xyz", "0 0 0") if o is not None else "0 0 0").split()]
        self.rpy = [float(v) for v in (o.get("rpy", "0 0 0") if o is not None else "0 0 0").split()]
        self.mass = float(ine.find("mass").get("value"))
        i = ine.find("inertia")
        self.e = {k: float(i.get(k)) for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")}
        self.text = {k: i.get(k).strip() for k in self.e}
        self.has_geometry = el.find("visual/geometry") is not None or el.find("collision/geometry") is not None

    def matrix(self):
        e = self.e
        return np.array([[e["ixx"], e["ixy"], e["ixz"]], [e["ixy"], e["iyy"], e["iyz"]],
                         [e["ixz"], e["iyz"], e["izz"]]])

    def link_axes(self):
        R = rpy_matrix(*self.rpy)
        return R @ self.matrix() @ R.T

    def key(self):
        return (self.name, self.mass, tuple(sorted(self.e.items())))

    def clean(self):
        if not (self.mass > 0 and self.has_geometry):
            return False
        lam = np.linalg.eigvalsh(self.link_axes())
        return lam[0] > 0 and lam[0] + lam[1] > lam[2] * (1 + 1e-6) and lam[0] > 1e-6 * lam[2]


def inertial(mass, xyz, rpy, I=None, text=None):
    if text is None:
        text = dict(ixx=fmt(I[0, 0]), iyy=fmt(I[1, 1]), izz=fmt(I[2, 2]), ixy=fmt(I[0, 1]),
                    ixz=fmt(I[0, 2]), iyz=fmt(I[1, 2]))
    d = dict(mass=fmt(mass), xyz=" ".join(fmt(v) for v in xyz), rpy=" ".join(fmt(v) for v in rpy))
    d.update(text)
    return d


def change(link, mass, xyz, rpy, I_written):
    """||I_c' - I_c|| / ||I_c|| in link axes (mass and CoM changes add their own terms)."""
    I0 = link.link_axes()
    I1 = rpy_matrix(*rpy) @ I_written @ rpy_matrix(*rpy).T
    return float(np.linalg.norm(I1 - I0) / np.linalg.norm(I0))


def inject(code, link, others, rng):
    """One fault: (variant, inertial dict, change), or None when it does not apply."""
    m, c, rpy, I = link.mass, np.array(link.xyz), link.rpy, link.matrix()
    if code == "round_off":
        # a body on the boundary (a plate: smallest second moment zero) computed with rounding:
        # the smallest eigenvalue of S_c = tr(I)/2 1 - I at -4 ulps of tr(I about the origin)
        IL = link.link_axes()
        S = 0.5 * np.trace(IL) * np.eye(3) - IL
        w, V = np.linalg.eigh(S)
        w = w.copy()
        w[0] = -4 * np.finfo(float).eps * (np.trace(IL) + 2 * m * c.dot(c))
        S2 = V @ np.diag(w) @ V.T
        IL2 = np.trace(S2) * np.eye(3) - S2
        R = rpy_matrix(*rpy)
        I2 = R.T @ IL2 @ R
        return "a plate, smallest second moment -4 ulps", inertial(m, c, rpy, I2), change(link, m, c, rpy, I2)
    if code == "units_grams":
        return "mass x1000", inertial(m * 1000, c, rpy, text=link.text), None
    if code == "units_millimetres":
        return "CoM x1000, inertia x1e6", inertial(m, c * 1000, rpy, I * 1e6), 1e6
    if code == "about_link_origin":
        if np.linalg.norm(c) < 1e-3:
            return None
        R = rpy_matrix(*rpy)
        S = m * (c.dot(c) * np.eye(3) - np.outer(c, c))
        I2 = I + R.T @ S @ R
        return "Steiner to the link origin added", inertial(m, c, rpy, I2), change(link, m, c, rpy, I2)
    if code == "product_sign":
        if max(abs(I[0, 1]), abs(I[0, 2]), abs(I[1, 2])) < 1e-3 * max(I[0, 0], I[1, 1], I[2, 2]):
            return None
        I2 = I.copy()
        for a, b in ((0, 1), (0, 2), (1, 2)):
            I2[a, b] = I2[b, a] = -I[a, b]
        return "products negated", inertial(m, c, rpy, I2), change(link, m, c, rpy, I2)
    if code == "rotation_lost":
        IL = link.link_axes()
        w, V = np.linalg.eigh(IL)
        if np.linalg.det(V) < 0:
            V[:, 0] = -V[:, 0]
        r = matrix_rpy(V)
        D = np.diag(w)
        if rng.random() < 0.5:
            return "dropped", inertial(m, c, [0, 0, 0], D), change(link, m, c, [0, 0, 0], D)
        return "applied_twice", inertial(m, c, r, IL), change(link, m, c, r, IL)
    if code == "digit_typo":
        big = max(abs(v) for v in link.e.values())
        keys = [k for k, v in link.e.items() if abs(v) >= 0.01 * big]
        k = rng.choice(sorted(keys))
        text = dict(link.text)
        kind = rng.choice(["x10", "/10", "swap"])
        if kind == "swap":
            s = text[k]
            end = min([i for i in (s.find("e"), s.find("E")) if i >= 0] or [len(s)])
            pos = [i for i in range(end) if s[i].isdigit()]
            pairs = [(i, j) for a, i in enumerate(pos) for j in pos[a + 1:] if s[i] != s[j]]
            if not pairs:
                return None
            i, j = rng.choice(pairs)
            b = list(s)
            b[i], b[j] = b[j], b[i]
            text[k] = "".join(b)
        else:
            x = float(text[k]) * (10.0 if kind == "x10" else 0.1)
            text[k] = fmt(x)
        e = {kk: float(v) for kk, v in text.items()}
        I2 = np.array([[e["ixx"], e["ixy"], e["ixz"]], [e["ixy"], e["iyy"], e["iyz"]],
                       [e["ixz"], e["iyz"], e["izz"]]])
        return f"{k} {kind}", inertial(m, c, rpy, text=text), change(link, m, c, rpy, I2)
    if code == "copied":
        cands = [o for o in others if o.name != link.name and o.clean()
                 and max(o.mass, m) >= 2 * min(o.mass, m) and o.e != link.e]
        if not cands:
            return None
        o = rng.choice(cands)
        return f"from {o.name}", inertial(m, c, rpy, text=o.text), change(link, m, c, rpy, o.matrix())
    if code == "zero_inertia":
        text = {k: "0" for k in link.e}
        return "all zero", inertial(m, c, rpy, text=text), 1.0
    raise ValueError(code)


def main():
    args = sys.argv[1:]
    per_code = int(args[args.index("--per-code") + 1]) if "--per-code" in args else 50
    seed = int(args[args.index("--seed") + 1]) if "--seed" in args else 1
    rng = random.Random(seed)
    links, robots = [], {}
    seen = set()
    for package in SOURCES:
        root = PACKAGES[package]()
        if root is None:
            sys.exit(f"{package} is not installed: pip install -r scripts/requirements-test.txt")
        for path in sorted(glob.glob(os.path.join(root, "**", "*.urdf"), recursive=True)):
            try:
                tree = ET.parse(path)
            except ET.ParseError:
                continue
            file_links = []
            for el in tree.getroot().findall("link"):
                if el.find("inertial/mass") is None or el.find("inertial/inertia") is None:
                    continue
                try:
                    link = Link(package, root, path, el)
                except (TypeError, ValueError, AttributeError):
                    continue
                file_links.append(link)
            robots[(package, os.path.relpath(path, root))] = file_links
            for link in file_links:
                if link.clean() and link.key() not in seen:
                    seen.add(link.key())
                    links.append(link)
    faults = []
    for code in CODES:
        pool = links[:]
        rng.shuffle(pool)
        per_family = {}
        for link in pool:
            if len([f for f in faults if f["code"] == code]) >= per_code:
                break
            fam = (link.package, link.family)
            if per_family.get(fam, 0) >= 3:
                continue
            got = inject(code, link, robots[(link.package, link.file)], rng)
            if got is None:
                continue
            variant, ine, ch = got
            if code not in ("round_off", "units_grams") and ch < MATERIAL:
                continue
            per_family[fam] = per_family.get(fam, 0) + 1
            faults.append(dict(package=link.package, file=link.file, link=link.name, code=code,
                               variant=variant, change=ch, inertial=ine))
    json.dump(dict(seed=seed, faults=faults), sys.stdout, indent=1, allow_nan=False)
    print()


if __name__ == "__main__":
    main()
