//! Wheeled bases on the plane: each wheel's rolling condition gives a row of `H(φ)`, the body
//! twist comes back through `F = H(0)†`, and odometry integrates it with the planar exponential
//! (Lynch & Park §13.2–13.4).

use super::MobileError;
use nalgebra::{DMatrix, Matrix3, Vector3};

/// One wheel of a base (Lynch & Park Fig. 13.4), in the chassis frame {b} whose x axis points
/// forward.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wheel {
    /// `(x_i, y_i)`: where the wheel touches the floor in {b} (m).
    pub position: [f64; 2],
    /// `β_i`: the direction the wheel drives in, from {b}'s x axis (rad).
    pub drive: f64,
    /// `γ_i`: the direction of free sliding of its rollers, from the driving direction (rad):
    /// 0 for an omniwheel or a conventional wheel, ±π/4 for a mecanum wheel.
    pub sliding: f64,
    /// `r_i` (m), positive.
    pub radius: f64,
}

impl Wheel {
    /// `h_i(0) = 1/(r_i cos γ_i) [x_i sin(β_i+γ_i) - y_i cos(β_i+γ_i), cos(β_i+γ_i), sin(β_i+γ_i)]`
    /// (Lynch & Park eq. 13.5): `u_i = h_i(0) V_b` for the planar body twist
    /// `V_b = (ω_bz, v_bx, v_by)`.
    #[must_use]
    pub fn h0(&self) -> [f64; 3] {
        let [x, y] = self.position;
        let (s, c) = (self.drive + self.sliding).sin_cos();
        let k = 1.0 / (self.radius * self.sliding.cos());
        [k * (x * s - y * c), k * c, k * s]
    }
}

/// What the wheels allow.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// Omniwheels or mecanum wheels: any planar twist (rank `H(0)` = 3).
    Omnidirectional,
    /// Two conventional wheels on one axle, `track` apart, the chassis frame at the axle's
    /// middle: no sideways motion, `A(q) q̇ = 0` (Lynch & Park §13.3).
    DiffDrive {
        /// Distance between the wheels, `2d` (m).
        track: f64,
    },
    /// A car: the rear axle drives as a differential drive, the front wheels steer;
    /// `ω = v tan ψ / ℓ` (Lynch & Park eq. 13.14).
    Car {
        /// Distance between the rear wheels (m).
        track: f64,
        /// `ℓ`, rear axle to front axle (m).
        wheelbase: f64,
    },
}

/// A wheeled base: its wheels, `H(0)` (`m × 3`) and `F = H(0)†` (`3 × m`).
///
/// ```
/// use rigid::mobile::Base;
/// let base = Base::mecanum(0.0475, 0.235, 0.15)?;
/// // all four wheels forward at 1 rad/s: straight ahead at r m/s
/// let v = base.body_twist(&[1.0, 1.0, 1.0, 1.0])?;
/// assert!(v[0].abs() < 1e-15 && (v[1] - 0.0475).abs() < 1e-15 && v[2].abs() < 1e-15);
/// # Ok::<(), rigid::mobile::MobileError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Base {
    name: &'static str,
    kind: Kind,
    wheels: Vec<Wheel>,
    H0: DMatrix<f64>,
    F: DMatrix<f64>,
}

/// Singular values of `H(0)` below this fraction of the largest count as zero.
const RANK_TOLERANCE: f64 = 1e-9;

fn positive(what: &'static str, value: f64) -> Result<f64, MobileError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(MobileError::NotPositive { what, value })
    }
}

impl Base {
    /// A base with the given wheels and kind; checks every wheel (finite, `r > 0`, rollers not
    /// along the driving direction) and that `H(0)` has the rank the kind needs (3, or 2 for a
    /// differential drive or a car).
    ///
    /// # Errors
    /// [`MobileError::NotPositive`], [`MobileError::NotFinite`], [`MobileError::RollersAlongDrive`],
    /// [`MobileError::RankDeficient`].
    pub fn new(name: &'static str, kind: Kind, wheels: Vec<Wheel>) -> Result<Self, MobileError> {
        for (i, w) in wheels.iter().enumerate() {
            positive("wheel radius", w.radius).map_err(|e| e.on_wheel(i))?;
            if !(w.position.iter().all(|x| x.is_finite())
                && w.drive.is_finite()
                && w.sliding.is_finite())
            {
                return Err(MobileError::NotFinite {
                    what: "wheel geometry",
                }
                .on_wheel(i));
            }
            if w.sliding.cos().abs() < 1e-9 {
                return Err(MobileError::RollersAlongDrive { wheel: i });
            }
        }
        let m = wheels.len();
        let needed = if kind == Kind::Omnidirectional { 3 } else { 2 };
        if m == 0 {
            return Err(MobileError::RankDeficient {
                base: name,
                rank: 0,
                needed,
            });
        }
        let H0 = DMatrix::from_fn(m, 3, |i, j| wheels[i].h0()[j]);
        let svd = H0.clone().svd(true, true);
        let smax = svd.singular_values.max();
        let rank = svd
            .singular_values
            .iter()
            .filter(|&&s| s > RANK_TOLERANCE * smax && smax > 0.0)
            .count();
        if rank < needed {
            return Err(MobileError::RankDeficient {
                base: name,
                rank,
                needed,
            });
        }
        let F =
            svd.pseudo_inverse(RANK_TOLERANCE * smax)
                .map_err(|_| MobileError::RankDeficient {
                    base: name,
                    rank,
                    needed,
                })?;
        Ok(Self {
            name,
            kind,
            wheels,
            H0,
            F,
        })
    }

    /// Four mecanum wheels (rollers at ±45°) at `(±l, ±w)`, radius `r`, in the order front-left,
    /// front-right, rear-right, rear-left (Lynch & Park eq. 13.10, the youBot's base):
    /// `H(0) = 1/r [[-l-w, 1, -1], [l+w, 1, 1], [l+w, 1, -1], [-l-w, 1, 1]]`.
    ///
    /// # Errors
    /// A radius that is not positive, `l` or `w` negative, `l + w = 0` (rank 2).
    pub fn mecanum(r: f64, l: f64, w: f64) -> Result<Self, MobileError> {
        for (what, x) in [("half-length l", l), ("half-width w", w)] {
            if !(x.is_finite() && x >= 0.0) {
                return Err(MobileError::NotPositive { what, value: x });
            }
        }
        let q = std::f64::consts::FRAC_PI_4;
        let wheel = |x: f64, y: f64, sliding: f64| Wheel {
            position: [x, y],
            drive: 0.0,
            sliding,
            radius: r,
        };
        Self::new(
            "mecanum",
            Kind::Omnidirectional,
            vec![
                wheel(l, w, -q),
                wheel(l, -w, q),
                wheel(-l, -w, -q),
                wheel(-l, w, q),
            ],
        )
    }

    /// The KUKA youBot's mecanum base of the capstone: `r = 0.0475`, `l = 0.235`, `w = 0.15`.
    #[must_use]
    pub fn youbot() -> Self {
        Self::mecanum(0.0475, 0.235, 0.15).expect("the youBot's base is valid")
    }

    /// Three omniwheels at distance `d` from the centre, 120° apart, driving tangentially; wheel 1
    /// at `(0, d)` driving along +x, wheels 2 and 3 following clockwise (Lynch & Park eq. 13.9):
    /// `H(0) = 1/r [[-d, 1, 0], [-d, -1/2, -sin(π/3)], [-d, -1/2, sin(π/3)]]`.
    ///
    /// # Errors
    /// A radius or distance that is not positive.
    pub fn omni3(r: f64, d: f64) -> Result<Self, MobileError> {
        positive("distance d", d)?;
        let wheels = (0..3)
            .map(|i| {
                // the wheel's angle about z, and its driving direction 90° ahead of it
                let a = std::f64::consts::FRAC_PI_2 - 2.0 * std::f64::consts::FRAC_PI_3 * i as f64;
                Wheel {
                    position: [d * a.cos(), d * a.sin()],
                    drive: a - std::f64::consts::FRAC_PI_2,
                    sliding: 0.0,
                    radius: r,
                }
            })
            .collect();
        Self::new("omni3", Kind::Omnidirectional, wheels)
    }

    /// A differential drive: left wheel at `(0, track/2)`, right at `(0, -track/2)`, radius `r`
    /// (Lynch & Park §13.3): `u_L = (v - d ω)/r`, `u_R = (v + d ω)/r`, `d = track/2`.
    ///
    /// # Errors
    /// A radius or track that is not positive.
    pub fn diff_drive(r: f64, track: f64) -> Result<Self, MobileError> {
        positive("track", track)?;
        Self::new("diff-drive", Kind::DiffDrive { track }, axle(r, track))
    }

    /// A car-like base: the rear axle (wheels `track` apart, radius `r`) drives, the front axle
    /// `wheelbase` ahead steers; the chassis frame at the middle of the rear axle (Lynch & Park
    /// §13.3.1). `H` and `F` are those of the rear axle.
    ///
    /// # Errors
    /// A radius, track or wheelbase that is not positive.
    pub fn car(r: f64, track: f64, wheelbase: f64) -> Result<Self, MobileError> {
        positive("track", track)?;
        positive("wheelbase", wheelbase)?;
        Self::new("car", Kind::Car { track, wheelbase }, axle(r, track))
    }

    /// The base's name (`mecanum`, `omni3`, `diff-drive`, `car`, or the one given to [`Base::new`]).
    #[must_use]
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// What the wheels allow.
    #[must_use]
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// The wheels, in the order of the rows of `H`.
    #[must_use]
    pub fn wheels(&self) -> &[Wheel] {
        &self.wheels
    }

    /// `H(φ) = H(0) [[1, 0, 0], [0, cos φ, sin φ], [0, -sin φ, cos φ]]` (`m × 3`; Lynch & Park
    /// eq. 13.5): the wheel speeds `u = H(φ) q̇` for the chassis velocity `q̇ = (φ̇, ẋ, ẏ)`.
    #[must_use]
    pub fn H(&self, phi: f64) -> DMatrix<f64> {
        let (s, c) = phi.sin_cos();
        let rot = DMatrix::from_row_slice(3, 3, &[1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c]);
        &self.H0 * rot
    }

    /// `F = H(0)†` (`3 × m`): the planar body twist `V_b = (ω_bz, v_bx, v_by) = F u` from the wheel
    /// speeds (Lynch & Park eq. 13.33); for a differential drive or a car the least-squares
    /// inverse, with `v_by = 0`.
    #[must_use]
    pub fn F(&self) -> &DMatrix<f64> {
        &self.F
    }

    /// `F6 = [0; 0; F; 0]` (`6 × m`): the six-dimensional body twist `(0, 0, ω_bz, v_bx, v_by, 0)`
    /// from the wheel speeds (Lynch & Park §13.5).
    #[must_use]
    pub fn F6(&self) -> DMatrix<f64> {
        let mut f6 = DMatrix::zeros(6, self.wheels.len());
        f6.rows_mut(2, 3).copy_from(&self.F);
        f6
    }

    /// `V_b = F u` for wheel speeds (or increments) `u`.
    ///
    /// # Errors
    /// [`MobileError::Dimension`] when `u` is not one number per wheel; [`MobileError::NotFinite`].
    pub fn body_twist(&self, u: &[f64]) -> Result<[f64; 3], MobileError> {
        self.check_wheels("wheel speeds", u)?;
        let v = &self.F * nalgebra::DVector::from_column_slice(u);
        Ok([v[0], v[1], v[2]])
    }

    /// Odometry (Lynch & Park §13.4): the chassis configuration `q = (φ, x, y)` after the wheels
    /// turned by `Δθ`: `V_b = F Δθ`, the planar exponential
    /// `Δq_b = (ω, (v_x sin ω + v_y (cos ω - 1))/ω, (v_y sin ω + v_x (1 - cos ω))/ω)`
    /// (`(0, v_x, v_y)` when `ω = 0`; eq. 13.35), then `Δq = R(φ) Δq_b`.
    ///
    /// ```
    /// use rigid::mobile::Base;
    /// let base = Base::diff_drive(0.1, 0.5)?;
    /// // both wheels turn by 10 rad: straight ahead by r · 10 = 1 m
    /// let q = base.odometry([0.0, 0.0, 0.0], &[10.0, 10.0])?;
    /// assert!((q[1] - 1.0).abs() < 1e-15 && q[0] == 0.0 && q[2] == 0.0);
    /// # Ok::<(), rigid::mobile::MobileError>(())
    /// ```
    ///
    /// # Errors
    /// As [`Base::body_twist`]; a non-finite `q`.
    pub fn odometry(&self, q: [f64; 3], dtheta: &[f64]) -> Result<[f64; 3], MobileError> {
        if !q.iter().all(|x| x.is_finite()) {
            return Err(MobileError::NotFinite {
                what: "chassis configuration",
            });
        }
        let [w, vx, vy] = self.body_twist(dtheta)?;
        // sin ω / ω and (1 - cos ω)/ω, by their series near 0
        let (a, b) = if w.abs() < 1e-6 {
            (1.0 - w * w / 6.0, w / 2.0 - w * w * w / 24.0)
        } else {
            (w.sin() / w, (1.0 - w.cos()) / w)
        };
        let (dx, dy) = (vx * a - vy * b, vy * a + vx * b);
        let (s, c) = q[0].sin_cos();
        Ok([q[0] + w, q[1] + c * dx - s * dy, q[2] + s * dx + c * dy])
    }

    /// The nonholonomic constraint `A(q) q̇ = 0` of a differential drive or a car: no sideways
    /// motion of the axle, `A(q) = [0, sin φ, -cos φ]` (Lynch & Park eq. 13.15); `None` for an
    /// omnidirectional base.
    #[must_use]
    pub fn constraint(&self, q: [f64; 3]) -> Option<[f64; 3]> {
        match self.kind {
            Kind::Omnidirectional => None,
            Kind::DiffDrive { .. } | Kind::Car { .. } => {
                let (s, c) = q[0].sin_cos();
                Some([0.0, s, -c])
            }
        }
    }

    /// A car's steering angle `ψ = atan(ℓ ω / v)` for the body twist `(ω, v, 0)` (Lynch & Park
    /// eq. 13.14); `None` for other bases or `v = 0` with `ω ≠ 0` (turning in place, which a car
    /// cannot).
    #[must_use]
    pub fn steering(&self, twist: [f64; 3]) -> Option<f64> {
        let Kind::Car { wheelbase, .. } = self.kind else {
            return None;
        };
        let [w, v, _] = twist;
        if v == 0.0 {
            return (w == 0.0).then_some(0.0);
        }
        Some((wheelbase * w / v).atan())
    }

    fn check_wheels(&self, what: &'static str, u: &[f64]) -> Result<(), MobileError> {
        if u.len() != self.wheels.len() {
            return Err(MobileError::Dimension(crate::error::DimensionError {
                what,
                expected: self.wheels.len(),
                got: u.len(),
            }));
        }
        if !u.iter().all(|x| x.is_finite()) {
            return Err(MobileError::NotFinite { what });
        }
        Ok(())
    }
}

/// Two conventional wheels on the y axis, left first.
fn axle(r: f64, track: f64) -> Vec<Wheel> {
    [0.5 * track, -0.5 * track]
        .into_iter()
        .map(|y| Wheel {
            position: [0.0, y],
            drive: 0.0,
            sliding: 0.0,
            radius: r,
        })
        .collect()
}

/// The rotation `R(φ)` of the chassis configuration, acting on `(φ, x, y)` (Lynch & Park eq. 13.36
/// without the `Δ`): `[[1, 0, 0], [0, cos φ, -sin φ], [0, sin φ, cos φ]]`.
#[must_use]
pub fn planar_rotation(phi: f64) -> Matrix3<f64> {
    let (s, c) = phi.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// `q̇ = R(φ) V_b`: the chassis velocity `(φ̇, ẋ, ẏ)` of the planar body twist `(ω, v_x, v_y)`.
#[must_use]
pub fn chassis_velocity(phi: f64, twist: [f64; 3]) -> [f64; 3] {
    let v = planar_rotation(phi) * Vector3::from(twist);
    [v[0], v[1], v[2]]
}
