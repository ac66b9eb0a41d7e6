"""The package: the example script runs (gravity compensation holds the Panda still), and
the type stubs ship with the module and declare exactly its public names."""

import os
import re
import subprocess
import sys

from conftest import ROOT


def test_gravity_compensation_example_holds_the_arm():
    script = os.path.join(ROOT, "examples", "python", "gravity_compensation.py")
    out = subprocess.run([sys.executable, script, "--seconds", "0.5"], capture_output=True,
                         text=True, check=True).stdout
    drift = {name.strip(): float(x) for name, x in
             re.findall(r"^\s*(.+?): \|q\(T\) - q\(0\)\| = (\S+) rad", out, re.M)}
    assert set(drift) == {"no torque", "tau = g(q)", "tau = 0.9 g(q)"}
    assert drift["tau = g(q)"] < 1e-9 < 1e-2 < drift["tau = 0.9 g(q)"] < drift["no torque"]
    assert "M(q) diagonal" in out


def test_the_stubs_declare_exactly_the_public_names_and_ship_with_the_module():
    import ast

    import rigid
    stub = os.path.join(os.path.dirname(rigid.__file__), "__init__.pyi")
    assert os.path.exists(stub) and os.path.exists(os.path.join(os.path.dirname(stub),
                                                                "py.typed"))
    tree = ast.parse(open(stub, encoding="utf-8").read())
    declared = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            declared.add(node.name)
        elif isinstance(node, (ast.Assign, ast.AnnAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            declared.update(t.id for t in targets if isinstance(t, ast.Name))
    helpers = {"ArrayLike", "Vector", "Matrix", "Path", "Layout", "Frame", "Spec"}
    public = {n for n in dir(rigid.rigid) if not n.startswith("_")} | {"__version__"}
    assert declared - helpers == public
    for name in public - {"__version__", "UrdfWarning"}:
        assert getattr(rigid, name).__doc__, f"rigid.{name} has no docstring"
