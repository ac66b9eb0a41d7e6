//! The ten inertial parameters of a rigid body as a vector, the form in which the dynamics are
//! linear (`τ = Y(q, v, a) π`, Atkeson, An & Hollerbach 1986; Khalil & Dombre 2002, §12.3).

use super::{RotationalInertia, SpatialInertia};
use crate::spatial::{Mat3, Vec3};

/// The names of the ten parameters, in the order of [`SpatialInertia::to_parameters`]:
/// `m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz` (short: `m`, `mx`, `my`, `mz`, ...).
pub const PARAMETER_NAMES: [&str; 10] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

impl SpatialInertia {
    /// The ten inertial parameters `π = (m, m cx, m cy, m cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz)`:
    /// the mass, the first moment `h = m c` and the rotational inertia `Ī` about **this frame's
    /// origin** (not the CoM), in this frame's axes, with the products as the matrix entries
    /// (`Ixy = -∫ x y dm`). This is Pinocchio's `Inertia::toDynamicParameters` order; the
    /// dynamics are linear in it.
    ///
    /// ```
    /// use rigid::mass::{RotationalInertia, SpatialInertia};
    /// use rigid::spatial::Vec3;
    /// // 2 kg at (0, 0, 1), inertia diag(1, 2, 3) about the CoM
    /// let g = SpatialInertia::from_com(2.0, Vec3::z(), RotationalInertia::diagonal(1.0, 2.0, 3.0));
    /// let p = g.to_parameters();
    /// assert_eq!(p, [2.0, 0.0, 0.0, 2.0, 3.0, 0.0, 4.0, 0.0, 0.0, 3.0]); // Steiner: +m d² on x, y
    /// assert_eq!(SpatialInertia::from_parameters(&p), g);
    /// ```
    #[must_use]
    pub fn to_parameters(&self) -> [f64; 10] {
        let h = self.first_moment();
        let i = self.inertia_origin_matrix();
        [
            self.mass(),
            h.x,
            h.y,
            h.z,
            i[(0, 0)],
            i[(0, 1)],
            i[(1, 1)],
            i[(0, 2)],
            i[(1, 2)],
            i[(2, 2)],
        ]
    }

    /// The body of the parameters `π` ([`to_parameters`](Self::to_parameters)), whatever
    /// they are (no check: identified parameters may be non-physical; [`crate::mass::Consistency`]
    /// tells).
    #[must_use]
    pub fn from_parameters(p: &[f64; 10]) -> Self {
        let i = Mat3::new(p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9]);
        Self::from_parts(
            p[0],
            Vec3::new(p[1], p[2], p[3]),
            RotationalInertia::from_matrix_unchecked(&i),
        )
    }
}
