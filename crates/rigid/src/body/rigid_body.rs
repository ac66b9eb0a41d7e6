//! A rigid body as a dynamical system on SE(3): free, or on a pivot, with gravity and an applied
//! wrench.

use super::newton_euler::{gravity_wrench, InverseInertia, InverseRotationalInertia};
use super::BodyError;
use crate::mass::{RotationalInertia, SpatialInertia, DEFAULT_INERTIA_TOLERANCE};
use crate::spatial::{Transform, Twist, Vec3, Wrench};

/// The state of one body: its pose `T_sb` in the world {s} and its body twist `V_b`
/// (`[V_b] = T_sb⁻¹ Ṫ_sb`, angular first).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct State {
    /// `T_sb`: the body frame {b} seen from the world {s}.
    pub pose: Transform,
    /// `V_b = (ω_b, v_b)`: angular velocity and velocity of the origin of {b}, in {b} axes.
    pub twist: Twist,
}

impl State {
    /// `(T_sb, V_b)`.
    #[must_use]
    pub fn new(pose: Transform, twist: Twist) -> Self {
        Self { pose, twist }
    }

    /// Whether every number is finite.
    #[must_use]
    pub fn is_finite(&self) -> bool {
        self.pose.rotation.iter().all(|x| x.is_finite())
            && self.pose.translation.iter().all(|x| x.is_finite())
            && self.twist.w.iter().all(|x| x.is_finite())
            && self.twist.v.iter().all(|x| x.is_finite())
    }
}

/// How the body is held.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Support {
    /// A free body (six degrees of freedom).
    Free,
    /// The origin of the body frame {b} is fixed in the world (a spherical pivot): the body
    /// obeys Euler's equations about that point, `I_O ω̇ + ω × I_O ω = m_O`, and `v_b = 0`.
    Pivot,
}

/// An applied wrench as a function of time and state, returning `F_b` (body frame {b}, moment
/// about the origin of {b}), on top of gravity.
pub trait WrenchFn: Fn(f64, &State) -> Wrench {}
impl<F: Fn(f64, &State) -> Wrench> WrenchFn for F {}

/// The zero applied wrench (the default of [`RigidBody`]).
#[must_use]
pub fn no_wrench(_t: f64, _x: &State) -> Wrench {
    Wrench::zero()
}

/// One rigid body with spatial inertia `G_b` in its frame {b}, held by a [`Support`], under the
/// world gravity `g_s` and an applied wrench `W(t, state)` in {b}.
///
/// Its motion is `Ṫ_sb = T_sb [V_b]` and, for a free body, the forward Newton-Euler equations
/// `V̇_b = G_b⁻¹ (F_b + [ad_{V_b}]ᵀ G_b V_b)` with `F_b = W + (c × m Rᵀ g_s, m Rᵀ g_s)`; on a
/// pivot at the origin of {b}, Euler's equations `ω̇ = I_O⁻¹ (m_O - ω × I_O ω)`, `v̇_b = 0`.
#[derive(Clone, Debug)]
pub struct RigidBody<W = fn(f64, &State) -> Wrench> {
    inertia: SpatialInertia,
    support: Support,
    gravity: Vec3,
    wrench: W,
    /// `G_b⁻¹` (free bodies only).
    inv_g: Option<InverseInertia>,
    /// The reference point `o` of the rotational dynamics in {b}: the CoM of a free body, the
    /// origin of {b} (the pivot) otherwise.
    point: Vec3,
    /// `J`: the rotational inertia about `o`.
    j: RotationalInertia,
    /// `J⁻¹`.
    inv_j: InverseRotationalInertia,
}

impl RigidBody {
    /// A free body with spatial inertia `G_b` in its frame {b} (any body-fixed frame), no gravity
    /// and no applied wrench.
    ///
    /// # Errors
    /// If the body is not physical (mass ≤ 0, non-finite, bad inertia) or its inertia about the
    /// CoM is singular.
    pub fn free(inertia: SpatialInertia) -> Result<Self, BodyError> {
        let inv_g = InverseInertia::new(&inertia)?;
        let j = inertia.inertia_com();
        Ok(Self {
            inertia,
            support: Support::Free,
            gravity: Vec3::zeros(),
            wrench: no_wrench,
            inv_g: Some(inv_g),
            point: inertia.com(),
            j,
            inv_j: InverseRotationalInertia::new(&j, "inertia about the CoM")?,
        })
    }

    /// A body on a spherical pivot at the origin of its frame {b}; `inertia` is `G_b` about the
    /// pivot (mass, CoM `c` relative to the pivot, inertia).
    ///
    /// # Errors
    /// [`BodyError::MasslessPivot`] for a massless body; [`BodyError::Inertia`] if it is not
    /// physical; [`BodyError::SingularInertia`] if the inertia about the pivot is singular.
    pub fn pivot(inertia: SpatialInertia) -> Result<Self, BodyError> {
        let m = inertia.mass();
        if m.is_nan() || m <= 0.0 {
            return Err(BodyError::MasslessPivot { mass: m });
        }
        inertia.validate(DEFAULT_INERTIA_TOLERANCE)?;
        let j = inertia.inertia_origin();
        Ok(Self {
            inertia,
            support: Support::Pivot,
            gravity: Vec3::zeros(),
            wrench: no_wrench,
            inv_g: None,
            point: Vec3::zeros(),
            j,
            inv_j: InverseRotationalInertia::new(&j, "inertia about the pivot")?,
        })
    }
}

impl<W: WrenchFn> RigidBody<W> {
    /// The same body under the world gravity `g_s` (m/s²).
    ///
    /// # Errors
    /// [`BodyError::NonFinite`] if `g_s` is not finite.
    pub fn with_gravity(mut self, gravity: Vec3) -> Result<Self, BodyError> {
        if !gravity.iter().all(|x| x.is_finite()) {
            return Err(BodyError::NonFinite { what: "gravity" });
        }
        self.gravity = gravity;
        Ok(self)
    }

    /// The same body with the applied wrench `W(t, state)` (in {b}, about the origin of {b}).
    #[must_use]
    pub fn with_wrench<W2: WrenchFn>(self, wrench: W2) -> RigidBody<W2> {
        RigidBody {
            inertia: self.inertia,
            support: self.support,
            gravity: self.gravity,
            wrench,
            inv_g: self.inv_g,
            point: self.point,
            j: self.j,
            inv_j: self.inv_j,
        }
    }

    /// `G_b`.
    #[must_use]
    pub fn inertia(&self) -> &SpatialInertia {
        &self.inertia
    }

    /// The support.
    #[must_use]
    pub fn support(&self) -> Support {
        self.support
    }

    /// The world gravity `g_s`.
    #[must_use]
    pub fn gravity(&self) -> Vec3 {
        self.gravity
    }

    /// The reference point of the rotational dynamics in {b} (CoM if free, pivot otherwise) and
    /// the inertia `J` about it, with `J⁻¹`.
    pub(crate) fn rotational(&self) -> (Vec3, &RotationalInertia, &InverseRotationalInertia) {
        (self.point, &self.j, &self.inv_j)
    }

    /// The applied wrench `W(t, state)` alone (in {b}, about the origin of {b}), without gravity.
    #[must_use]
    #[inline]
    pub(crate) fn applied_wrench(&self, t: f64, x: &State) -> Wrench {
        (self.wrench)(t, x)
    }

    /// The total wrench `F_b` on the body in {b}: applied plus gravity (without the reaction of
    /// a pivot).
    #[must_use]
    #[inline]
    pub fn wrench(&self, t: f64, x: &State) -> Wrench {
        self.applied_wrench(t, x) + gravity_wrench(&self.inertia, &x.pose, &self.gravity)
    }

    /// The body acceleration `V̇_b`: forward Newton-Euler for a free body, Euler's equations
    /// about the pivot (and `v̇_b = 0`) on a pivot.
    #[must_use]
    #[inline]
    pub fn acceleration(&self, t: f64, x: &State) -> Twist {
        let f = self.wrench(t, x);
        match &self.inv_g {
            Some(inv_g) => inv_g.forward_dynamics(&x.twist, &f),
            None => {
                let w = &x.twist.w;
                let wdot = self.inv_j.solve(&(f.m - w.cross(&self.j.mul_vec(w))));
                Twist::new(wdot, Vec3::zeros())
            }
        }
    }

    /// Kinetic energy `K = ½ V_bᵀ G_b V_b` (J).
    #[must_use]
    pub fn kinetic_energy(&self, x: &State) -> f64 {
        self.inertia.kinetic_energy(&x.twist)
    }

    /// Potential energy of gravity `U = -m g_sᵀ c_s`, with `c_s = T_sb c_b` the CoM in the world
    /// (zero at the world origin).
    #[must_use]
    pub fn potential_energy(&self, x: &State) -> f64 {
        -self.inertia.mass() * self.gravity.dot(&x.pose.act_point(&self.inertia.com()))
    }

    /// Total mechanical energy `K + U` (J); conserved without applied wrench.
    #[must_use]
    pub fn energy(&self, x: &State) -> f64 {
        self.kinetic_energy(x) + self.potential_energy(x)
    }

    /// The spatial momentum in the world frame, about the world origin:
    /// `P_s = [Ad_{T_bs}]ᵀ G_b V_b`.
    #[must_use]
    pub fn spatial_momentum(&self, x: &State) -> Wrench {
        x.pose.act_wrench(&self.inertia.momentum(&x.twist))
    }

    /// The angular momentum in world axes about the reference point: the CoM of a free body
    /// (`R I_c ω`, conserved under uniform gravity), the pivot of a pivoted body (`R I_O ω`;
    /// with gravity only its component along `g_s` is conserved).
    #[must_use]
    pub fn angular_momentum(&self, x: &State) -> Vec3 {
        x.pose.rotation * self.j.mul_vec(&x.twist.w)
    }
}
