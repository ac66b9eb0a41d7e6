//! The verbs of a [`MimicModel`]: each loads the full state `(E(q), G q̇, G q̈)` into its
//! [`MimicData`], runs the full model's algorithm and projects the result with `G` (the table of
//! the [module docs](super)).

use super::{MimicData, MimicModel};
use crate::error::DimensionError;
use crate::multibody::algorithms::derivatives::{AbaDerivatives, RneaDerivatives};
use crate::multibody::constraints::solver::{cholesky, cholesky_solve};
use crate::multibody::{
    center_of_mass, crba, forward_kinematics_q, frame_jacobian, gravity_torques, joint_jacobian,
    kinetic_energy, nonlinear_effects, potential_energy, rnea, rnea_derivatives, FrameId, JointId,
    MultibodyError, ReferenceFrame,
};
use crate::spatial::Vec3;
use nalgebra::{DMatrix, DVector};

impl MimicModel {
    /// Inverse dynamics in the reduced coordinates, `τ = Gᵀ ID(E(q), G q̇, G q̈)`, into `md.tau`.
    ///
    /// # Errors
    /// Wrong lengths, non-finite entries, a non-unit quaternion, or an `md` made for another
    /// model.
    pub fn rnea<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        v: &[f64],
        a: &[f64],
    ) -> Result<&'a DVector<f64>, MultibodyError> {
        self.load(md, q, [Some(("v", v)), Some(("a", a))])?;
        let tau = rnea(&self.model, &mut md.data, &md.q, &md.v, &md.a)?;
        self.reduce_force(tau.as_slice(), md.tau.as_mut_slice());
        Ok(&md.tau)
    }

    /// The mass matrix in the reduced coordinates, `M = Gᵀ M_full G` (armature included), into
    /// `md.mass_matrix`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn crba<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
    ) -> Result<&'a DMatrix<f64>, MultibodyError> {
        self.load(md, q, [None, None])?;
        let m = crba(&self.model, &mut md.data, &md.q)?;
        self.reduce_matrix(m, &mut md.mass_matrix);
        Ok(&md.mass_matrix)
    }

    /// `c + g = Gᵀ (c + g)_full`, into `md.nle`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn nonlinear_effects<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        v: &[f64],
    ) -> Result<&'a DVector<f64>, MultibodyError> {
        self.load(md, q, [Some(("v", v)), None])?;
        let b = nonlinear_effects(&self.model, &mut md.data, &md.q, &md.v)?;
        self.reduce_force(b.as_slice(), md.nle.as_mut_slice());
        Ok(&md.nle)
    }

    /// `g = Gᵀ g_full`, into `md.g`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn gravity_torques<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
    ) -> Result<&'a DVector<f64>, MultibodyError> {
        self.load(md, q, [None, None])?;
        let g = gravity_torques(&self.model, &mut md.data, &md.q)?;
        self.reduce_force(g.as_slice(), md.g.as_mut_slice());
        Ok(&md.g)
    }

    /// Forward dynamics `q̈ = M⁻¹ (τ − c − g)` in the reduced coordinates (the reduced `M` by a
    /// dense Cholesky factorisation: the coupling breaks the tree structure ABA relies on), into
    /// `md.ddq`; `md.mass_matrix` holds `M`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea), and [`MultibodyError::NotPositiveDefinite`].
    pub fn aba<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        v: &[f64],
        tau: &[f64],
    ) -> Result<&'a DVector<f64>, MultibodyError> {
        DimensionError::check("tau", self.nv, tau.len())?;
        super::finite("tau", tau)?;
        self.nonlinear_effects(md, q, v)?;
        self.factor_mass_matrix(md)?;
        for ((x, t), b) in md.ddq.iter_mut().zip(tau).zip(md.nle.iter()) {
            *x = t - b;
        }
        cholesky_solve(&md.chol, self.nv, md.ddq.as_mut_slice());
        Ok(&md.ddq)
    }

    /// `M` at `md.q` into `md.mass_matrix`, its Cholesky factor into `md.chol`.
    fn factor_mass_matrix(&self, md: &mut MimicData) -> Result<(), MultibodyError> {
        let m = crba(&self.model, &mut md.data, &md.q)?;
        self.reduce_matrix(m, &mut md.mass_matrix);
        md.chol.copy_from(&md.mass_matrix);
        cholesky(&mut md.chol, self.nv).map_err(|_| MultibodyError::NotPositiveDefinite)
    }

    /// `∂τ/∂q`, `∂τ/∂q̇` and `M` in the reduced coordinates: `Gᵀ ∂τ_full/∂q_full G` (each mimic
    /// coordinate is linear in its source's, so `δq_full = G δq`), into `md.dtau_dq`,
    /// `md.dtau_dv`, `md.mass_matrix`; `md.tau` holds `τ`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea), and a joint whose motion subspace depends on `q`.
    pub fn rnea_derivatives<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        v: &[f64],
        a: &[f64],
    ) -> Result<RneaDerivatives<'a>, MultibodyError> {
        self.load(md, q, [Some(("v", v)), Some(("a", a))])?;
        self.reduced_rnea_derivatives(md)?;
        Ok(RneaDerivatives {
            dtau_dq: &md.dtau_dq,
            dtau_dv: &md.dtau_dv,
            dtau_da: &md.mass_matrix,
        })
    }

    /// The RNEA derivatives at the full state in `md`, reduced.
    fn reduced_rnea_derivatives(&self, md: &mut MimicData) -> Result<(), MultibodyError> {
        let d = rnea_derivatives(&self.model, &mut md.data, &md.q, &md.v, &md.a)?;
        self.reduce_matrix(d.dtau_dq, &mut md.dtau_dq);
        self.reduce_matrix(d.dtau_dv, &mut md.dtau_dv);
        self.reduce_matrix(d.dtau_da, &mut md.mass_matrix);
        self.reduce_force(md.data.tau.as_slice(), md.tau.as_mut_slice());
        Ok(())
    }

    /// `∂q̈/∂q = −M⁻¹ ∂τ/∂q`, `∂q̈/∂q̇ = −M⁻¹ ∂τ/∂q̇` (the RNEA derivatives at `q̈`) and
    /// `∂q̈/∂τ = M⁻¹`, in the reduced coordinates (Carpentier & Mansard, RSS 2018, §V), into
    /// `md.dqdd_dq`, `md.dqdd_dv`, `md.minv`; `md.ddq` holds `q̈`.
    ///
    /// # Errors
    /// As [`aba`](Self::aba), and a joint whose motion subspace depends on `q`.
    pub fn aba_derivatives<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        v: &[f64],
        tau: &[f64],
    ) -> Result<AbaDerivatives<'a>, MultibodyError> {
        self.aba(md, q, v, tau)?;
        let MimicData { a, ddq, .. } = md;
        self.expand_v(ddq.as_slice(), a);
        self.reduced_rnea_derivatives(md)?;
        let n = self.nv;
        md.minv.fill_with_identity();
        for c in 0..n {
            let mut col = md.minv.column_mut(c);
            cholesky_solve(&md.chol, n, col.as_mut_slice());
        }
        md.minv.mul_to(&md.dtau_dq, &mut md.dqdd_dq);
        md.minv.mul_to(&md.dtau_dv, &mut md.dqdd_dv);
        md.dqdd_dq.neg_mut();
        md.dqdd_dv.neg_mut();
        Ok(AbaDerivatives {
            dqdd_dq: &md.dqdd_dq,
            dqdd_dv: &md.dqdd_dv,
            dqdd_dtau: &md.minv,
        })
    }

    /// The Jacobian (6 x nv) of frame `frame` in `rf`, `J = J_full G`, into `md.jacobian`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea), and a frame out of range.
    pub fn frame_jacobian<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        frame: FrameId,
        rf: ReferenceFrame,
    ) -> Result<&'a DMatrix<f64>, MultibodyError> {
        self.load(md, q, [None, None])?;
        let j = frame_jacobian(&self.model, &mut md.data, &md.q, frame, rf)?;
        self.reduce_columns(j, &mut md.jacobian);
        Ok(&md.jacobian)
    }

    /// The Jacobian (6 x nv) of joint `joint`'s moved frame in `rf`, `J = J_full G`, into
    /// `md.jacobian`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea), and a joint out of range.
    pub fn joint_jacobian<'a>(
        &self,
        md: &'a mut MimicData,
        q: &[f64],
        joint: JointId,
        rf: ReferenceFrame,
    ) -> Result<&'a DMatrix<f64>, MultibodyError> {
        self.load(md, q, [None, None])?;
        let j = joint_jacobian(&self.model, &mut md.data, &md.q, joint, rf)?;
        self.reduce_columns(j, &mut md.jacobian);
        Ok(&md.jacobian)
    }

    /// Forward kinematics: every joint's world placement into `md.data.placements` (and the
    /// frames' into `md.data.frame_placements`).
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn forward_kinematics(&self, md: &mut MimicData, q: &[f64]) -> Result<(), MultibodyError> {
        self.load(md, q, [None, None])?;
        forward_kinematics_q(&self.model, &mut md.data, &md.q)?;
        crate::multibody::update_frame_placements(&self.model, &mut md.data);
        Ok(())
    }

    /// `½ q̇ᵀ M q̇`, the full model's kinetic energy at `(E(q), G q̇)`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn kinetic_energy(
        &self,
        md: &mut MimicData,
        q: &[f64],
        v: &[f64],
    ) -> Result<f64, MultibodyError> {
        self.load(md, q, [Some(("v", v)), None])?;
        kinetic_energy(&self.model, &mut md.data, &md.q, &md.v)
    }

    /// The potential energy `-Σ mᵢ gᵀ cᵢ` at `E(q)`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn potential_energy(&self, md: &mut MimicData, q: &[f64]) -> Result<f64, MultibodyError> {
        self.load(md, q, [None, None])?;
        potential_energy(&self.model, &mut md.data, &md.q)
    }

    /// The centre of mass of the moving bodies at `E(q)`.
    ///
    /// # Errors
    /// As [`rnea`](Self::rnea).
    pub fn center_of_mass(&self, md: &mut MimicData, q: &[f64]) -> Result<Vec3, MultibodyError> {
        self.load(md, q, [None, None])?;
        center_of_mass(&self.model, &mut md.data, &md.q)
    }
}
