//! The workspace of a [`MimicModel`].

use super::MimicModel;
use crate::multibody::Data;
use nalgebra::{DMatrix, DVector};

/// The workspace of a [`MimicModel`]: the full model's [`Data`], the full state and the reduced
/// results, each filled by the verb named on it. No verb allocates.
#[derive(Clone, Debug)]
pub struct MimicData {
    /// The full model's workspace (placements, velocities, ... of every body).
    pub data: Data,
    /// The full state of the last call: `E(q)`, `G q̇`, `G q̈`.
    pub q: Vec<f64>,
    /// `G q̇`.
    pub v: Vec<f64>,
    /// `G q̈`.
    pub a: Vec<f64>,
    /// `τ` ([`MimicModel::rnea`], [`MimicModel::rnea_derivatives`]).
    pub tau: DVector<f64>,
    /// `c + g` ([`MimicModel::nonlinear_effects`], [`MimicModel::aba`]).
    pub nle: DVector<f64>,
    /// `g` ([`MimicModel::gravity_torques`]).
    pub g: DVector<f64>,
    /// `q̈` ([`MimicModel::aba`]).
    pub ddq: DVector<f64>,
    /// `M` ([`MimicModel::crba`], [`MimicModel::aba`], the derivatives).
    pub mass_matrix: DMatrix<f64>,
    /// `M⁻¹` ([`MimicModel::aba_derivatives`]).
    pub minv: DMatrix<f64>,
    /// `∂τ/∂q`.
    pub dtau_dq: DMatrix<f64>,
    /// `∂τ/∂q̇`.
    pub dtau_dv: DMatrix<f64>,
    /// `∂q̈/∂q`.
    pub dqdd_dq: DMatrix<f64>,
    /// `∂q̈/∂q̇`.
    pub dqdd_dv: DMatrix<f64>,
    /// A frame Jacobian (6 x nv, [`MimicModel::frame_jacobian`]).
    pub jacobian: DMatrix<f64>,
    pub(super) chol: DMatrix<f64>,
}

impl MimicData {
    /// The workspace of `mm`.
    #[must_use]
    pub fn new(mm: &MimicModel) -> Self {
        let (n, full) = (mm.nv, &mm.model);
        let square = || DMatrix::zeros(n, n);
        Self {
            data: Data::new(full),
            q: vec![0.0; full.nq()],
            v: vec![0.0; full.nv()],
            a: vec![0.0; full.nv()],
            tau: DVector::zeros(n),
            nle: DVector::zeros(n),
            g: DVector::zeros(n),
            ddq: DVector::zeros(n),
            mass_matrix: square(),
            minv: square(),
            dtau_dq: square(),
            dtau_dv: square(),
            dqdd_dq: square(),
            dqdd_dv: square(),
            jacobian: DMatrix::zeros(6, n),
            chol: square(),
        }
    }
}
