//! Pinocchio's layout of the configuration and velocity vectors, so that `q`, `v`, `a` and `τ`
//! pass between rigid and Pinocchio-based code unchanged.
//!
//! For the same joints in the same order (a URDF loaded with
//! [`SiblingOrder::Name`](crate::io::urdf::SiblingOrder::Name), the order of urdfdom and so of
//! Pinocchio), the two layouts differ in three joint types only:
//!
//! | joint | rigid `q` | Pinocchio `q` | rigid `v` | Pinocchio `v` |
//! | --- | --- | --- | --- | --- |
//! | continuous | `θ` | `(cos θ, sin θ)` | `θ̇` | `θ̇` |
//! | planar | `(x, y, θ)` | `(x, y, cos θ, sin θ)` | `(v_x, v_y, ω)` | `(v_x, v_y, ω)` |
//! | free-flyer | `(x, y, z, qx, qy, qz, qw)` | the same | `(ω_b, v_b)` | `(v_b, ω_b)` |
//!
//! Every other joint (revolute, prismatic, spherical) has the same coordinates in both. So a
//! Pinocchio vector in velocity space (`v`, `a`, `τ`, rows and columns of `M`) is rigid's with
//! each free-flyer's two halves swapped ([`PinocchioLayout::v_index`]), and a Pinocchio
//! configuration is rigid's with each angle of a continuous or planar joint written as its cosine
//! and sine ([`PinocchioLayout::q_to_pinocchio`], [`PinocchioLayout::q_from_pinocchio`]).
//!
//! ```
//! use rigid::interop::PinocchioLayout;
//! use rigid::multibody::{JointType, ModelBuilder};
//! use rigid::mass::SpatialInertia;
//! use rigid::spatial::{Transform, Vec3};
//! let mut b = ModelBuilder::new("wheel");
//! let g = SpatialInertia::from_com(1.0, Vec3::zeros(), rigid::mass::RotationalInertia::diagonal(1.0, 1.0, 1.0));
//! let base = b.add_joint(None, "base", JointType::FreeFlyer, Transform::identity(), g)?;
//! let wheel = b.add_joint(Some(base), "wheel", JointType::Revolute { axis: Vec3::y() }, Transform::identity(), g)?;
//! b.set_continuous(wheel)?; // a URDF `continuous` joint
//! let model = b.build()?;
//! let layout = PinocchioLayout::new(&model);
//! assert_eq!((model.nq(), layout.nq()), (8, 9));
//! let mut q_pin = vec![0.0; 9];
//! layout.q_to_pinocchio(&[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.5], &mut q_pin);
//! assert_eq!(&q_pin[7..], &[0.5f64.cos(), 0.5f64.sin()]);
//! assert_eq!(layout.v_index(0), 3); // Pinocchio's v[0] (linear x) is rigid's v[3]
//! # Ok::<(), rigid::multibody::ModelError>(())
//! ```

use crate::error::DimensionError;
use crate::multibody::{Model, MultibodyError, PinocchioCoords};
use thiserror::Error;

/// Largest accepted `|√(c² + s²) - 1|` for the `(cos θ, sin θ)` pair of a continuous or planar
/// joint in Pinocchio's layout (as [`QUATERNION_TOLERANCE`](crate::multibody::QUATERNION_TOLERANCE)).
pub const COS_SIN_TOLERANCE: f64 = 1e-6;

/// A Pinocchio-layout configuration that rigid cannot read.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum LayoutError {
    /// A vector of the wrong length ([`MultibodyError::Dimension`]) or a NaN or infinite entry
    /// ([`MultibodyError::NonFinite`], its index in the Pinocchio-layout vector).
    #[error(transparent)]
    Input(#[from] MultibodyError),
    /// A `(cos θ, sin θ)` pair that is not on the unit circle.
    #[error(
        "joint '{joint}': (cos θ, sin θ) = ({cos}, {sin}) has norm {norm}, not 1 (tolerance 1e-6)"
    )]
    NotUnitCosSin {
        /// The joint.
        joint: String,
        /// The cosine given.
        cos: f64,
        /// The sine given.
        sin: f64,
        /// `√(c² + s²)`.
        norm: f64,
    },
}

/// One joint: its kind of difference and where its coordinates start in each layout.
#[derive(Clone, Copy, Debug)]
struct JointMap {
    coords: PinocchioCoords,
    /// First index in rigid's `q`.
    idx_q: usize,
    /// Number of rigid configuration coordinates.
    nq: usize,
    /// First index in Pinocchio's `q`.
    pin_idx_q: usize,
    /// Number of Pinocchio configuration coordinates.
    pin_nq: usize,
    /// First index in `v` (the same in both).
    idx_v: usize,
}

/// The map between rigid's layout of a [`Model`]'s vectors and Pinocchio's (see the
/// [module](crate::interop) documentation). Made once per model; the conversions allocate nothing.
#[derive(Clone, Debug)]
pub struct PinocchioLayout {
    joints: Vec<JointMap>,
    names: Vec<String>,
    nq: usize,
    /// `v_pin[k] = v[perm[k]]`; an involution (each free-flyer's halves swapped).
    perm: Vec<usize>,
}

impl PinocchioLayout {
    /// The layout map of `model` (joints in the model's order).
    #[must_use]
    pub fn new(model: &Model) -> Self {
        let joints = model.joints().iter().map(|j| (j, j.idx_q, j.idx_v));
        Self::of_joints(joints, model.nv())
    }

    /// The layout map of a model with mimic joints in its reduced coordinates
    /// ([`MimicModel`](crate::multibody::MimicModel)): the free joints' coordinates in
    /// Pinocchio's form, in the model's order, the mimic joints with none (Pinocchio's
    /// `mimic=True`). [`joint_q`](Self::joint_q) indexes the free joints.
    #[must_use]
    pub fn of_mimic(mm: &crate::multibody::MimicModel) -> Self {
        let model = mm.model();
        let joints = (0..model.njoints())
            .map(crate::multibody::JointId)
            .filter(|&id| mm.mimic_of(id).is_none())
            .map(|id| {
                let (iq, iv) = mm.joint_coordinates(id);
                (model.joint(id), iq, iv)
            });
        Self::of_joints(joints, mm.nv())
    }

    /// The map of these joints at these `(idx_q, idx_v)` in rigid's vectors.
    fn of_joints<'a>(
        list: impl Iterator<Item = (&'a crate::multibody::Joint, usize, usize)>,
        nv: usize,
    ) -> Self {
        let mut joints = Vec::new();
        let mut names = Vec::new();
        let mut perm: Vec<usize> = (0..nv).collect();
        let mut pin_idx_q = 0;
        for (j, idx_q, idx_v) in list {
            let coords = j.kind.pinocchio_coords(j.continuous);
            let pin_nq = coords.nq(j.nq);
            if coords == PinocchioCoords::FreeFlyer {
                for k in 0..3 {
                    perm.swap(idx_v + k, idx_v + 3 + k);
                }
            }
            joints.push(JointMap {
                coords,
                idx_q,
                nq: j.nq,
                pin_idx_q,
                pin_nq,
                idx_v,
            });
            names.push(j.name.clone());
            pin_idx_q += pin_nq;
        }
        Self {
            joints,
            names,
            nq: pin_idx_q,
            perm,
        }
    }

    /// Pinocchio's `nq`: rigid's plus one per continuous or planar joint.
    #[must_use]
    pub fn nq(&self) -> usize {
        self.nq
    }

    /// `nv` (the same in both layouts).
    #[must_use]
    pub fn nv(&self) -> usize {
        self.perm.len()
    }

    /// True when the two layouts are the same for this model (no continuous, planar or
    /// free-flyer joint): every conversion is a copy.
    #[must_use]
    pub fn is_identity(&self) -> bool {
        self.joints
            .iter()
            .all(|j| matches!(j.coords, PinocchioCoords::Same | PinocchioCoords::Spherical))
    }

    /// `(idx_q, nq)` of joint `i` (model order) in Pinocchio's `q`.
    #[must_use]
    pub fn joint_q(&self, i: usize) -> (usize, usize) {
        (self.joints[i].pin_idx_q, self.joints[i].pin_nq)
    }

    /// The index in rigid's velocity-space vectors of Pinocchio's coordinate `k`:
    /// `v_pin[k] = v[v_index(k)]`, and `M_pin[(r, c)] = M[(v_index(r), v_index(c))]`. The map is
    /// its own inverse.
    #[must_use]
    pub fn v_index(&self, k: usize) -> usize {
        self.perm[k]
    }

    /// `v_pin[k] = v[v_index(k)]` (also rigid from Pinocchio: the map is its own inverse).
    ///
    /// # Panics
    /// If a slice is shorter than `nv`.
    pub fn permute_v(&self, v: &[f64], out: &mut [f64]) {
        for (o, &p) in out.iter_mut().zip(&self.perm) {
            *o = v[p];
        }
    }

    /// `M_pin[(r, c)] = M[(v_index(r), v_index(c))]`: an `nv x nv` matrix of velocity space (`M`,
    /// `M⁻¹`, `C`, the derivatives of `τ` or `q̈`) with its rows and columns permuted, stored in
    /// `m` row-major or column-major (`out` in the same order). Also rigid's from Pinocchio's:
    /// the map is its own inverse.
    ///
    /// # Panics
    /// If `m` or `out` is shorter than `nv²`.
    pub fn permute_matrix(&self, m: &[f64], out: &mut [f64]) {
        let n = self.perm.len();
        for (row, &p) in out.chunks_exact_mut(n.max(1)).take(n).zip(&self.perm) {
            self.permute_v(&m[p * n..(p + 1) * n], row);
        }
    }

    /// Pinocchio's configuration of rigid's `q`: `(cos θ, sin θ)` for each angle of a continuous
    /// or planar joint, other coordinates copied.
    ///
    /// # Panics
    /// If `q` is shorter than the model's `nq` or `q_pin` than [`nq`](Self::nq).
    pub fn q_to_pinocchio(&self, q: &[f64], q_pin: &mut [f64]) {
        for j in &self.joints {
            let (src, dst) = (&q[j.idx_q..j.idx_q + j.nq], &mut q_pin[j.pin_idx_q..]);
            match j.coords {
                PinocchioCoords::CosSin => (dst[1], dst[0]) = src[0].sin_cos(),
                PinocchioCoords::Planar => {
                    dst[0] = src[0];
                    dst[1] = src[1];
                    (dst[3], dst[2]) = src[2].sin_cos();
                }
                PinocchioCoords::Same | PinocchioCoords::FreeFlyer | PinocchioCoords::Spherical => {
                    dst[..j.nq].copy_from_slice(src)
                }
            }
        }
    }

    /// Rigid's configuration of Pinocchio's `q_pin`: `θ = atan2(sin θ, cos θ)` for each
    /// continuous or planar joint, other coordinates copied.
    ///
    /// # Errors
    /// A wrong length, a non-finite entry (its index in `q_pin`), or a `(cos θ, sin θ)` pair off
    /// the unit circle by more than [`COS_SIN_TOLERANCE`] (naming the joint).
    pub fn q_from_pinocchio(&self, q_pin: &[f64], q: &mut [f64]) -> Result<(), LayoutError> {
        DimensionError::check("q", self.nq, q_pin.len()).map_err(MultibodyError::from)?;
        if let Some(index) = q_pin.iter().position(|x| !x.is_finite()) {
            return Err(MultibodyError::NonFinite { what: "q", index }.into());
        }
        for (j, name) in self.joints.iter().zip(&self.names) {
            let src = &q_pin[j.pin_idx_q..j.pin_idx_q + j.pin_nq];
            let dst = &mut q[j.idx_q..j.idx_q + j.nq];
            let angle = |c: f64, s: f64| {
                let norm = c.hypot(s);
                if (norm - 1.0).abs() > COS_SIN_TOLERANCE {
                    return Err(LayoutError::NotUnitCosSin {
                        joint: name.clone(),
                        cos: c,
                        sin: s,
                        norm,
                    });
                }
                Ok(s.atan2(c))
            };
            match j.coords {
                PinocchioCoords::CosSin => dst[0] = angle(src[0], src[1])?,
                PinocchioCoords::Planar => {
                    dst[0] = src[0];
                    dst[1] = src[1];
                    dst[2] = angle(src[2], src[3])?;
                }
                PinocchioCoords::Same | PinocchioCoords::FreeFlyer | PinocchioCoords::Spherical => {
                    dst.copy_from_slice(src)
                }
            }
        }
        Ok(())
    }

    /// Moves each continuous and planar angle of `q1` by a multiple of 2π to within π of `q0`'s
    /// (`θ1 ← θ0 + atan2(sin(θ1 - θ0), cos(θ1 - θ0))`), so that rigid's
    /// [`difference`](crate::multibody::difference)`(q0, q1)` is Pinocchio's, whose angles are points on
    /// the circle (the shortest way round).
    pub fn nearest_angles(&self, q0: &[f64], q1: &mut [f64]) {
        for j in &self.joints {
            let k = match j.coords {
                PinocchioCoords::CosSin => j.idx_q,
                PinocchioCoords::Planar => j.idx_q + 2,
                PinocchioCoords::Same | PinocchioCoords::FreeFlyer | PinocchioCoords::Spherical => {
                    continue
                }
            };
            let d = q1[k] - q0[k];
            q1[k] = q0[k] + d.sin().atan2(d.cos());
        }
    }

    /// Gives each quaternion of `q_out = integrate(q, v)` Pinocchio's sign (rigid's
    /// [`integrate`](crate::multibody::integrate) returns `w ≥ 0`): for a free-flyer, the one with
    /// `q_out · q ≥ 0` (Pinocchio's SE(3) integration keeps the hemisphere); for a spherical
    /// joint, that of the product `q ⊗ exp(ω dt / 2)`, whose dot product with `q` is
    /// `cos(|ω| dt / 2)` (Pinocchio's SO(3) integration does not change the sign). `q`, `v` and
    /// `q_out` are in rigid's layout.
    pub fn integrate_signs(&self, q: &[f64], v: &[f64], dt: f64, q_out: &mut [f64]) {
        for j in &self.joints {
            let (o, cos_half) = match j.coords {
                PinocchioCoords::FreeFlyer => (j.idx_q + 3, 1.0),
                PinocchioCoords::Spherical => {
                    let w = &v[j.idx_v..j.idx_v + 3];
                    let angle = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt() * dt;
                    (j.idx_q, (0.5 * angle).cos())
                }
                PinocchioCoords::Same | PinocchioCoords::CosSin | PinocchioCoords::Planar => {
                    continue
                }
            };
            let dot: f64 = (o..o + 4).map(|k| q[k] * q_out[k]).sum();
            if dot * cos_half < 0.0 {
                for x in &mut q_out[o..o + 4] {
                    *x = -*x;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::urdf::{load_urdf_with, SiblingOrder, UrdfOptions};
    use crate::multibody::{integrate, random_configuration, Rng};

    /// The fixture with every joint type (continuous, planar, a free-flyer below the root).
    fn all_joints() -> Model {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/tests/pinocchio/all_joints.urdf"
        );
        let opts = UrdfOptions {
            floating: true,
            sibling_order: SiblingOrder::Name,
            ..UrdfOptions::default()
        };
        load_urdf_with(path, &opts).unwrap().0
    }

    #[test]
    fn configurations_survive_the_round_trip_through_pinocchio_layout() {
        let model = all_joints();
        let l = PinocchioLayout::new(&model);
        assert!(!l.is_identity());
        assert_eq!(l.nq(), model.nq() + 2); // one continuous, one planar joint
        let mut rng = Rng::new(3);
        for _ in 0..20 {
            let q = random_configuration(&model, &mut rng);
            let mut q_pin = vec![0.0; l.nq()];
            l.q_to_pinocchio(&q, &mut q_pin);
            let mut back = vec![0.0; model.nq()];
            l.q_from_pinocchio(&q_pin, &mut back).unwrap();
            for (a, b) in q.iter().zip(&back) {
                assert!((a - b).abs() < 1e-14, "{a} != {b}");
            }
        }
    }

    #[test]
    fn velocity_map_swaps_each_free_flyer_half_and_is_its_own_inverse() {
        let model = all_joints();
        let l = PinocchioLayout::new(&model);
        let v: Vec<f64> = (0..model.nv()).map(|k| k as f64).collect();
        let (mut p, mut back) = (vec![0.0; v.len()], vec![0.0; v.len()]);
        l.permute_v(&v, &mut p);
        l.permute_v(&p, &mut back);
        assert_eq!(back, v);
        let root = &model.joints()[0];
        assert_eq!(root.kind, crate::multibody::JointType::FreeFlyer);
        assert_eq!(&p[..6], &[3.0, 4.0, 5.0, 0.0, 1.0, 2.0]);
    }

    #[test]
    fn matrix_map_permutes_rows_and_columns_as_the_vectors() {
        let model = all_joints();
        let l = PinocchioLayout::new(&model);
        let n = model.nv();
        // M_pin x_pin = (M x)_pin for every x: the matrix map is the vector map on both sides
        let m: Vec<f64> = (0..n * n).map(|k| (k * 7 % 13) as f64 - 6.0).collect();
        let x: Vec<f64> = (0..n).map(|k| k as f64 + 0.5).collect();
        let mul = |m: &[f64], x: &[f64]| -> Vec<f64> {
            m.chunks_exact(n)
                .map(|row| row.iter().zip(x).map(|(a, b)| a * b).sum())
                .collect()
        };
        let (mut m_pin, mut x_pin, mut y_pin) = (vec![0.0; n * n], vec![0.0; n], vec![0.0; n]);
        l.permute_matrix(&m, &mut m_pin);
        l.permute_v(&x, &mut x_pin);
        l.permute_v(&mul(&m, &x), &mut y_pin);
        assert_eq!(mul(&m_pin, &x_pin), y_pin);
        let mut back = vec![0.0; n * n];
        l.permute_matrix(&m_pin, &mut back);
        assert_eq!(back, m);
    }

    #[test]
    fn bad_pinocchio_configurations_are_errors_naming_the_joint_or_index() {
        let model = all_joints();
        let l = PinocchioLayout::new(&model);
        let mut q_pin = vec![0.0; l.nq()];
        l.q_to_pinocchio(&crate::multibody::neutral(&model), &mut q_pin);
        let mut q = vec![0.0; model.nq()];
        let short = l.q_from_pinocchio(&q_pin[1..], &mut q).unwrap_err();
        assert!(matches!(
            short,
            LayoutError::Input(MultibodyError::Dimension(_))
        ));
        let mut nan = q_pin.clone();
        nan[4] = f64::NAN;
        let e = l.q_from_pinocchio(&nan, &mut q).unwrap_err();
        let nonfinite = MultibodyError::NonFinite {
            what: "q",
            index: 4,
        };
        assert_eq!(e, LayoutError::Input(nonfinite));
        let (k, _) = l.joint_q(model.joint_id("a_wheel").unwrap().0);
        q_pin[k] = 2.0;
        let e = l.q_from_pinocchio(&q_pin, &mut q).unwrap_err().to_string();
        assert!(e.contains("a_wheel") && e.contains("norm 2"), "{e}");
    }

    #[test]
    fn nearest_angles_take_the_short_way_round() {
        let model = all_joints();
        let l = PinocchioLayout::new(&model);
        let i = model.joints()[model.joint_id("a_wheel").unwrap().0].idx_q;
        let q0 = crate::multibody::neutral(&model);
        let mut q1 = q0.clone();
        q1[i] = 3.0 * std::f64::consts::PI / 2.0;
        l.nearest_angles(&q0, &mut q1);
        assert!((q1[i] + std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    }

    #[test]
    fn free_flyer_quaternions_keep_the_hemisphere_of_the_start() {
        let model = all_joints();
        let l = PinocchioLayout::new(&model);
        let mut q = crate::multibody::neutral(&model);
        q[3..7].copy_from_slice(&[0.0, 0.0, 0.0, -1.0]); // w < 0: rigid's integrate flips it
        let mut v = vec![0.0; model.nv()];
        v[2] = 0.1;
        let mut out = vec![0.0; model.nq()];
        integrate(&model, &q, &v, 1.0, &mut out).unwrap();
        assert!(out[6] > 0.0);
        l.integrate_signs(&q, &v, 1.0, &mut out);
        assert!(out[6] < 0.0 && (out[5] + (0.05f64).sin()).abs() < 1e-15);
    }
}
