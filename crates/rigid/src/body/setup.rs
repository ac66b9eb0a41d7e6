//! A body made of parts (a `rigid mass` spec) set up for simulation, as `rigid simulate
//! SPEC.toml` and Python's `rigid.simulate_body` do it.

use super::rigid_body::{RigidBody, State};
use super::BodyError;
use crate::mass::{MassProperties, SpatialInertia};
use crate::spatial::{Transform, Twist, Vec3};

/// A body ready to simulate from its mass properties in the spec frame: the body in a frame {b}
/// with the axes of the spec frame, at the CoM for a free body and at the pivot for a body on a
/// pivot; its initial state, with {b} at the world origin and the spec frame's axes along the
/// world's; and the CoM in {b}, to report the motion of the CoM frame ([`com_frame`]).
///
/// [`com_frame`]: Self::com_frame
///
/// ```
/// use rigid::body::{Integrator, Setup, Simulator};
/// use rigid::mass::{MassProperties, RotationalInertia, SpatialInertia};
/// use rigid::spatial::Vec3;
/// // a 1 kg ball whose centre is 0.5 m above the spec frame's origin, on a pivot at that origin
/// let g = SpatialInertia::from_com(1.0, Vec3::new(0.0, 0.0, 0.5), RotationalInertia::diagonal(0.004, 0.004, 0.004));
/// let props = MassProperties::from_spatial_inertia(&g);
/// let s = Setup::new(&props, Some(Vec3::zeros()), Vec3::x(), Vec3::zeros(), Vec3::new(0.0, 0.0, -9.81))?;
/// let (pose, twist) = s.com_frame(&s.x0);
/// assert_eq!((pose.translation, twist.v), (Vec3::new(0.0, 0.0, 0.5), Vec3::new(0.0, -0.5, 0.0)));
/// let mut sim = Simulator::new(s.body.clone(), s.x0, Integrator::default(), 1e-3)?;
/// sim.run(100, |_, _| {})?;
/// assert!((s.com_frame(sim.state()).0.translation.norm() - 0.5).abs() < 1e-12); // on its sphere
/// # Ok::<(), rigid::body::BodyError>(())
/// ```
#[derive(Clone, Debug)]
pub struct Setup {
    /// The body in {b}, under gravity.
    pub body: RigidBody,
    /// The initial state: {b} at the world origin, axes along the world's, twist
    /// `(ω, v_CoM)` (free) or `(ω, 0)` (pivot).
    pub x0: State,
    /// `r`: the CoM in {b} (zero for a free body, CoM minus pivot on a pivot).
    pub com: Vec3,
}

impl Setup {
    /// The body of mass properties `props` (in the spec frame): free (`pivot` is `None`), or on
    /// a spherical pivot at the point `pivot` of the spec frame; under the world gravity
    /// `gravity`; starting with angular velocity `omega` (spec axes) and, for a free body, the
    /// CoM velocity `velocity` (spec axes).
    ///
    /// # Errors
    /// [`BodyError::PivotMoves`] for a velocity on a pivot; a body that is not physical, a
    /// massless body on a pivot, a singular inertia about the CoM or the pivot, non-finite
    /// gravity (as [`RigidBody::free`], [`RigidBody::pivot`], [`RigidBody::with_gravity`]).
    pub fn new(
        props: &MassProperties,
        pivot: Option<Vec3>,
        omega: Vec3,
        velocity: Vec3,
        gravity: Vec3,
    ) -> Result<Self, BodyError> {
        let (body, com) = match pivot {
            None => {
                let g = SpatialInertia::from_com(props.mass, Vec3::zeros(), props.inertia_com);
                (RigidBody::free(g)?, Vec3::zeros())
            }
            Some(o) => {
                if velocity != Vec3::zeros() {
                    return Err(BodyError::PivotMoves {
                        speed: velocity.norm(),
                    });
                }
                let r = props.com - o;
                let g = SpatialInertia::from_com(props.mass, r, props.inertia_com);
                (RigidBody::pivot(g)?, r)
            }
        };
        Ok(Self {
            body: body.with_gravity(gravity)?,
            x0: State::new(Transform::identity(), Twist::new(omega, velocity)),
            com,
        })
    }

    /// The frame at the CoM with the axes of the spec frame, in the state `x`: its pose in the
    /// world `T_sc = T_sb (1, r)` and its body twist `V_c = [Ad_{T_cb}] V_b`.
    #[must_use]
    pub fn com_frame(&self, x: &State) -> (Transform, Twist) {
        let t_bc = Transform::from_translation(self.com);
        (x.pose * t_bc, t_bc.inv_act_twist(&x.twist))
    }
}
