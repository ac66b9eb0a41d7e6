//! Locking joints: a reduced model in which some 1-dof joints are welded at given values, their
//! bodies merged into the nearest moving ancestor (or dropped when welded to the world, where they
//! take no part in the dynamics), like Pinocchio's `buildReducedModel`.
//!
//! The Panda's two prismatic finger joints, for example: `lock_joints(&panda,
//! &[("panda_finger_joint1", 0.0), ("panda_finger_joint2", 0.0)])` leaves the 7-joint arm whose
//! last body carries the hand and both fingers. The reduced model's `M`, `c` and `g` are the full
//! model's rows and columns of the free joints with the locked joints at their values and at
//! rest.

use super::ExplicitError;
use crate::mass::SpatialInertia;
use crate::multibody::{JointId, Model, ModelBuilder};
use crate::spatial::Transform;

/// `model` with the joints named in `locked` welded at the given values (see the module
/// documentation). Joints keep their order, names, limits and armature.
///
/// # Errors
/// An unknown joint name, a locked joint with more than one coordinate, a non-finite value.
///
/// ```
/// use rigid::explicit::lock_joints;
/// use rigid::multibody::{crba, double_pendulum, Data};
/// let single = lock_joints(&double_pendulum(), &[("joint2".into(), 0.0)])?;
/// assert_eq!(single.nv(), 1);
/// // the locked rod hangs below the first: M = 1/3 + (1/12 + 1.5²), both rods about the pivot
/// let m = crba(&single, &mut Data::new(&single), &[0.4]).unwrap()[(0, 0)];
/// assert!((m - 8.0 / 3.0).abs() < 1e-12);
/// # Ok::<(), rigid::explicit::ExplicitError>(())
/// ```
pub fn lock_joints(model: &Model, locked: &[(String, f64)]) -> Result<Model, ExplicitError> {
    let n = model.njoints();
    let mut value = vec![None; n];
    for (name, v) in locked {
        let id = model
            .joint_id(name)
            .ok_or_else(|| ExplicitError::UnknownJoint { name: name.clone() })?;
        let j = model.joint(id);
        if j.nq != 1 || !v.is_finite() {
            return Err(ExplicitError::BadLock {
                joint: name.clone(),
            });
        }
        value[id.0] = Some(*v);
    }
    // host[j]: the kept joint (new index) whose body carries j's body, or None for the world,
    // and the pose of j's moved frame in the host's frame
    let mut host: Vec<(Option<usize>, Transform)> = Vec::with_capacity(n);
    let mut new_index = vec![None; n];
    let mut kept: Vec<(usize, Option<usize>, Transform, SpatialInertia)> = Vec::new();
    for (j, joint) in model.joints().iter().enumerate() {
        let (parent_host, to_parent) = match joint.parent {
            Some(p) => match new_index[p.0] {
                Some(k) => (Some(k), Transform::identity()),
                None => host[p.0],
            },
            None => (None, Transform::identity()),
        };
        let placement = to_parent * joint.placement;
        let body = *model.inertia(JointId(j));
        match value[j] {
            Some(v) => {
                let pose = placement * joint.kind.transform(&[v]);
                if let Some(h) = parent_host {
                    kept[h].3 += body.transformed(&pose);
                }
                host.push((parent_host, pose));
            }
            None => {
                new_index[j] = Some(kept.len());
                kept.push((j, parent_host, placement, body));
                host.push((Some(kept.len() - 1), Transform::identity()));
            }
        }
    }
    let err = |e| ExplicitError::Model(format!("{e}"));
    let mut b = ModelBuilder::new(model.name());
    b.set_gravity(model.gravity());
    for (j, parent, placement, inertia) in &kept {
        let joint = model.joint(JointId(*j));
        let id = b
            .add_joint(
                parent.map(JointId),
                &joint.name,
                joint.kind,
                *placement,
                *inertia,
            )
            .map_err(err)?;
        let (q, v) = (
            joint.idx_q..joint.idx_q + joint.nq,
            joint.idx_v..joint.idx_v + joint.nv,
        );
        b.set_limits(
            id,
            &model.lower_limits()[q.clone()],
            &model.upper_limits()[q],
            &model.velocity_limits()[v.clone()],
            &model.effort_limits()[v.clone()],
        )
        .map_err(err)?;
        b.set_armature(id, &model.armature()[v]).map_err(err)?;
    }
    b.build().map_err(err)
}
