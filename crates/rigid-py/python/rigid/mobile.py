"""rigid.mobile: wheeled mobile robots (Modern Robotics ch. 13) and the capstone.

The names of `rigid::mobile` in Rust, from the native submodule: `Base` (`Base.mecanum(r, l, w)`,
`Base.omni3(r, d)`, `Base.diff_drive(r, track)`, `Base.car(r, track, wheelbase)`, with `H(phi)`,
`F`, `F6`, `odometry(q, dtheta)`, `constraint(q)`), `MobileManipulator` (`youbot()`, `forward`,
`jacobian`, `next_state`, `feedback`), `Feedback` (PI with its integral), `pick_and_place`,
`capstone`, and `drive` (a robot file on the ground, its wheels under velocity control); and the product of exponentials of a chain given by screw axes (`fkin_body`,
`fkin_space`, `jacobian_body`, `jacobian_space`), with `Blist` a 6 x n array of columns as in the
Modern Robotics code library. Chassis configurations are (phi, x, y); twists angular first.

    >>> import rigid.mobile as mobile
    >>> mobile.Base.mecanum(0.0475, 0.235, 0.15).H(0.0).shape
    (4, 3)
"""

from .rigid import _mobile as _native

Base = _native.Base
MobileManipulator = _native.MobileManipulator
Feedback = _native.Feedback
pick_and_place = _native.pick_and_place
capstone = _native.capstone
drive = _native.drive
fkin_body = _native.fkin_body
fkin_space = _native.fkin_space
jacobian_body = _native.jacobian_body
jacobian_space = _native.jacobian_space

__all__ = [
    "Base",
    "MobileManipulator",
    "Feedback",
    "pick_and_place",
    "capstone",
    "drive",
    "fkin_body",
    "fkin_space",
    "jacobian_body",
    "jacobian_space",
]
