//! The compiled plan of a [`Model`](super::Model): everything the fast algorithms precompute from
//! the model's joints and inertias, built by one function ([`Plan::new`]) and rebuilt by every
//! method that changes what it derives from, so that it is never stale. Nothing outside this file
//! writes it; the reference algorithms ([`reference`](super::reference)) do not read it.
//!
//! | cache | what it saves |
//! | --- | --- |
//! | `dof_S`, `dof_joint`, `dof_axis` | the motion-subspace columns of constant-`S` joints, and when a column is `±e_c` (then `I S` is a column of `I` and `Sᵀ F` one component of `F`) |
//! | `placement` ([`PlacementKind`]) | `R_λ R_T` as a column pick (signed permutation) or two columns turned (a turn about a coordinate axis) instead of a 3x3 product |
//! | `turn` | a revolute joint about a coordinate axis with an unrotated `X_T`: `liMi`'s rotation turns two components (the batch kernels' `Turn`) |
//! | `placement_translation` | `R_λ t` as a scaled column when `t` lies on a coordinate axis |
//! | `subtree_end_v` | where each joint's subtree's dofs end (`idx_v..subtree_end_v[i]`), read by every backward pass over a subtree's columns |
//! | `chain_angles` | the angles whose sines and cosines CRBA's first pass computes ahead of the chain, several at a time |
//! | `principal` | each body's inertia in its [`PrincipalForm`], cheaper to rotate |
//!
//! A rotation within 4 ulps of a signed permutation or of a turn about a coordinate axis is
//! treated as exactly that (URDF writes `rpy="0 1.570796325 0"` for a quarter turn): the results
//! differ from the general product by round-off only, and the test
//! `crba_shortcuts_equal_rnea_columns` checks every shortcut against RNEA.

use super::joint::Shape;
use super::model::Joint;
use crate::mass::{PrincipalForm, SpatialInertia};
use crate::spatial::{Mat3, ModelVec3, Transform, Twist, Vec3};

/// What `X_T`'s rotation is, for composing `R_λ R_T` cheaply.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum PlacementKind {
    /// Exactly the identity (a URDF origin without `rpy`).
    Identity,
    /// A signed permutation: column `c` of `R_T` is `s e_k` for `(k, s)` in slot `c`.
    SignedPermutation([(usize, f64); 3]),
    /// A turn by `θ` about the coordinate axis `axis`, with `(sin θ, cos θ)`.
    AxisTurn {
        /// `e_k`.
        axis: Vec3,
        /// `sin θ`.
        s: f64,
        /// `cos θ`.
        c: f64,
    },
    /// Any other rotation.
    General,
}

/// The speed caches of a model (see the [module](self) documentation).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Plan {
    /// Motion-subspace column per degree of freedom, in the child frame, for the joints whose
    /// `S` is constant; for the others `S` at the neutral configuration (the algorithms compute
    /// theirs at `q`).
    pub(crate) dof_S: Vec<Twist>,
    /// The joint of each degree of freedom.
    pub(crate) dof_joint: Vec<usize>,
    /// `Some((c, s))` when `S_k = s e_c` is constant (a coordinate axis, angular first,
    /// `s = ±1`).
    pub(crate) dof_axis: Vec<Option<(usize, f64)>>,
    /// `(joint, index in q)` of every quaternion.
    pub(crate) quaternions: Vec<(usize, usize)>,
    /// The joints whose motion subspace depends on `q` (then `c_J ≠ 0`).
    pub(crate) variable_subspace: Vec<usize>,
    /// Per joint: whether its motion subspace depends on `q`.
    pub(crate) varies: Vec<bool>,
    /// Per joint: the kind of `X_T`'s rotation.
    pub(crate) placement: Vec<PlacementKind>,
    /// Per joint: `Some((k, s))` when it is revolute about `s e_k` (`s = ±1`) and `X_T`'s
    /// rotation is [`PlacementKind::Identity`]: then `liMi = (Rot_k(s q), t)`.
    pub(crate) turn: Vec<Option<(usize, f64)>>,
    /// Per joint: `X_T`'s translation, kept as `s e_k` when it lies on a coordinate axis.
    pub(crate) placement_translation: Vec<ModelVec3>,
    /// Per joint: the end of its subtree's dofs, `idx_v + nv` of the subtree's last joint (the
    /// subtree's dofs are `idx_v..subtree_end_v`, joints being depth-first).
    pub(crate) subtree_end_v: Vec<usize>,
    /// The `q` indices of the joints for which [`Plan::reads_chain_angle`] holds.
    pub(crate) chain_angles: Vec<usize>,
    /// Per body: its inertia's principal form, `None` when it has none.
    pub(crate) principal: Vec<Option<PrincipalForm>>,
    /// A digest of the joints (each one's parent and type, axes included), which a
    /// [`Data`](super::Data) keeps to refuse a model of its shape with other joints: it holds
    /// their constant motion subspaces and the derivatives' tree from when it was made.
    pub(crate) joints_key: u64,
}

impl Plan {
    /// The plan of a model with these joints (depth-first) and body inertias.
    pub(crate) fn new(joints: &[Joint], inertias: &[SpatialInertia]) -> Self {
        let mut plan = Self {
            joints_key: {
                use std::hash::{Hash, Hasher};
                let mut h = std::collections::hash_map::DefaultHasher::new();
                for j in joints {
                    format!("{:?} {:?}", j.parent, j.kind).hash(&mut h);
                }
                h.finish()
            },
            dof_S: Vec::new(),
            dof_joint: Vec::new(),
            dof_axis: Vec::new(),
            quaternions: Vec::new(),
            variable_subspace: Vec::new(),
            varies: joints.iter().map(|j| !j.kind.constant_subspace()).collect(),
            placement: joints
                .iter()
                .map(|j| placement_kind(&j.placement))
                .collect(),
            turn: Vec::new(),
            placement_translation: joints
                .iter()
                .map(|j| ModelVec3::new(&j.placement.translation))
                .collect(),
            subtree_end_v: joints
                .iter()
                .map(|j| {
                    let last = &joints[j.subtree_end - 1];
                    last.idx_v + last.nv
                })
                .collect(),
            chain_angles: Vec::new(),
            principal: inertias.iter().map(PrincipalForm::new).collect(),
        };
        let mut S = [Twist::zero(); 6];
        for (i, j) in joints.iter().enumerate() {
            let mut neutral = [0.0; 7];
            j.kind.neutral(&mut neutral);
            j.kind.subspace(&neutral[..j.nq], &mut S[..j.nv]);
            let constant = j.kind.constant_subspace();
            for Sk in &S[..j.nv] {
                plan.dof_S.push(*Sk);
                plan.dof_axis.push(unit_axis(Sk).filter(|_| constant));
                plan.dof_joint.push(i);
            }
            let revolute = matches!(j.kind.shape(), Shape::Revolute(_));
            let unrotated = plan.placement[i] == PlacementKind::Identity;
            // a revolute joint's one column is (axis, 0): an axis `s e_k` is `dof_axis`'s (k, s)
            plan.turn
                .push(plan.dof_axis[j.idx_v].filter(|_| revolute && unrotated));
            if !constant {
                plan.variable_subspace.push(i);
            }
            if let Some(o) = j.kind.quaternion_offset() {
                plan.quaternions.push((i, j.idx_q + o));
            }
            if plan.reads_chain_angle(joints, i) {
                plan.chain_angles.push(j.idx_q);
            }
        }
        plan
    }

    /// Whether the first pass of CRBA, `M⁻¹` and the RNEA derivatives (`root_frame_bodies`)
    /// turns joint `i` by a sine and cosine computed ahead of the chain: a revolute joint that is
    /// a root's child, or deeper with an `X_T` whose rotation is not [`PlacementKind::General`].
    /// The one definition behind `chain_angles` and the pass's match arms.
    pub(crate) fn reads_chain_angle(&self, joints: &[Joint], i: usize) -> bool {
        let j = &joints[i];
        matches!(j.kind.shape(), Shape::Revolute(_))
            && j.parent.is_some_and(|p| {
                joints[p.0].parent.is_none() || self.placement[i] != PlacementKind::General
            })
    }
}

/// `Some((c, s))` when the twist is `s e_c` with `s = ±1`.
fn unit_axis(S: &Twist) -> Option<(usize, f64)> {
    let x = S.to_vector();
    let mut nonzero = (0..6).filter(|&c| x[c] != 0.0);
    match (nonzero.next(), nonzero.next()) {
        (Some(c), None) if x[c].abs() == 1.0 => Some((c, x[c])),
        _ => None,
    }
}

/// The kind of `X_T`'s rotation (4 ulps of tolerance on the zeros and ones).
fn placement_kind(t: &Transform) -> PlacementKind {
    let r = &t.rotation;
    if *r == Mat3::identity() {
        return PlacementKind::Identity;
    }
    if let Some(p) = signed_permutation(r) {
        return PlacementKind::SignedPermutation(p);
    }
    match coordinate_turn(r) {
        Some((axis, s, c)) => PlacementKind::AxisTurn { axis, s, c },
        None => PlacementKind::General,
    }
}

/// `Some` when `r` is a signed permutation up to 4 ulps: column `c` is `s e_k` for `(k, s)` in
/// slot `c`.
fn signed_permutation(r: &Mat3) -> Option<[(usize, f64); 3]> {
    const TOL: f64 = 4.0 * f64::EPSILON;
    let mut out = [(0, 0.0); 3];
    let mut used = [false; 3];
    for (c, slot) in out.iter_mut().enumerate() {
        let col = r.column(c);
        let k = col.iamax();
        let ones = (col[k].abs() - 1.0).abs() <= TOL;
        let zeros = (0..3).all(|t| t == k || col[t].abs() <= TOL);
        if !ones || !zeros || used[k] {
            return None;
        }
        used[k] = true;
        *slot = (k, col[k].signum());
    }
    Some(out)
}

/// `Some((e_k, sin θ, cos θ))` when `r` turns by `θ` about the coordinate axis `e_k` (up to
/// 4 ulps).
fn coordinate_turn(r: &Mat3) -> Option<(Vec3, f64, f64)> {
    const TOL: f64 = 4.0 * f64::EPSILON;
    // the axis: r_kk = 1 and the rest of row and column k zero (every k tried: a tiny turn
    // about a later axis also has r_kk = 1 on an earlier k)
    let k = (0..3).find(|&k| {
        (r[(k, k)] - 1.0).abs() <= TOL
            && (0..3).all(|t| t == k || (r[(k, t)].abs() <= TOL && r[(t, k)].abs() <= TOL))
    })?;
    // about e_k, the plane (j, l) in cyclic order turns: r_jj = r_ll = c, r_lj = -r_jl = s
    let (j, l) = ((k + 1) % 3, (k + 2) % 3);
    let (s, c) = (r[(l, j)], r[(j, j)]);
    if (r[(l, l)] - c).abs() > TOL || (r[(j, l)] + s).abs() > TOL {
        return None;
    }
    Some((Vec3::ith(k, 1.0), s, c))
}
