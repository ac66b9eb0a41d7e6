"""Type stubs of rigid.mobile (docs/mobile.md): wheeled mobile robots, Modern Robotics ch. 13."""

from os import PathLike
from typing import Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Array = npt.ArrayLike
_Gain = Union[float, npt.ArrayLike]

class Base:
    """A wheeled base; chassis configurations q = (phi, x, y), planar twists (omega_z, v_x, v_y)."""

    @staticmethod
    def mecanum(r: float, l: float, w: float) -> Base:
        """Four mecanum wheels at (±l, ±w): front-left, front-right, rear-right, rear-left (eq. 13.10)."""
    @staticmethod
    def omni3(r: float, d: float) -> Base:
        """Three omniwheels at distance d, 120° apart (eq. 13.9)."""
    @staticmethod
    def diff_drive(r: float, track: float) -> Base:
        """A differential drive: left and right wheels `track` apart."""
    @staticmethod
    def car(r: float, track: float, wheelbase: float) -> Base:
        """A car: the rear axle drives, the front axle `wheelbase` ahead steers."""
    @property
    def name(self) -> str: ...
    @property
    def kind(self) -> str:
        """`omnidirectional` or `nonholonomic`."""
    @property
    def n_wheels(self) -> int: ...
    def H(self, phi: float = 0.0) -> np.ndarray:
        """H(phi), m x 3: wheel speeds u = H(phi) q_dot (eq. 13.5)."""
    @property
    def F(self) -> np.ndarray:
        """F = H(0)^+, 3 x m: the planar body twist from wheel speeds."""
    @property
    def F6(self) -> np.ndarray:
        """[0; 0; F; 0], 6 x m."""
    def body_twist(self, u: _Array) -> np.ndarray: ...
    def odometry(self, q: _Array, dtheta: _Array) -> np.ndarray:
        """The chassis configuration after the wheels turned by dtheta (§13.4)."""
    def constraint(self, q: _Array) -> Optional[np.ndarray]:
        """A(q) of A(q) q_dot = 0 (nonholonomic bases), else None."""
    def steering(self, twist: _Array) -> Optional[float]:
        """A car's steering angle atan(l omega / v), else None."""

class MobileManipulator:
    """An arm (Blist: 6 x n, columns; home M_0e) on a base at T_b0, the chassis `height` up."""

    def __init__(
        self, base: Base, T_b0: _Array, M_0e: _Array, Blist: _Array, height: float = 0.0
    ) -> None: ...
    @staticmethod
    def youbot() -> MobileManipulator:
        """The KUKA youBot of the capstone."""
    @property
    def base(self) -> Base: ...
    @property
    def n_arm(self) -> int: ...
    @property
    def n_wheels(self) -> int: ...
    def chassis_pose(self, q: _Array) -> np.ndarray: ...
    def forward(self, q: _Array, theta: _Array) -> np.ndarray:
        """X = T_sb(q) T_b0 M_0e exp([B_1] theta_1) ... (4 x 4)."""
    def jacobian(self, theta: _Array) -> np.ndarray:
        """J_e = [J_base, J_arm], 6 x (m + n), wheels first."""
    def next_state(
        self,
        chassis_q: _Array,
        arm: _Array,
        wheels: _Array,
        speeds: _Array,
        dt: float,
        max_speed: float = ...,
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """One Euler step (NextState): the new (chassis, arm, wheels)."""
    def feedback(
        self,
        X: _Array,
        Xd: _Array,
        Xd_next: _Array,
        Kp: _Gain,
        Ki: _Gain,
        dt: float,
        theta: _Array,
        limits: Optional[Sequence[Tuple[float, float]]] = None,
        tolerance: float = 1e-4,
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(V, speeds, X_err) of one feedback step from a zero integral (eq. 13.37)."""

class Feedback:
    """Feedforward plus PI on the end-effector pose, keeping its integral."""

    def __init__(
        self,
        Kp: _Gain,
        Ki: _Gain,
        limits: Optional[Sequence[Tuple[float, float]]] = None,
        tolerance: float = 1e-4,
    ) -> None: ...
    def command(
        self,
        robot: MobileManipulator,
        X: _Array,
        Xd: _Array,
        Xd_next: _Array,
        dt: float,
        theta: _Array,
    ) -> Tuple[np.ndarray, np.ndarray, np.ndarray]: ...
    @property
    def integral(self) -> np.ndarray: ...
    def reset(self) -> None: ...

def pick_and_place(
    start: _Array,
    cube_initial: Optional[_Array] = None,
    cube_final: Optional[_Array] = None,
    grasp: Optional[_Array] = None,
    standoff: Optional[_Array] = None,
    dt: float = 0.01,
) -> np.ndarray:
    """The capstone's reference, N x 13 (r11..r33, px, py, pz, gripper)."""

def capstone(
    Kp: Optional[_Gain] = None,
    Ki: Optional[_Gain] = None,
    chassis: Optional[_Array] = None,
    arm: Optional[_Array] = None,
    cube_initial: Optional[_Array] = None,
    cube_final: Optional[_Array] = None,
    limits: Optional[Sequence[Tuple[float, float]]] = None,
    dt: float = 0.01,
    max_speed: float = 15.0,
) -> dict:
    """A whole capstone run: states (N x 13), errors (N-1 x 6), reference (N x 13), dt."""

def drive(
    path: Union[str, PathLike],
    wheels: Sequence[str],
    speeds: Sequence[float],
    time: float = 3.0,
    dt: float = 1e-3,
    gain: float = 20.0,
    friction: float = 1.0,
    wheel_friction: Optional[float] = None,
    hold: bool = False,
) -> dict:
    """A robot file on the ground, its wheels under velocity control: t, x, y, yaw, v, omega,
    wheel_speeds, q."""

def fkin_body(M: _Array, Blist: _Array, theta: _Array) -> np.ndarray: ...
def fkin_space(M: _Array, Slist: _Array, theta: _Array) -> np.ndarray: ...
def jacobian_body(Blist: _Array, theta: _Array) -> np.ndarray: ...
def jacobian_space(Slist: _Array, theta: _Array) -> np.ndarray: ...
