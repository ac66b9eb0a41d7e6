"""``python -m rigid.pinocchio script.py [args]``: runs a script written for Pinocchio with its
``import pinocchio`` (``import pinocchio as pin``, ``from pinocchio import ...``,
``pinocchio.utils``, ``pinocchio.robot_wrapper``, ...) resolved to ``rigid.pinocchio``.

An import finder placed first on ``sys.meta_path`` maps the top-level name ``pinocchio`` and its
submodules to ``rigid.pinocchio`` and its submodules; a submodule the layer does not have
is a module whose every attribute raises NotImplementedError when used. ``import hppfcl`` and
``import coal`` give ``rigid.pinocchio.fcl`` (hpp-fcl's shapes, for geometry objects). Then the script runs as ``__main__`` with ``sys.argv = [script, *args]``.
"""

import importlib
import importlib.abc
import importlib.util
import os
import runpy
import sys
import types

LAYER = "rigid.pinocchio"
#: hpp-fcl's and coal's module names: their shapes are rigid.pinocchio.fcl's
_FCL = ("hppfcl", "coal")
_SUBMODULES = {"utils": "utils", "robot_wrapper": "robot_wrapper", "shortcuts": "loaders",
               "explog": "explog", "rpy": None, "deprecated": None, "deprecation": None}


class _Alias(importlib.abc.Loader):
    """Loads ``pinocchio[.sub]`` as the layer's module (the same object)."""

    def __init__(self, target):
        self.target = target

    def create_module(self, spec):
        return self.target

    def exec_module(self, module):
        pass


class _Missing(types.ModuleType):
    def __getattr__(self, attr):
        if attr.startswith("__"):
            raise AttributeError(attr)
        layer = importlib.import_module(LAYER)
        return layer._Missing(f"{self.__name__.split('.', 1)[1]}.{attr}")


class PinocchioFinder(importlib.abc.MetaPathFinder):
    """Finds ``pinocchio`` and ``pinocchio.*`` in ``rigid.pinocchio``."""

    def find_spec(self, fullname, path=None, target=None):
        top = fullname.split(".")[0]
        if top in _FCL:
            return importlib.util.spec_from_loader(
                fullname, _Alias(importlib.import_module(f"{LAYER}.fcl")))
        if top != "pinocchio":
            return None
        layer = importlib.import_module(LAYER)
        if fullname == "pinocchio":
            module = layer
        else:
            sub = fullname.split(".", 1)[1]
            head = sub.split(".")[0]
            name = _SUBMODULES.get(head, head)
            if head == "rpy":
                module = _module_of(fullname, layer.rpy)
            elif name is not None and importlib.util.find_spec(f"{LAYER}.{name}") is not None:
                module = importlib.import_module(f"{LAYER}.{name}")
            elif name is None:
                module = layer
            else:
                module = _Missing(fullname)
        return importlib.util.spec_from_loader(fullname, _Alias(module))


def _module_of(name, obj):
    m = types.ModuleType(name)
    for k in dir(obj):
        if not k.startswith("_"):
            setattr(m, k, getattr(obj, k))
    return m


def install():
    """Makes ``import pinocchio`` give rigid.pinocchio in this process."""
    if not any(isinstance(f, PinocchioFinder) for f in sys.meta_path):
        sys.meta_path.insert(0, PinocchioFinder())
    for k in [k for k in sys.modules if k.split(".")[0] in ("pinocchio",) + _FCL]:
        del sys.modules[k]


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if argv else 2
    script = argv[0]
    if not os.path.isfile(script):
        print(f"python -m rigid.pinocchio: no such script: {script}", file=sys.stderr)
        return 2
    install()
    sys.argv = list(argv)
    sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
    runpy.run_path(script, run_name="__main__")
    return 0


if __name__ == "__main__":
    sys.exit(main())
