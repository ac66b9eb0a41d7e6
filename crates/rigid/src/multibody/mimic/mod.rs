//! Mimic joints as couplings: a joint driven by another, `q_m = multiplier · q_s + offset`, with
//! no coordinate of its own (URDF `<mimic>`; Pinocchio's `buildModelFromUrdf(path, mimic=True)`).
//!
//! The coupled robot moves in the reduced coordinates `q` of its free joints (the full model's
//! with every mimic coordinate dropped, in the same order). Its full configuration and velocity
//! are `q_full = E(q)`, `q̇_full = G q̇`, where `G` (nv_full x nv) holds one entry per row: `1` in
//! a free dof's own column, the multiplier in its source's column for a mimic dof. The virtual
//! work `δqᵀ τ = δq_fullᵀ τ_full` then gives every algorithm from the full model's (Lagrange's
//! equations in the reduced coordinates; Featherstone 2008 §8.1, "constraints by projection"):
//!
//! | reduced | from the full model | verb |
//! | --- | --- | --- |
//! | `τ = Gᵀ ID(E(q), G q̇, G q̈)` | RNEA | [`MimicModel::rnea`] |
//! | `M = Gᵀ M_full G` | CRBA | [`MimicModel::crba`] |
//! | `c + g = Gᵀ (c + g)_full` | RNEA at `q̈ = 0` | [`MimicModel::nonlinear_effects`] |
//! | `q̈ = M⁻¹ (τ − c − g)` | dense Cholesky of the reduced `M` | [`MimicModel::aba`] |
//! | `∂τ/∂q = Gᵀ ∂τ_full/∂q_full G`, the same in `q̇` | RNEA derivatives (the coupling is linear in each 1-dof joint's coordinate) | [`MimicModel::rnea_derivatives`] |
//! | `∂q̈/∂(q, q̇) = −M⁻¹ ∂τ/∂(q, q̇)` at `q̈`, `∂q̈/∂τ = M⁻¹` | RNEA derivatives | [`MimicModel::aba_derivatives`] |
//! | `J = J_full G` | frame Jacobian | [`MimicModel::frame_jacobian`] |
//!
//! Pinocchio 4.1's `mimic=True` computes `rnea` and `crba` the same way; its ABA and derivatives
//! refuse a mimic joint, so the cross-check of `aba` is `M⁻¹ (τ − nle)` from Pinocchio's own
//! `M` and `nle`. A mimic of a mimic is composed into a mimic of the free joint at the chain's
//! end, so a source that comes later in the tree (TALOS, Romeo) is no special case. For the
//! simulator, [`MimicModel::constraints`] gives the same couplings as constraints of the full
//! model (the constraint force is the coupling's torque).
//!
//! ```
//! use rigid::multibody::{double_pendulum, JointId, Mimic, MimicData, MimicModel};
//! // the elbow turns twice as far as the shoulder: one degree of freedom
//! let mm = MimicModel::new(double_pendulum(), &[Mimic::new(JointId(1), JointId(0), 2.0, 0.0)])?;
//! assert_eq!((mm.nq(), mm.nv()), (1, 1));
//! let mut md = MimicData::new(&mm);
//! let tau = mm.rnea(&mut md, &[0.3], &[0.5], &[1.0])?.clone();
//! let ddq = mm.aba(&mut md, &[0.3], &[0.5], tau.as_slice())?;
//! assert!((ddq[0] - 1.0).abs() < 1e-12);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use super::constraints::{ConstraintKind, ConstraintModel};
use super::{check_data, JointId, Model, MultibodyError, Rng};
use crate::error::DimensionError;
use nalgebra::DMatrix;
use thiserror::Error;

mod data;
mod dynamics;

pub use data::MimicData;

/// One coupling: joint `joint` follows joint `source`, `q_joint = multiplier · q_source + offset`
/// (URDF `<mimic joint multiplier offset>`, MJCF `<equality joint polycoef="offset multiplier">`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mimic {
    /// The joint that follows (it has no coordinate of its own).
    pub joint: JointId,
    /// The joint it follows.
    pub source: JointId,
    /// `∂q_joint/∂q_source`.
    pub multiplier: f64,
    /// `q_joint` when `q_source = 0` (rad or m).
    pub offset: f64,
}

impl Mimic {
    /// `q_joint = multiplier · q_source + offset`.
    #[must_use]
    pub fn new(joint: JointId, source: JointId, multiplier: f64, offset: f64) -> Self {
        Self {
            joint,
            source,
            multiplier,
            offset,
        }
    }

    /// The coupling a joint-coordinate constraint states when its polynomial is linear,
    /// `q_1 = c_0 + c_1 q_2` (an MJCF `<equality joint>` whose `polycoef` is `c0 c1 0 0 0`).
    #[must_use]
    pub fn from_constraint(c: &ConstraintModel) -> Option<Self> {
        match c.kind {
            ConstraintKind::JointCoordinate { polycoef }
                if polycoef[2..].iter().all(|&x| x == 0.0) =>
            {
                Some(Self::new(c.joint1?, c.joint2?, polycoef[1], polycoef[0]))
            }
            ConstraintKind::JointCoordinate { .. }
            | ConstraintKind::Point
            | ConstraintKind::Frame => None,
        }
    }
}

/// Why a set of couplings was refused; each names the joint.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MimicError {
    /// A joint index past the model's joints.
    #[error("mimic: joint index {index} out of range (the model has {njoints} joints)")]
    OutOfRange {
        /// The index.
        index: usize,
        /// The model's number of joints.
        njoints: usize,
    },
    /// A mimic or mimicked joint that is not a one-coordinate joint.
    #[error("mimic: joint \"{joint}\" is {kind}; a mimic joint and the joint it follows must each have one coordinate (revolute, continuous, prismatic, helical)")]
    NotOneDof {
        /// The joint.
        joint: String,
        /// Its type.
        kind: &'static str,
    },
    /// A joint that mimics itself, two couplings on one joint, or a chain that comes back.
    #[error("mimic: {0}")]
    Invalid(String),
    /// A multiplier or offset that is NaN or infinite.
    #[error("mimic: joint \"{joint}\": multiplier and offset must be finite")]
    NotFinite {
        /// The joint.
        joint: String,
    },
}

/// A model whose mimic joints follow their sources, evaluated in the reduced coordinates (see
/// the [module docs](self)). Made once, like a [`Model`]; evaluate it with a [`MimicData`].
#[derive(Clone, Debug)]
pub struct MimicModel {
    model: Model,
    /// The couplings, each resolved to a free source, in the order of their joints.
    mimics: Vec<Mimic>,
    nq: usize,
    nv: usize,
    /// Per joint of the full model: its `(idx_q, idx_v)` in the reduced coordinates (a mimic's
    /// are its source's, as Pinocchio's `idx_q`, `idx_v` of a mimic joint).
    coords: Vec<(usize, usize)>,
    /// Per full dof k: `q̇_full[k] = factor[k] · q̇[dof[k]]` (the one entry of row k of `G`).
    dof: Vec<usize>,
    factor: Vec<f64>,
    /// Per full coordinate i: `q_full[i] = factor · q[src] + offset` for a mimic, `q[src]` else.
    q_src: Vec<(usize, f64, f64)>,
    /// Per reduced coordinate: its index in the full `q` (and per reduced dof, in the full `v`).
    q_full_index: Vec<usize>,
    v_full_index: Vec<usize>,
}

impl MimicModel {
    /// The model `model` with `mimics` as couplings. A chain (a mimic of a mimic) is composed.
    ///
    /// # Errors
    /// [`MimicError`]: a joint out of range, a mimic or source that is not a one-coordinate
    /// joint, a joint that mimics itself or is coupled twice, a loop of mimics, a non-finite
    /// multiplier or offset.
    pub fn new(model: Model, mimics: &[Mimic]) -> Result<Self, MimicError> {
        let n = model.njoints();
        let name = |j: JointId| model.joint(j).name.clone();
        let mut of: Vec<Option<Mimic>> = vec![None; n];
        for m in mimics {
            for id in [m.joint, m.source] {
                if id.0 >= n {
                    return Err(MimicError::OutOfRange {
                        index: id.0,
                        njoints: n,
                    });
                }
                let j = model.joint(id);
                if j.nq != 1 || j.nv != 1 {
                    return Err(MimicError::NotOneDof {
                        joint: j.name.clone(),
                        kind: j.type_name(),
                    });
                }
            }
            if !(m.multiplier.is_finite() && m.offset.is_finite()) {
                return Err(MimicError::NotFinite {
                    joint: name(m.joint),
                });
            }
            if m.joint == m.source {
                let msg = format!("joint \"{}\" mimics itself", name(m.joint));
                return Err(MimicError::Invalid(msg));
            }
            if of[m.joint.0].is_some() {
                let msg = format!("joint \"{}\" mimics two joints", name(m.joint));
                return Err(MimicError::Invalid(msg));
            }
            of[m.joint.0] = Some(*m);
        }
        // compose chains: q_c = m2 (m1 q_a + o1) + o2
        let mut resolved = Vec::new();
        for m in of.iter().flatten() {
            let (mut r, mut path) = (*m, vec![name(m.joint)]);
            while let Some(next) = of[r.source.0] {
                path.push(name(r.source));
                if path.len() > n {
                    let msg = format!("mimic loop: {}", path[..n + 1].join(" -> "));
                    return Err(MimicError::Invalid(msg));
                }
                r = Mimic::new(
                    r.joint,
                    next.source,
                    r.multiplier * next.multiplier,
                    r.multiplier * next.offset + r.offset,
                );
            }
            resolved.push(r);
        }
        let free = |id: usize| of[id].is_none();
        let (mut coords, mut nq, mut nv) = (vec![(0, 0); n], 0, 0);
        let (mut q_full_index, mut v_full_index) = (Vec::new(), Vec::new());
        for (i, j) in model.joints().iter().enumerate() {
            if free(i) {
                coords[i] = (nq, nv);
                q_full_index.extend(j.coordinates());
                v_full_index.extend(j.dofs());
                nq += j.nq;
                nv += j.nv;
            }
        }
        let (mut dof, mut factor) = (vec![0; model.nv()], vec![1.0; model.nv()]);
        let mut q_src = vec![(0, 1.0, 0.0); model.nq()];
        for (i, j) in model.joints().iter().enumerate() {
            let (iq, iv) = coords[i];
            for k in 0..j.nq {
                q_src[j.idx_q + k] = (iq + k, 1.0, 0.0);
            }
            for k in 0..j.nv {
                dof[j.idx_v + k] = iv + k;
            }
        }
        for m in &resolved {
            let (j, s) = (model.joint(m.joint), m.source.0);
            coords[m.joint.0] = coords[s];
            q_src[j.idx_q] = (coords[s].0, m.multiplier, m.offset);
            (dof[j.idx_v], factor[j.idx_v]) = (coords[s].1, m.multiplier);
        }
        Ok(Self {
            model,
            mimics: resolved,
            nq,
            nv,
            coords,
            dof,
            factor,
            q_src,
            q_full_index,
            v_full_index,
        })
    }

    /// The full model (every joint with its own coordinate).
    #[must_use]
    pub fn model(&self) -> &Model {
        &self.model
    }
    /// The couplings, each to a joint that is no mimic (chains composed), in joint order.
    #[must_use]
    pub fn mimics(&self) -> &[Mimic] {
        &self.mimics
    }
    /// The coupling that drives joint `id`, if it is a mimic joint.
    #[must_use]
    pub fn mimic_of(&self, id: JointId) -> Option<&Mimic> {
        self.mimics.iter().find(|m| m.joint == id)
    }
    /// The number of reduced configuration coordinates.
    #[must_use]
    pub fn nq(&self) -> usize {
        self.nq
    }
    /// The number of degrees of freedom (the full model's minus one per mimic joint).
    #[must_use]
    pub fn nv(&self) -> usize {
        self.nv
    }
    /// Joint `id`'s `(idx_q, idx_v)` in the reduced coordinates; a mimic joint has none of its
    /// own and gets its source's (as Pinocchio's `idx_q`, `idx_v` of a mimic joint, whose `nq`,
    /// `nv` are 0). Panics if `id` is out of range.
    #[must_use]
    pub fn joint_coordinates(&self, id: JointId) -> (usize, usize) {
        self.coords[id.0]
    }
    /// The reduced coordinates' indices in the full `q` (the mimic coordinates left out).
    #[must_use]
    pub fn q_full_indices(&self) -> &[usize] {
        &self.q_full_index
    }
    /// The reduced degrees of freedom's indices in the full `v`.
    #[must_use]
    pub fn v_full_indices(&self) -> &[usize] {
        &self.v_full_index
    }

    /// `q_full = E(q)`: each mimic coordinate `multiplier · q_source + offset`, the others
    /// copied.
    ///
    /// # Panics
    /// If `q` is shorter than [`nq`](Self::nq) or `q_full` than the full model's (the helpers
    /// below likewise: their lengths are the reduced and the full model's).
    pub fn expand_q(&self, q: &[f64], q_full: &mut [f64]) {
        for (x, &(src, m, o)) in q_full.iter_mut().zip(&self.q_src) {
            *x = m * q[src] + o;
        }
    }
    /// `v_full = G v` (also for accelerations).
    pub fn expand_v(&self, v: &[f64], v_full: &mut [f64]) {
        for ((x, &d), &f) in v_full.iter_mut().zip(&self.dof).zip(&self.factor) {
            *x = f * v[d];
        }
    }
    /// `q`: the full configuration with its mimic coordinates dropped.
    pub fn reduce_q(&self, q_full: &[f64], q: &mut [f64]) {
        for (x, &i) in q.iter_mut().zip(&self.q_full_index) {
            *x = q_full[i];
        }
    }
    /// The full configuration consistent with the couplings, from `q` in the reduced
    /// coordinates (`nq` numbers) or in the full model's (each mimic coordinate then recomputed
    /// from its source's); `None` for another length.
    #[must_use]
    pub fn consistent_q(&self, q: &[f64]) -> Option<Vec<f64>> {
        let mut reduced = vec![0.0; self.nq];
        if q.len() == self.nq {
            reduced.copy_from_slice(q);
        } else if q.len() == self.model.nq() {
            self.reduce_q(q, &mut reduced);
        } else {
            return None;
        }
        let mut full = vec![0.0; self.model.nq()];
        self.expand_q(&reduced, &mut full);
        Some(full)
    }
    /// The full velocity `G v` from `v` in the reduced coordinates (`nv` numbers) or in the
    /// full model's (its free dofs kept); `None` for another length.
    #[must_use]
    pub fn consistent_v(&self, v: &[f64]) -> Option<Vec<f64>> {
        let reduced: Vec<f64> = if v.len() == self.nv {
            v.to_vec()
        } else if v.len() == self.model.nv() {
            self.v_full_index.iter().map(|&k| v[k]).collect()
        } else {
            return None;
        };
        let mut full = vec![0.0; self.model.nv()];
        self.expand_v(&reduced, &mut full);
        Some(full)
    }
    /// `τ = Gᵀ τ_full`: the generalised force on the reduced coordinates that does the same
    /// virtual work (a mimic dof's force reaches its source times the multiplier).
    pub fn reduce_force(&self, tau_full: &[f64], tau: &mut [f64]) {
        tau.iter_mut().for_each(|x| *x = 0.0);
        for ((x, &d), &f) in tau_full.iter().zip(&self.dof).zip(&self.factor) {
            tau[d] += f * x;
        }
    }
    /// `Gᵀ A G` of a full `nv_full x nv_full` matrix (`M`, `∂τ/∂q`, `∂τ/∂q̇`).
    pub fn reduce_matrix(&self, a: &DMatrix<f64>, out: &mut DMatrix<f64>) {
        out.fill(0.0);
        for c in 0..a.ncols() {
            let (dc, fc) = (self.dof[c], self.factor[c]);
            for r in 0..a.nrows() {
                out[(self.dof[r], dc)] += self.factor[r] * fc * a[(r, c)];
            }
        }
    }
    /// `A G` of a full matrix with `nv_full` columns (a Jacobian).
    pub fn reduce_columns(&self, a: &DMatrix<f64>, out: &mut DMatrix<f64>) {
        out.fill(0.0);
        for c in 0..a.ncols() {
            let (dc, fc) = (self.dof[c], self.factor[c]);
            for r in 0..a.nrows() {
                out[(r, dc)] += fc * a[(r, c)];
            }
        }
    }
    /// The coupling matrix `G` (nv_full x nv): `q̇_full = G q̇`.
    #[must_use]
    pub fn coupling_matrix(&self) -> DMatrix<f64> {
        let mut g = DMatrix::zeros(self.model.nv(), self.nv);
        for (k, (&d, &f)) in self.dof.iter().zip(&self.factor).enumerate() {
            g[(k, d)] = f;
        }
        g
    }
    /// The couplings as constraints of the full model, `q_m = offset + multiplier · q_s`
    /// ([`ConstraintModel::joint_coordinate`]): the constrained dynamics of the full model under
    /// them are this model's, and the constraint force is the torque that drives each mimic.
    #[must_use]
    pub fn constraints(&self) -> Vec<ConstraintModel> {
        self.mimics
            .iter()
            .map(|m| {
                let poly = [m.offset, m.multiplier, 0.0, 0.0, 0.0];
                ConstraintModel::joint_coordinate(m.joint, Some(m.source), poly)
            })
            .collect()
    }

    /// Checks `md` and the reduced inputs, and writes `E(q)`, `G v`, `G a` into its full buffers.
    fn load(
        &self,
        md: &mut MimicData,
        q: &[f64],
        vs: [Option<(&'static str, &[f64])>; 2],
    ) -> Result<(), MultibodyError> {
        check_data(&self.model, &md.data)?;
        if md.tau.len() != self.nv || md.q.len() != self.model.nq() {
            return Err(MultibodyError::DataMismatch {
                njoints: md.data.placements.len(),
                nq: md.q.len(),
                nv: md.v.len(),
            });
        }
        DimensionError::check("q", self.nq, q.len())?;
        finite("q", q)?;
        self.expand_q(q, &mut md.q);
        for (x, out) in vs.into_iter().zip([&mut md.v, &mut md.a]) {
            if let Some((what, x)) = x {
                DimensionError::check(what, self.nv, x.len())?;
                finite(what, x)?;
                self.expand_v(x, out);
            }
        }
        Ok(())
    }

    /// `q_out = q ⊕ v dt` on the free joints' groups.
    ///
    /// # Errors
    /// Wrong lengths, non-finite input or a non-unit quaternion.
    pub fn integrate(
        &self,
        q: &[f64],
        v: &[f64],
        dt: f64,
        q_out: &mut [f64],
    ) -> Result<(), MultibodyError> {
        self.check_q(q)?;
        DimensionError::check("v", self.nv, v.len())?;
        finite("v", v)?;
        DimensionError::check("q_out", self.nq, q_out.len())?;
        for (j, &(iq, iv)) in self.free_joints() {
            let (rq, rv) = (iq..iq + j.nq, iv..iv + j.nv);
            j.kind.integrate(&q[rq.clone()], &v[rv], dt, &mut q_out[rq]);
        }
        Ok(())
    }

    /// `v_out = q1 ⊖ q0` on the free joints' groups.
    ///
    /// # Errors
    /// Wrong lengths, non-finite input or a non-unit quaternion.
    pub fn difference(
        &self,
        q0: &[f64],
        q1: &[f64],
        v_out: &mut [f64],
    ) -> Result<(), MultibodyError> {
        self.check_q(q0)?;
        self.check_q(q1)?;
        DimensionError::check("v_out", self.nv, v_out.len())?;
        for (j, &(iq, iv)) in self.free_joints() {
            let rq = iq..iq + j.nq;
            let out = &mut v_out[iv..iv + j.nv];
            j.kind.difference(&q0[rq.clone()], &q1[rq], out);
        }
        Ok(())
    }

    /// The neutral configuration of the free joints (zeros, identity quaternions).
    #[must_use]
    pub fn neutral(&self) -> Vec<f64> {
        let mut q = vec![0.0; self.nq];
        self.reduce_q(&super::neutral(&self.model), &mut q);
        q
    }

    /// A random configuration of the free joints within their limits
    /// ([`random_configuration`](super::random_configuration)).
    #[must_use]
    pub fn random_configuration(&self, rng: &mut Rng) -> Vec<f64> {
        let mut q = vec![0.0; self.nq];
        self.reduce_q(&super::random_configuration(&self.model, rng), &mut q);
        q
    }

    /// The free joints with their reduced `(idx_q, idx_v)`.
    fn free_joints(&self) -> impl Iterator<Item = (&super::Joint, &(usize, usize))> {
        let joints = self.model.joints().iter().zip(&self.coords).enumerate();
        joints
            .filter(|(i, _)| self.mimic_of(JointId(*i)).is_none())
            .map(|(_, x)| x)
    }

    /// Length `nq`, finite, each free joint's quaternion of unit norm (nothing allocated).
    fn check_q(&self, q: &[f64]) -> Result<(), MultibodyError> {
        DimensionError::check("q", self.nq, q.len())?;
        finite("q", q)?;
        for (j, &(iq, _)) in self.free_joints() {
            if let Some(o) = j.kind.quaternion_offset() {
                let norm = crate::spatial::quat_norm(&q[iq + o..iq + o + 4]);
                if (norm - 1.0).abs() > super::QUATERNION_TOLERANCE {
                    let joint = j.name.clone();
                    return Err(MultibodyError::NotUnitQuaternion { joint, norm });
                }
            }
        }
        Ok(())
    }
}

fn finite(what: &'static str, x: &[f64]) -> Result<(), MultibodyError> {
    match super::first_non_finite(x) {
        Some(index) => Err(MultibodyError::NonFinite { what, index }),
        None => Ok(()),
    }
}
