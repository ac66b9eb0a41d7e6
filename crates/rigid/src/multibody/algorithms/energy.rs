//! Kinetic and potential energy and the centre of mass.

use super::kinematics::{forward_kinematics_qv, placements_unchecked};
use crate::multibody::{check_data, check_q, Data, Model, MultibodyError};
use crate::spatial::Vec3;

/// Kinetic energy `K = ½ vᵀ M(q) v = Σ_i ½ V_iᵀ G_i V_i + Σ_k ½ armature_k v_k²` (Lynch & Park
/// §8.1.2; the armature term is the energy of the reflected rotor inertias, so that `K` matches
/// the mass matrix of [`crba`](super::crba), as in Pinocchio), with the body twists `V_i` from
/// forward kinematics.
///
/// # Errors
/// Wrong lengths, non-finite entries, or a non-unit quaternion.
pub fn kinetic_energy(
    model: &Model,
    data: &mut Data,
    q: &[f64],
    v: &[f64],
) -> Result<f64, MultibodyError> {
    forward_kinematics_qv(model, data, q, v)?;
    let bodies: f64 = model
        .inertias()
        .iter()
        .zip(&data.velocities)
        .map(|(G, V)| G.kinetic_energy(V))
        .sum();
    let rotors: f64 = model
        .armature
        .iter()
        .zip(v)
        .map(|(a, v)| 0.5 * a * v * v)
        .sum();
    Ok(bodies + rotors)
}

/// Potential energy in the uniform gravity field, `U = -Σ_i m_i gᵀ c_i` with `c_i` the world CoM of
/// moving body i (zero at the world origin; welded-to-world links excluded).
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
pub fn potential_energy(model: &Model, data: &mut Data, q: &[f64]) -> Result<f64, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    placements_unchecked(model, data, q);
    let g = model.gravity;
    Ok(model
        .inertias()
        .iter()
        .zip(&data.placements)
        .map(|(G, oMi)| -g.dot(&(oMi.rotation * G.first_moment() + oMi.translation * G.mass())))
        .sum())
}

/// Centre of mass of the moving bodies in the world, `c = Σ m_i c_i / Σ m_i` (zero if massless).
/// Also sets `data.com` and `data.mass`.
///
/// # Errors
/// Wrong length, non-finite entry or non-unit quaternion in `q`.
pub fn center_of_mass(model: &Model, data: &mut Data, q: &[f64]) -> Result<Vec3, MultibodyError> {
    check_q(model, q)?;
    check_data(model, data)?;
    placements_unchecked(model, data, q);
    let mut h = Vec3::zeros();
    let mut m = 0.0;
    for (G, oMi) in model.inertias().iter().zip(&data.placements) {
        h += oMi.rotation * G.first_moment() + oMi.translation * G.mass();
        m += G.mass();
    }
    data.mass = m;
    data.com = if m > 0.0 { h / m } else { Vec3::zeros() };
    Ok(data.com)
}
