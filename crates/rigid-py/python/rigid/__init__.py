"""rigid: rigid-body dynamics from Rust, with Pinocchio's verbs and numpy arrays.

The names are those of the native module `rigid.rigid` (see the stubs, `__init__.pyi`);
`rigid.pinocchio` is a drop-in layer for Pinocchio scripts (`import rigid.pinocchio as pin`,
`python -m rigid.pinocchio script.py`).
"""

from . import rigid as _native
from .rigid import *  # noqa: F401,F403
from .rigid import __version__  # noqa: F401

__doc__ = _native.__doc__
