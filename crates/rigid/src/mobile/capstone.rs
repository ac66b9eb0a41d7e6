//! The capstone of *Modern Robotics* (Lynch & Park, the Coursera course's final project): a
//! youBot picks a cube and places it elsewhere, its end effector driven along a reference by
//! [`Feedback`], its state advanced by a first-order Euler step. Three pieces, as the course
//! builds them: [`MobileManipulator::next_state`] (milestone 1), [`PickAndPlace::reference`]
//! (milestone 2), [`Feedback::command`] (milestone 3); [`Capstone::run`] ties them together.

use super::{Feedback, MobileError, MobileManipulator};
use crate::simulation::{PosePath, PoseTrajectory, TimeScaling};
use crate::spatial::{so3, Mat6, Transform, Twist, Vec3};

/// A mobile manipulator's configuration: chassis `(φ, x, y)`, arm joints `θ`, wheel angles.
#[derive(Clone, Debug, PartialEq)]
pub struct MobileState {
    /// `(φ, x, y)` (rad, m, m).
    pub chassis: [f64; 3],
    /// The arm's joint angles (rad).
    pub arm: Vec<f64>,
    /// The wheel angles (rad).
    pub wheels: Vec<f64>,
}

impl MobileManipulator {
    /// One Euler step of `dt` (the capstone's `NextState`): the speeds `(u, θ̇)` (wheels first, as
    /// the columns of [`MobileManipulator::jacobian`]) clipped to `±max_speed`, then
    /// `θ ← θ + θ̇ dt`, wheels `← + u dt`, and the chassis by odometry on `Δθ = u dt`.
    ///
    /// # Errors
    /// Wrong lengths, non-finite input, `dt` not positive and finite, `max_speed` not positive
    /// (it may be infinite).
    pub fn next_state(
        &self,
        state: &MobileState,
        speeds: &[f64],
        dt: f64,
        max_speed: f64,
    ) -> Result<MobileState, MobileError> {
        let (m, n) = (self.n_wheels(), self.n_arm());
        for (what, got, expected) in [
            ("speeds", speeds.len(), m + n),
            ("arm", state.arm.len(), n),
            ("wheels", state.wheels.len(), m),
        ] {
            crate::error::DimensionError::check(what, expected, got)?;
        }
        if !(dt.is_finite() && dt > 0.0) {
            return Err(MobileError::NotPositive {
                what: "dt",
                value: dt,
            });
        }
        if max_speed.is_nan() || max_speed <= 0.0 {
            return Err(MobileError::NotPositive {
                what: "max_speed",
                value: max_speed,
            });
        }
        super::manipulator::finite("speeds", speeds)?;
        super::manipulator::finite("chassis", &state.chassis)?;
        super::manipulator::finite("arm", &state.arm)?;
        super::manipulator::finite("wheels", &state.wheels)?;
        let clip: Vec<f64> = speeds
            .iter()
            .map(|s| s.clamp(-max_speed, max_speed) * dt)
            .collect();
        Ok(MobileState {
            chassis: self.base.odometry(state.chassis, &clip[..m])?,
            arm: state
                .arm
                .iter()
                .zip(&clip[m..])
                .map(|(a, d)| a + d)
                .collect(),
            wheels: state
                .wheels
                .iter()
                .zip(&clip[..m])
                .map(|(a, d)| a + d)
                .collect(),
        })
    }
}

/// One point of a reference: the end-effector pose and whether the gripper is closed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReferencePoint {
    /// `X_d = T_se,d`.
    pub X: Transform,
    /// Gripper closed.
    pub closed: bool,
}

impl ReferencePoint {
    /// The course's reference row (milestone 2, 13 columns): `r11, r12, r13, r21, …, r33, px, py,
    /// pz, gripper` (0 open, 1 closed).
    #[must_use]
    pub fn row(&self) -> [f64; 13] {
        let (r, p) = (self.X.rotation, self.X.translation);
        let mut out = [0.0; 13];
        for i in 0..3 {
            for j in 0..3 {
                out[3 * i + j] = r[(i, j)];
            }
            out[9 + i] = p[i];
        }
        out[12] = if self.closed { 1.0 } else { 0.0 };
        out
    }
}

/// A pick-and-place task: the cube's initial and final poses, the gripper's pose relative to the
/// cube when grasping and at standoff above it, and how fast the reference moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PickAndPlace {
    /// `T_sc,initial`.
    pub cube_initial: Transform,
    /// `T_sc,final`.
    pub cube_final: Transform,
    /// `T_ce,grasp`.
    pub grasp: Transform,
    /// `T_ce,standoff`.
    pub standoff: Transform,
    /// Speed of the reference's origin on a segment (m/s); sets the segment's duration with
    /// `angular_speed`, each at least `gripper_time`.
    pub linear_speed: f64,
    /// Rotation speed of the reference on a segment (rad/s).
    pub angular_speed: f64,
    /// Time for the gripper to open or close, the reference at rest (s; the course's gripper needs
    /// 0.625 s).
    pub gripper_time: f64,
}

impl PickAndPlace {
    /// The course's default task: the cube (5 cm) from `(1, 0)` to `(0, -1)` turned by -90°,
    /// grasped from above with the gripper tilted 45° (`T_ce,grasp = (Rot(y, 3π/4), 0)`), the
    /// standoff 10 cm above.
    #[must_use]
    pub fn course() -> Self {
        let tilt = so3::from_rpy(0.0, 3.0 * std::f64::consts::FRAC_PI_4, 0.0);
        Self {
            cube_initial: Transform::from_translation(Vec3::new(1.0, 0.0, 0.025)),
            cube_final: Transform::new(
                so3::from_rpy(0.0, 0.0, -std::f64::consts::FRAC_PI_2),
                Vec3::new(0.0, -1.0, 0.025),
            ),
            grasp: Transform::from_rotation(tilt),
            standoff: Transform::new(tilt, Vec3::new(0.0, 0.0, 0.1)),
            linear_speed: 0.25,
            angular_speed: 0.5,
            gripper_time: 1.0,
        }
    }

    /// The reference of the eight segments (the capstone's `TrajectoryGenerator`): from `start`
    /// to the standoff above the cube, down to the grasp, close, up, to the standoff above the
    /// goal, down, open, up; each a screw path (Lynch & Park §9.1.3) with a quintic time scaling,
    /// sampled every `dt` (the first point is `start`, open).
    ///
    /// # Errors
    /// `dt` or a speed not positive; a non-finite pose.
    pub fn reference(
        &self,
        start: &Transform,
        dt: f64,
    ) -> Result<Vec<ReferencePoint>, MobileError> {
        for (what, x) in [
            ("dt", dt),
            ("linear_speed", self.linear_speed),
            ("angular_speed", self.angular_speed),
            ("gripper_time", self.gripper_time),
        ] {
            if !(x.is_finite() && x > 0.0) {
                return Err(MobileError::NotPositive { what, value: x });
            }
        }
        for (what, t) in [
            ("start", start),
            ("cube_initial", &self.cube_initial),
            ("cube_final", &self.cube_final),
            ("grasp", &self.grasp),
            ("standoff", &self.standoff),
        ] {
            super::manipulator::finite(what, t.rotation.as_slice())?;
            super::manipulator::finite(what, t.translation.as_slice())?;
        }
        let (c0, c1) = (self.cube_initial, self.cube_final);
        let waypoints = [
            (c0 * self.standoff, false),
            (c0 * self.grasp, false),
            (c0 * self.grasp, true),
            (c0 * self.standoff, true),
            (c1 * self.standoff, true),
            (c1 * self.grasp, true),
            (c1 * self.grasp, false),
            (c1 * self.standoff, false),
        ];
        let mut out = vec![ReferencePoint {
            X: *start,
            closed: false,
        }];
        let mut from = *start;
        for (to, closed) in waypoints {
            let d = (from.inverse() * to).log();
            let travel = (to.translation - from.translation).norm() / self.linear_speed;
            let turn = d.w.norm() / self.angular_speed;
            let duration = travel.max(turn).max(self.gripper_time);
            let steps = (duration / dt).ceil() as usize;
            let traj = PoseTrajectory::new(
                from,
                to,
                steps as f64 * dt,
                TimeScaling::Quintic,
                PosePath::Screw,
            )
            .map_err(|e| MobileError::Simulation(e.to_string()))?;
            out.extend((1..=steps).map(|k| ReferencePoint {
                X: traj.sample(k as f64 * dt),
                closed,
            }));
            from = to;
        }
        Ok(out)
    }
}

/// A whole capstone run: the robot, its task, where the reference starts, where the robot
/// actually starts, the feedback, the control period and the speed limit.
#[derive(Clone, Debug, PartialEq)]
pub struct Capstone {
    /// The youBot, or another mobile manipulator.
    pub robot: MobileManipulator,
    /// The cube, the grasp, the speeds.
    pub task: PickAndPlace,
    /// Where the reference starts, `T_se` at `t = 0`.
    pub reference_start: Transform,
    /// The robot's configuration at `t = 0` (off the reference: the feedback must correct it).
    pub start: MobileState,
    /// Gains, joint limits, the pseudo-inverse's tolerance.
    pub feedback: Feedback,
    /// Control period and reference step (s).
    pub dt: f64,
    /// Speed limit of every wheel and joint (rad/s).
    pub max_speed: f64,
}

/// What [`Capstone::run`] produced, one row per control step.
#[derive(Clone, Debug, PartialEq)]
pub struct CapstoneRun {
    /// The control period (s).
    pub dt: f64,
    /// The reference followed.
    pub reference: Vec<ReferencePoint>,
    /// The configuration at each step, with the gripper state (closed) of the reference point it
    /// was driven to.
    pub states: Vec<(MobileState, bool)>,
    /// `X_err` at each control step (one fewer than `states`).
    pub errors: Vec<Twist>,
}

impl CapstoneRun {
    /// Row `k` in the course's scene format (13 columns): `φ, x, y, θ_1..θ_5, w_1..w_4, gripper`
    /// (for other robots: chassis, arm, wheels, gripper 0 or 1).
    #[must_use]
    pub fn row(&self, k: usize) -> Vec<f64> {
        let (s, closed) = &self.states[k];
        let mut r = s.chassis.to_vec();
        r.extend_from_slice(&s.arm);
        r.extend_from_slice(&s.wheels);
        r.push(if *closed { 1.0 } else { 0.0 });
        r
    }
}

impl Capstone {
    /// Where the cube is at each state of `run`: at its initial pose until the gripper first
    /// closes, then carried by the gripper while it is closed (`T_sc = X T_ce,grasp⁻¹`), then at
    /// its final pose.
    ///
    /// # Errors
    /// A state the robot's forward kinematics refuses.
    pub fn cube_poses(&self, run: &CapstoneRun) -> Result<Vec<Transform>, MobileError> {
        let mut pose = self.task.cube_initial;
        let mut carried = false;
        run.states
            .iter()
            .map(|(s, closed)| {
                if *closed {
                    pose = self.robot.forward(s.chassis, &s.arm)? * self.task.grasp.inverse();
                    carried = true;
                } else if carried {
                    pose = self.task.cube_final;
                }
                Ok(pose)
            })
            .collect()
    }

    /// The youBot on the course's task: the reference starts at `(R, (0, 0, 0.5))` with the
    /// gripper pointing forward-down (`R = Rot(y, π/2)`), the robot at chassis
    /// `(0.5, -0.2, 0.2)`, arm `(0, 0, 0.2, -1.6, 0)` (0.42 m and 30° off), feedforward plus
    /// `K_p = 1.5 I` (`K_i = 0`: an integral term adds a slow closed-loop pole, `s² + K_p s + K_i`),
    /// 10 ms, 15 rad/s.
    #[must_use]
    pub fn youbot() -> Self {
        let robot = MobileManipulator::youbot();
        let feedback = Feedback::new(Mat6::identity() * 1.5, Mat6::zeros()).expect("finite gains");
        Self {
            start: MobileState {
                chassis: [0.5, -0.2, 0.2],
                arm: vec![0.0, 0.0, 0.2, -1.6, 0.0],
                wheels: vec![0.0; 4],
            },
            robot,
            task: PickAndPlace::course(),
            reference_start: Transform::new(
                so3::from_rpy(0.0, std::f64::consts::FRAC_PI_2, 0.0),
                Vec3::new(0.0, 0.0, 0.5),
            ),
            feedback,
            dt: 0.01,
            max_speed: 15.0,
        }
    }

    /// [`Capstone::youbot`] with joints 3 and 4 kept below −0.2 rad (away from the stretched
    /// arm's singularity, as the capstone suggests), the arm starting at `(0, 0, −0.3, −1.6, 0)`
    /// inside that range.
    #[must_use]
    pub fn youbot_with_limits() -> Self {
        let mut c = Self::youbot();
        let free = (-3.2, 3.2);
        c.feedback.limits = vec![free, free, (-3.2, -0.2), (-3.2, -0.2), free];
        c.start.arm = vec![0.0, 0.0, -0.3, -1.6, 0.0];
        c
    }

    /// Runs the task: at each step `X = forward(state)`, the feedback's speeds toward the
    /// reference's next point, [`MobileManipulator::next_state`].
    ///
    /// # Errors
    /// What [`PickAndPlace::reference`], [`Feedback::command`] or
    /// [`MobileManipulator::next_state`] refuse.
    pub fn run(&self) -> Result<CapstoneRun, MobileError> {
        let reference = self.task.reference(&self.reference_start, self.dt)?;
        let mut feedback = self.feedback.clone();
        let mut state = self.start.clone();
        let mut states = vec![(state.clone(), reference[0].closed)];
        let mut errors = Vec::with_capacity(reference.len());
        for w in reference.windows(2) {
            let X = self.robot.forward(state.chassis, &state.arm)?;
            let c = feedback.command(&self.robot, &X, &w[0].X, &w[1].X, self.dt, &state.arm)?;
            state = self
                .robot
                .next_state(&state, &c.speeds, self.dt, self.max_speed)?;
            states.push((state.clone(), w[1].closed));
            errors.push(c.X_err);
        }
        Ok(CapstoneRun {
            dt: self.dt,
            reference,
            states,
            errors,
        })
    }
}
