//! Wheels under velocity control in the simulator: the wheel joints of a robot model driven to
//! commanded speeds, the rest of the body under another control law.

use super::MobileError;
use crate::multibody::{JointType, Model, MultibodyError};
use crate::simulation::Control;

/// `τ_k = K (u_k − v_k)` on each wheel joint `k` (its speed `v_k`, the command `u_k`), the other
/// joints' torques from `inner`. `K` is reported with the inner law's gains as a damping
/// ([`Control::pd_gains`]), so that the contact time stepper takes it implicitly: a light wheel
/// under a stiff gain stays stable at a 1 ms step.
///
/// ```
/// use rigid::mobile::WheelDrive;
/// use rigid::simulation::{Control, Controller};
/// let model = rigid::io::urdf::load_urdf(
///     concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/diff_drive.urdf"), true)?;
/// let none = Controller::none(&model);
/// let mut drive = WheelDrive::new(&model, none, &["left_wheel_joint", "right_wheel_joint"], 2.0)?;
/// drive.set_speeds(&[5.0, 5.0])?;
/// let mut tau = vec![0.0; model.nv()];
/// drive.torque(&model, 0.0, &rigid::multibody::neutral(&model), &vec![0.0; model.nv()], &mut tau)?;
/// assert_eq!(tau.iter().filter(|t| **t == 10.0).count(), 2); // K u on each wheel at rest
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct WheelDrive<C> {
    /// The law of the other joints.
    pub inner: C,
    wheels: Vec<usize>,
    speeds: Vec<f64>,
    gain: f64,
    kp: Vec<f64>,
    kd: Vec<f64>,
}

impl<C: Control> WheelDrive<C> {
    /// The wheels named `wheels` (revolute or continuous joints of `model`) under gain `gain`
    /// (N·m·s/rad), commanded to rest until [`set_speeds`](Self::set_speeds).
    ///
    /// # Errors
    /// [`MobileError::WheelJoint`] for a name that is not a one-dof revolute joint of `model`;
    /// [`MobileError::NotPositive`] for the gain.
    pub fn new(model: &Model, inner: C, wheels: &[&str], gain: f64) -> Result<Self, MobileError> {
        if !(gain.is_finite() && gain > 0.0) {
            return Err(MobileError::NotPositive {
                what: "wheel gain",
                value: gain,
            });
        }
        let mut idx = Vec::with_capacity(wheels.len());
        for name in wheels {
            let refuse = |reason: &str| MobileError::WheelJoint {
                name: (*name).to_string(),
                reason: reason.to_string(),
            };
            let j = model
                .joint_id(name)
                .ok_or_else(|| refuse("no joint of that name"))?;
            let joint = &model.joints()[j.0];
            if !matches!(joint.kind, JointType::Revolute { .. }) {
                return Err(refuse("not a revolute joint"));
            }
            idx.push(joint.idx_v);
        }
        let nv = model.nv();
        let (mut kp, mut kd) = match inner.pd_gains() {
            Some((kp, kd)) => (kp.to_vec(), kd.to_vec()),
            None => (vec![0.0; nv], vec![0.0; nv]),
        };
        for &k in &idx {
            kp[k] = 0.0;
            kd[k] = gain;
        }
        Ok(Self {
            inner,
            speeds: vec![0.0; idx.len()],
            wheels: idx,
            gain,
            kp,
            kd,
        })
    }

    /// The commanded wheel speeds `u` (rad/s), in the order of the names given.
    ///
    /// # Errors
    /// A wrong length, a non-finite speed.
    pub fn set_speeds(&mut self, u: &[f64]) -> Result<(), MobileError> {
        crate::error::DimensionError::check("wheel speeds", self.wheels.len(), u.len())?;
        super::manipulator::finite("wheel speeds", u)?;
        self.speeds.copy_from_slice(u);
        Ok(())
    }

    /// The velocity index of each wheel (in the model's `v`).
    #[must_use]
    pub fn wheels(&self) -> &[usize] {
        &self.wheels
    }
}

impl<C: Control> Control for WheelDrive<C> {
    fn torque(
        &mut self,
        model: &Model,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &mut [f64],
    ) -> Result<(), MultibodyError> {
        self.inner.torque(model, t, q, v, tau)?;
        for (&k, &u) in self.wheels.iter().zip(&self.speeds) {
            tau[k] = self.gain * (u - v[k]);
        }
        Ok(())
    }

    fn pd_gains(&self) -> Option<(&[f64], &[f64])> {
        Some((&self.kp, &self.kd))
    }
}

/// A wheeled robot's run on the ground ([`wheel_simulator`]): which joints are wheels, their
/// commanded speeds, the gain, the step.
#[cfg(feature = "collision")]
#[derive(Clone, Debug, PartialEq)]
pub struct DriveOptions {
    /// The wheel joints' names.
    pub wheels: Vec<String>,
    /// Their commanded speeds (rad/s).
    pub speeds: Vec<f64>,
    /// `K` of `τ = K (u_d − u)` (N·m·s/rad).
    pub gain: f64,
    /// The friction of the wheels' own collision shapes (`None`: the model's); with the ground's
    /// friction 0 this makes everything but the wheels slide freely (a geometry's friction with
    /// the ground is the larger of the two), as swivel casters that a URDF fixes.
    pub wheel_friction: Option<f64>,
    /// Hold the other joints at the start with the stance controller
    /// ([`ControlLaw::standing`](crate::simulation::ControlLaw::standing)); else they are
    /// passive.
    pub hold: bool,
    /// The time step (s).
    pub dt: f64,
}

/// The simulator of a robot with a free-flyer root on the ground of `collision`, set down at its
/// neutral configuration, its wheels under [`WheelDrive`] at `options.speeds`, the rest passive
/// or held: the run of `rigid mobile drive` and Python's `rigid.mobile.drive`.
///
/// # Errors
/// A root that is not a free flyer, no ground, a bad wheel name, friction or speeds; the
/// simulator's refusal ([`MobileError::Simulation`]).
#[cfg(feature = "collision")]
pub fn wheel_simulator(
    model: &Model,
    mut collision: crate::collision::CollisionModel,
    options: &DriveOptions,
) -> Result<crate::simulation::Simulator<WheelDrive<crate::simulation::Controller>>, MobileError> {
    use crate::simulation::{ControlLaw, Controller, Integrator, SimulationOptions, Simulator};
    let sim_error = |e: &dyn std::fmt::Display| MobileError::Simulation(e.to_string());
    if model.joints().first().map(|j| j.kind) != Some(JointType::FreeFlyer) {
        return Err(MobileError::Simulation(
            "the robot's root must be a free flyer (load it floating)".into(),
        ));
    }
    if collision.ground.is_none() {
        return Err(MobileError::Simulation("the world has no ground".into()));
    }
    if let Some(mu) = options.wheel_friction {
        if !(mu.is_finite() && mu >= 0.0) {
            return Err(MobileError::NotPositive {
                what: "wheel friction",
                value: mu,
            });
        }
        let ids: Vec<_> = options
            .wheels
            .iter()
            .filter_map(|n| model.joint_id(n))
            .collect();
        for g in &mut collision.geometries {
            if g.body.is_some_and(|b| ids.contains(&b)) {
                g.friction = Some(mu);
            }
        }
    }
    let mut q0 = crate::multibody::neutral(model);
    crate::collision::place_on_ground(model, &collision, &mut q0).map_err(|e| sim_error(&e))?;
    let inner = if options.hold {
        let law = ControlLaw::standing(model, &q0, &collision).map_err(|e| sim_error(&e))?;
        Controller::new(model, law).map_err(|e| sim_error(&e))?
    } else {
        Controller::none(model)
    };
    let names: Vec<&str> = options.wheels.iter().map(String::as_str).collect();
    let mut control = WheelDrive::new(model, inner, &names, options.gain)?;
    control.set_speeds(&options.speeds)?;
    let opts = SimulationOptions {
        dt: options.dt,
        integrator: Integrator::SemiImplicitEuler,
        ..SimulationOptions::default()
    };
    let v0 = vec![0.0; model.nv()];
    Simulator::new(model, &q0, &v0, opts, control)
        .and_then(|s| s.with_collision(collision))
        .map_err(|e| sim_error(&e))
}

/// The planar motion of a robot whose root is a free flyer: `[x, y, yaw, v, ω]`, the root's
/// position on the floor, its heading, its speed along the heading and its yaw rate (world
/// frame), from `q` and the body twist `v = (ω_b, v_b)` (their first 7 and 6 entries).
///
/// # Errors
/// [`MobileError::Dimension`] when `q` or `v` is too short for a free flyer.
pub fn chassis_motion(q: &[f64], v: &[f64]) -> Result<[f64; 5], MobileError> {
    if q.len() < 7 || v.len() < 6 {
        return Err(MobileError::Dimension(crate::error::DimensionError {
            what: "free-flyer q and v (7 and 6 numbers at least)",
            expected: 7,
            got: q.len().min(v.len() + 1),
        }));
    }
    let r = crate::spatial::quat_to_rot(q[3], q[4], q[5], q[6]);
    let yaw = r[(1, 0)].atan2(r[(0, 0)]);
    let v_world = r * crate::spatial::Vec3::new(v[3], v[4], v[5]);
    let w_world = r * crate::spatial::Vec3::new(v[0], v[1], v[2]);
    let forward = v_world.x * yaw.cos() + v_world.y * yaw.sin();
    Ok([q[0], q[1], yaw, forward, w_world.z])
}

/// What [`drive`] recorded, one row at `t = 0` and one after each step.
#[cfg(feature = "collision")]
#[derive(Clone, Debug, PartialEq)]
pub struct DriveRecord {
    /// The time step (s).
    pub dt: f64,
    /// `[x, y, yaw, v, ω]` of the root ([`chassis_motion`]).
    pub motion: Vec<[f64; 5]>,
    /// The wheel joints' speeds (rad/s), in the order of [`DriveOptions::wheels`].
    pub wheel_speeds: Vec<Vec<f64>>,
    /// The configurations.
    pub q: Vec<Vec<f64>>,
}

#[cfg(feature = "collision")]
impl DriveRecord {
    /// How far the simulated motion is from the kinematic model of `base` (its wheels in the
    /// order of the record's): the largest relative differences of the forward speed `v` and the
    /// yaw rate `ω` from `F u` of the simulated wheel speeds `u`, from `after` seconds on. `v` is
    /// relative to `max(|v_model|, rim speed)`, `ω` to `max(|ω_model|, rim speed / reach)` (the
    /// wheels' largest distance from the chassis origin), so that a turn in place or a straight
    /// line is measured against the motion's own speed.
    ///
    /// # Errors
    /// [`MobileError::Dimension`] when `base` has another number of wheels.
    pub fn agreement(&self, base: &super::Base, after: f64) -> Result<(f64, f64), MobileError> {
        let reach = base
            .wheels()
            .iter()
            .map(|w| w.position[0].hypot(w.position[1]))
            .fold(0.0, f64::max);
        let (mut worst_v, mut worst_w) = (0.0f64, 0.0f64);
        for (k, (m, u)) in self.motion.iter().zip(&self.wheel_speeds).enumerate() {
            if (k as f64) * self.dt < after {
                continue;
            }
            let [wm, vm, _] = base.body_twist(u)?;
            let rim = base
                .wheels()
                .iter()
                .zip(u)
                .map(|(w, x)| w.radius * x.abs())
                .sum::<f64>()
                / u.len() as f64;
            worst_v = worst_v.max((m[3] - vm).abs() / vm.abs().max(rim).max(1e-12));
            worst_w = worst_w.max((m[4] - wm).abs() / wm.abs().max(rim / reach).max(1e-12));
        }
        Ok((worst_v, worst_w))
    }
}

/// Runs [`wheel_simulator`] for `time` seconds, calling `observe(t, simulator)` at `t = 0` and
/// after each step (a replay, a plot), and records the motion, the wheel speeds and `q`.
///
/// # Errors
/// As [`wheel_simulator`]; a time that is not positive; a step that fails; more than 10⁸ numbers
/// to record ([`MobileError::Simulation`]); `observe`'s error.
#[cfg(feature = "collision")]
pub fn drive(
    model: &Model,
    collision: crate::collision::CollisionModel,
    options: &DriveOptions,
    time: f64,
    mut observe: impl FnMut(
        f64,
        &crate::simulation::Simulator<WheelDrive<crate::simulation::Controller>>,
    ) -> Result<(), String>,
) -> Result<DriveRecord, MobileError> {
    if !(time.is_finite() && time > 0.0) {
        return Err(MobileError::NotPositive {
            what: "time",
            value: time,
        });
    }
    let mut sim = wheel_simulator(model, collision, options)?;
    let steps = (time / options.dt).round() as usize;
    if (steps + 1).saturating_mul(model.nq() + 5 + options.wheels.len()) > 100_000_000 {
        return Err(MobileError::Simulation(format!(
            "{steps} steps of {} s: more than 10^8 numbers to record; a larger dt or a shorter time",
            options.dt
        )));
    }
    let wheels = sim.control().wheels().to_vec();
    let mut record = DriveRecord {
        dt: options.dt,
        motion: Vec::with_capacity(steps + 1),
        wheel_speeds: Vec::with_capacity(steps + 1),
        q: Vec::with_capacity(steps + 1),
    };
    for k in 0..=steps {
        let t = k as f64 * options.dt;
        if k > 0 {
            sim.step()
                .map_err(|e| MobileError::Simulation(format!("t = {t:.3} s: {e}")))?;
        }
        let (q, v) = (sim.q(), sim.v());
        record.motion.push(chassis_motion(q, v)?);
        record
            .wheel_speeds
            .push(wheels.iter().map(|&i| v[i]).collect());
        record.q.push(q.to_vec());
        observe(t, &sim).map_err(MobileError::Simulation)?;
    }
    Ok(record)
}
