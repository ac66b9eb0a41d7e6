//! Built-in models: `pendulum`, `double_pendulum`, `puma560`.

use super::{from_dh, DhConvention, DhJoint, DhLink, JointType, Model, ModelBuilder};
use crate::mass::{RotationalInertia, SpatialInertia};
use crate::spatial::{Transform, Vec3};
use std::f64::consts::FRAC_PI_2;

/// The names accepted by [`builtin`].
#[must_use]
pub fn builtin_names() -> &'static [&'static str] {
    &["pendulum", "double_pendulum", "puma560", "puma560_armature"]
}

/// A built-in model by name (see [`builtin_names`]): `pendulum`, `double_pendulum`, `puma560`
/// (rigid links) and `puma560_armature` (with rotor inertia `Jm G²`).
#[must_use]
pub fn builtin(name: &str) -> Option<Model> {
    match name {
        "pendulum" => Some(pendulum()),
        "double_pendulum" => Some(double_pendulum()),
        "puma560" => Some(puma560(Puma560Options::default())),
        "puma560_armature" => Some(puma560(Puma560Options { armature: true })),
        _ => None,
    }
}

/// A uniform thin rod of mass `m` and length `l` hanging along `-z` from its joint frame's origin:
/// CoM `(0, 0, -l/2)`, `I_com = diag(m l²/12, m l²/12, 0)`.
fn rod(m: f64, l: f64) -> SpatialInertia {
    let i = m * l * l / 12.0;
    SpatialInertia::from_com(
        m,
        Vec3::new(0.0, 0.0, -l / 2.0),
        RotationalInertia::diagonal(i, i, 0.0),
    )
}

/// A simple pendulum: one revolute joint `joint1` about the world `y` axis at the origin, and a
/// uniform thin rod of mass 1 kg and length 1 m hanging along `-z` at `q = 0`
/// (CoM 0.5 m below the pivot, `I_pivot = m l²/3 = 1/3 kg·m²`). With gravity `-9.81 ẑ`:
/// `M = 1/3`, `g(q) = m g (l/2) sin q = 4.905 sin q`.
#[must_use]
pub fn pendulum() -> Model {
    let mut b = ModelBuilder::new("pendulum");
    b.add_joint(
        None,
        "joint1",
        JointType::Revolute { axis: Vec3::y() },
        Transform::identity(),
        rod(1.0, 1.0),
    )
    .expect("valid built-in");
    b.build().expect("valid built-in")
}

/// A double pendulum in the x-z plane: two revolute joints about `y`, `joint1` at the world
/// origin and `joint2` at the tip of link 1 (`(0, 0, -1)` m in joint 1's frame); each link is a
/// uniform thin rod of mass 1 kg and length 1 m hanging along `-z` at `q = 0`.
#[must_use]
pub fn double_pendulum() -> Model {
    let mut b = ModelBuilder::new("double_pendulum");
    let y = JointType::Revolute { axis: Vec3::y() };
    let j1 = b
        .add_joint(None, "joint1", y, Transform::identity(), rod(1.0, 1.0))
        .expect("valid built-in");
    b.add_joint(
        Some(j1),
        "joint2",
        y,
        Transform::from_translation(Vec3::new(0.0, 0.0, -1.0)),
        rod(1.0, 1.0),
    )
    .expect("valid built-in");
    b.build().expect("valid built-in")
}

/// Options of [`puma560`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Puma560Options {
    /// Add the reflected rotor inertia `Jm G²` of each joint as armature (diagonal of `M`, ABA's
    /// `D`). Off by default (rigid links only).
    pub armature: bool,
}

/// Rotor inertia `Jm` (kg·m²) and gear ratio `G` per joint, from the Robotics Toolbox.
pub(crate) const PUMA560_JM: [f64; 6] = [200e-6, 200e-6, 200e-6, 33e-6, 33e-6, 33e-6];
/// Gear ratios `G` (signed, as in the toolbox).
pub(crate) const PUMA560_G: [f64; 6] = [-62.6111, 107.815, -53.7063, 76.0364, 71.923, 76.686];

/// The Unimation PUMA 560 in standard DH, as `roboticstoolbox-python` 1.5.0
/// `models.DH.Puma560` defines it (read from its source `roboticstoolbox/models/DH/Puma560.py`).
/// Gravity `[0, 0, -9.81]`. Joint angles are the toolbox's (the 1986 paper's `θ2 = q2 + π`,
/// `θ3 = q3 + π`).
///
/// | i | d (m) | a (m) | α | m (kg) | r = CoM in {i} (m) | I at CoM (Ixx, Iyy, Izz) kg·m² | Jm (kg·m²) | G |
/// | --- | --- | --- | --- | --- | --- | --- | --- | --- |
/// | 1 | 26.45 in = 0.67183 | 0 | π/2 | 0 | (0, 0, 0) | (0, 0.35, 0) | 200e-6 | -62.6111 |
/// | 2 | 0 | 0.4318 | 0 | 17.4 | (-0.3638, 0.006, 0.2275) | (0.13, 0.524, 0.539) | 200e-6 | 107.815 |
/// | 3 | 0.15005 | 0.0203 | -π/2 | 4.8 | (-0.0203, -0.0141, 0.070) | (0.066, 0.086, 0.0125) | 200e-6 | -53.7063 |
/// | 4 | 0.4318 | 0 | π/2 | 0.82 | (0, 0.019, 0) | (1.8e-3, 1.3e-3, 1.8e-3) | 33e-6 | 76.0364 |
/// | 5 | 0 | 0 | -π/2 | 0.34 | (0, 0, 0) | (0.3e-3, 0.4e-3, 0.3e-3) | 33e-6 | 71.923 |
/// | 6 | 0 | 0 | 0 | 0.09 | (0, 0, 0.032) | (0.15e-3, 0.15e-3, 0.04e-3) | 33e-6 | 76.686 |
///
/// Sources, as the toolbox states them: kinematic and dynamic parameters from Corke &
/// Armstrong-Hélouvry, "A search for consensus among model parameters reported for the PUMA 560
/// robot", ICRA 1994 (which draws on Armstrong, Khatib & Burdick 1986), the base height
/// 26.45 in (pedestal, mounting surface to shoulder axis) from the toolbox; `m1 = 0` because
/// Armstrong found no value for it (its 0.35 kg·m² about the joint axis is kept); products of
/// inertia are zero. Friction (`B`, `Tc`) is not modelled. Link 1 has zero mass and a non-zero
/// inertia, which the builder accepts (a massless body is not validated).
///
/// Joint limits (`qlim`, degrees): ±160, [-45, 225], [-225, 45], [-110, 170], ±100, ±266
/// (the toolbox cites Wang & Chen, IEEE T-RA 7(4) 1991).
///
/// `armature: true` adds `Jm G²` = (0.7840, 2.3248, 0.5769, 0.1908, 0.1707, 0.1941) kg·m² to the
/// diagonal of `M` (the toolbox's `inertia` includes it).
#[must_use]
pub fn puma560(options: Puma560Options) -> Model {
    let inch = 0.0254;
    let row = |d: f64, a: f64, alpha: f64, m: f64, r: [f64; 3], i: [f64; 3]| DhLink {
        a,
        alpha,
        d,
        theta_offset: 0.0,
        joint: DhJoint::Revolute,
        mass: m,
        com: Vec3::from(r),
        inertia: RotationalInertia::diagonal(i[0], i[1], i[2]),
    };
    let links = [
        row(
            26.45 * inch,
            0.0,
            FRAC_PI_2,
            0.0,
            [0.0, 0.0, 0.0],
            [0.0, 0.35, 0.0],
        ),
        row(
            0.0,
            0.4318,
            0.0,
            17.4,
            [-0.3638, 0.006, 0.2275],
            [0.13, 0.524, 0.539],
        ),
        row(
            0.15005,
            0.0203,
            -FRAC_PI_2,
            4.8,
            [-0.0203, -0.0141, 0.070],
            [0.066, 0.086, 0.0125],
        ),
        row(
            0.4318,
            0.0,
            FRAC_PI_2,
            0.82,
            [0.0, 0.019, 0.0],
            [1.8e-3, 1.3e-3, 1.8e-3],
        ),
        row(
            0.0,
            0.0,
            -FRAC_PI_2,
            0.34,
            [0.0, 0.0, 0.0],
            [0.3e-3, 0.4e-3, 0.3e-3],
        ),
        row(
            0.0,
            0.0,
            0.0,
            0.09,
            [0.0, 0.0, 0.032],
            [0.15e-3, 0.15e-3, 0.04e-3],
        ),
    ];
    let name = if options.armature {
        "puma560_armature"
    } else {
        "puma560"
    };
    let mut model = from_dh(
        name,
        DhConvention::Standard,
        &links,
        Vec3::new(0.0, 0.0, -9.81),
    )
    .expect("valid built-in");
    // joint limits of the toolbox (`qlim`, from Wang & Chen 1991), in degrees
    let qlim = [
        (-160.0, 160.0),
        (-45.0, 225.0),
        (-225.0, 45.0),
        (-110.0, 170.0),
        (-100.0, 100.0),
        (-266.0, 266.0),
    ];
    for (k, (lo, hi)) in qlim.iter().enumerate() {
        model.lower[k] = f64::to_radians(*lo);
        model.upper[k] = f64::to_radians(*hi);
    }
    if options.armature {
        let arm: Vec<f64> = (0..6)
            .map(|i| PUMA560_JM[i] * PUMA560_G[i] * PUMA560_G[i])
            .collect();
        model.set_armature(&arm).expect("valid built-in");
    }
    model
}
