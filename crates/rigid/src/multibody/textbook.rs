//! Model builders from textbook descriptions: Denavit-Hartenberg tables (standard and modified)
//! and Modern Robotics' `(M_i, G_i, S_i)` lists.

use super::{JointId, JointType, Model, ModelBuilder, ModelError};
use crate::mass::{RotationalInertia, SpatialInertia};
use crate::spatial::{so3, Transform, Twist, Vec3};

/// Which Denavit-Hartenberg convention a table uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DhConvention {
    /// Standard (distal) DH: `T_{i-1,i} = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`; frame {i} sits at the
    /// far end of link i (Spong; the Robotics Toolbox's `RevoluteDH`).
    Standard,
    /// Modified (proximal, Craig) DH: `T_{i-1,i} = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)`; link i's
    /// row holds `a_{i-1}, α_{i-1}` and frame {i} sits on joint i's axis (`RevoluteMDH`).
    Modified,
}

/// Whether a DH joint rotates (`θ` varies) or slides (`d` varies).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DhJoint {
    /// `θ = q + theta_offset`, `d` fixed.
    Revolute,
    /// `d = q + d` (the `d` field is the offset), `θ = theta_offset` fixed.
    Prismatic,
}

/// One row of a DH table with the link's mass properties.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DhLink {
    /// Link length `a` (m) (`a_{i-1}` for modified DH).
    pub a: f64,
    /// Link twist `α` (rad) (`α_{i-1}` for modified DH).
    pub alpha: f64,
    /// Link offset `d` (m); for a prismatic joint, the offset added to `q`.
    pub d: f64,
    /// Joint angle offset: `θ = q + theta_offset` (revolute) or the fixed `θ` (prismatic).
    pub theta_offset: f64,
    /// Revolute or prismatic.
    pub joint: DhJoint,
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the DH link frame {i} (m).
    pub com: Vec3,
    /// Rotational inertia about the CoM, in the axes of frame {i} (kg·m²).
    pub inertia: RotationalInertia,
}

fn rz(t: f64) -> Transform {
    Transform::from_rotation(so3::exp(&(Vec3::z() * t)))
}
fn rx(t: f64) -> Transform {
    Transform::from_rotation(so3::exp(&(Vec3::x() * t)))
}
fn tz(d: f64) -> Transform {
    Transform::from_translation(Vec3::new(0.0, 0.0, d))
}
fn tx(a: f64) -> Transform {
    Transform::from_translation(Vec3::new(a, 0.0, 0.0))
}

/// A serial chain from a DH table; joints are named `joint1..jointN`, and a frame `link{i}` is
/// kept for each DH frame {i} (the last one is the flange).
///
/// Joint frames (the model's placements) follow `docs/conventions.md`:
/// - standard: joint i's frame is frame {i-1} rotated by `Rz(q_i + offset)` (revolute) or moved
///   by `Rz(θ_i) Tz(d_i + q_i)` (prismatic); link i's frame is then
///   `{i} = J_i Tz(d_i) Tx(a_i) Rx(α_i)` (revolute) or `J_i Tx(a_i) Rx(α_i)` (prismatic);
/// - modified: joint i's frame is frame {i} itself,
///   `{i} = {i-1} Rx(α_{i-1}) Tx(a_{i-1}) Tz(d_i) Rz(θ_i)` (the variable factor last).
///
/// Frame {0} is the world.
///
/// # Errors
/// Non-finite parameters or non-physical inertias (naming the joint).
///
/// ```
/// use rigid::mass::RotationalInertia;
/// use rigid::multibody::{from_dh, DhConvention, DhJoint, DhLink};
/// use rigid::spatial::Vec3;
/// // a planar 2R arm: a = 1 m each, point masses of 1 kg at the link tips (CoM at the frame origin)
/// let link = DhLink { a: 1.0, alpha: 0.0, d: 0.0, theta_offset: 0.0, joint: DhJoint::Revolute,
///                     mass: 1.0, com: Vec3::zeros(), inertia: RotationalInertia::zero() };
/// let model = from_dh("2r", DhConvention::Standard, &[link, link], Vec3::new(0.0, -9.81, 0.0))?;
/// assert_eq!(model.nv(), 2);
/// # Ok::<(), rigid::multibody::ModelError>(())
/// ```
pub fn from_dh(
    name: &str,
    convention: DhConvention,
    links: &[DhLink],
    gravity: Vec3,
) -> Result<Model, ModelError> {
    let mut b = ModelBuilder::new(name);
    b.set_gravity(gravity);
    let mut parent: Option<JointId> = None;
    // pose of the previous joint frame's successor frame {i-1} in the previous joint frame
    let mut to_prev_link = Transform::identity();
    for (i, l) in links.iter().enumerate() {
        let finite = [l.a, l.alpha, l.d, l.theta_offset]
            .iter()
            .all(|x| x.is_finite());
        if !finite {
            return Err(ModelError::BadPlacement {
                name: format!("joint{}", i + 1),
            });
        }
        let (placement, axis_joint, link_in_joint) = match (convention, l.joint) {
            (DhConvention::Standard, DhJoint::Revolute) => (
                to_prev_link * rz(l.theta_offset),
                JointType::Revolute { axis: Vec3::z() },
                tz(l.d) * tx(l.a) * rx(l.alpha),
            ),
            (DhConvention::Standard, DhJoint::Prismatic) => (
                to_prev_link * rz(l.theta_offset) * tz(l.d),
                JointType::Prismatic { axis: Vec3::z() },
                tx(l.a) * rx(l.alpha),
            ),
            (DhConvention::Modified, DhJoint::Revolute) => (
                to_prev_link * rx(l.alpha) * tx(l.a) * tz(l.d) * rz(l.theta_offset),
                JointType::Revolute { axis: Vec3::z() },
                Transform::identity(),
            ),
            (DhConvention::Modified, DhJoint::Prismatic) => (
                to_prev_link * rx(l.alpha) * tx(l.a) * rz(l.theta_offset) * tz(l.d),
                JointType::Prismatic { axis: Vec3::z() },
                Transform::identity(),
            ),
        };
        let inertia =
            SpatialInertia::from_com(l.mass, l.com, l.inertia).transformed(&link_in_joint);
        let id = b.add_joint(
            parent,
            &format!("joint{}", i + 1),
            axis_joint,
            placement,
            inertia,
        )?;
        b.add_frame(Some(id), &format!("link{}", i + 1), link_in_joint)?;
        parent = Some(id);
        to_prev_link = link_in_joint;
    }
    b.build()
}

/// A serial chain from Modern Robotics' lists (Lynch & Park §8.3.2, Alg. of §8.3.2 / code
/// `InverseDynamics`): `m_list[i] = M_{i-1,i}` the home pose of link frame {i} in {i-1}
/// (`m_list` may hold one more entry, `M_{n,n+1}`, the end-effector frame, kept as frame `ee`),
/// `g_list[i] = G_i` the spatial inertia of link i in {i}, `s_list[i] = S_i` the screw axis of
/// joint i in the space frame at home. A revolute screw (|ω| = 1, pitch `ωᵀv = 0`) gives a
/// revolute joint whose frame has {i}'s orientation and its origin at the foot of the
/// perpendicular from {i}'s origin to the axis; a prismatic screw (ω = 0, |v| = 1) a prismatic
/// joint at {i}'s origin. Link frames are kept as frames `link1..linkN`.
///
/// # Errors
/// Mismatched list lengths, helical or non-unit screws (naming the joint index), non-physical
/// inertias.
pub fn from_modern_robotics(
    name: &str,
    m_list: &[Transform],
    g_list: &[SpatialInertia],
    s_list: &[Twist],
    gravity: Vec3,
) -> Result<Model, ModelError> {
    let n = s_list.len();
    if g_list.len() != n || (m_list.len() != n && m_list.len() != n + 1) {
        return Err(ModelError::Unsupported {
            index: 0,
            reason: "list lengths differ (need n screws, n inertias, n or n+1 home poses)",
        });
    }
    let mut b = ModelBuilder::new(name);
    b.set_gravity(gravity);
    let mut m_0i = Transform::identity(); // home pose of {i} in the space frame
    let mut parent: Option<JointId> = None;
    let mut prev_joint_in_link = Transform::identity(); // T_{ {i-1}, J_{i-1} }
    for i in 0..n {
        m_0i = m_0i * m_list[i];
        let A = m_0i.inv_act_twist(&s_list[i]); // screw in {i}
        let wn = A.w.norm();
        let (joint, r) = if wn > 1e-9 {
            if (wn - 1.0).abs() > 1e-6 || A.w.dot(&A.v).abs() > 1e-6 {
                return Err(ModelError::Unsupported {
                    index: i,
                    reason: "revolute screw axis must have |ω| = 1 and zero pitch",
                });
            }
            (JointType::Revolute { axis: A.w }, A.w.cross(&A.v))
        } else {
            if (A.v.norm() - 1.0).abs() > 1e-6 {
                return Err(ModelError::Unsupported {
                    index: i,
                    reason: "prismatic screw axis must have |v| = 1",
                });
            }
            (JointType::Prismatic { axis: A.v }, Vec3::zeros())
        };
        let joint_in_link = Transform::from_translation(r); // T_{ {i}, J_i }
        let placement = prev_joint_in_link.inverse() * m_list[i] * joint_in_link;
        let inertia = g_list[i].transformed(&joint_in_link.inverse());
        let id = b.add_joint(
            parent,
            &format!("joint{}", i + 1),
            joint,
            placement,
            inertia,
        )?;
        b.add_frame(Some(id), &format!("link{}", i + 1), joint_in_link.inverse())?;
        parent = Some(id);
        prev_joint_in_link = joint_in_link;
    }
    if m_list.len() == n + 1 {
        let ee = prev_joint_in_link.inverse() * m_list[n];
        match parent {
            Some(_) => b.add_frame(parent, "ee", ee)?,
            None => b.add_frame(None, "ee", m_list[n])?,
        };
    }
    b.build()
}
