//! MuJoCo's frames: quaternions `(w, x, y, z)` (MuJoCo's order, not rigid's), the five ways an
//! MJCF element may write its orientation, and poses and their composition.
//!
//! Each function follows MuJoCo's compiler (`src/user/user_util.cc` and `ResolveOrientation` in
//! `src/user/user_objects.cc`, read at commit a725507) operation for operation, so that the
//! compiled frames agree to round-off: in particular `normalize` leaves a vector within `1e-14`
//! of unit length untouched.

use crate::spatial::{Mat3, Transform, Vec3};

/// MuJoCo's `mjEPS`: vectors shorter than this are not normalised.
pub(super) const EPS: f64 = 1e-14;

/// A quaternion in MuJoCo's order `(w, x, y, z)`.
pub(super) type Quat = [f64; 4];

/// The identity quaternion.
pub(super) const IDENTITY: Quat = [1.0, 0.0, 0.0, 0.0];

/// `mjuu_normvec`: scales `v` to unit length and returns its norm before; as MuJoCo, returns 0
/// and leaves `v` when `‖v‖² < 1e-14`, and leaves `v` when `|‖v‖ - 1| ≤ 1e-14`. Unlike MuJoCo,
/// a vector whose norm overflows (or holds a NaN) also returns 0, so that every caller's "too
/// small" check refuses it instead of dividing by infinity.
pub(super) fn normalize(v: &mut [f64]) -> f64 {
    let n2: f64 = v.iter().map(|x| x * x).sum();
    if !(n2 >= EPS && n2.is_finite()) {
        return 0.0;
    }
    let n = n2.sqrt();
    if (n - 1.0).abs() > EPS {
        v.iter_mut().for_each(|x| *x /= n);
    }
    n
}

/// `mjuu_mulquat`: the product `a ⊗ b`, normalised.
pub(super) fn mul(a: &Quat, b: &Quat) -> Quat {
    let mut q = [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ];
    normalize(&mut q);
    q
}

/// `mjuu_rotVecQuat`: `v` rotated by `q`.
pub(super) fn rotate(v: &[f64; 3], q: &Quat) -> [f64; 3] {
    if v == &[0.0; 3] {
        return [0.0; 3];
    }
    if q == &IDENTITY {
        return *v;
    }
    let t = [
        q[0] * v[0] + q[2] * v[2] - q[3] * v[1],
        q[0] * v[1] + q[3] * v[0] - q[1] * v[2],
        q[0] * v[2] + q[1] * v[1] - q[2] * v[0],
    ];
    [
        v[0] + 2.0 * (q[2] * t[2] - q[3] * t[1]),
        v[1] + 2.0 * (q[3] * t[0] - q[1] * t[2]),
        v[2] + 2.0 * (q[1] * t[1] - q[2] * t[0]),
    ]
}

/// `mjuu_quat2mat`: the rotation matrix of `q`, row-major.
pub(super) fn to_matrix(q: &Quat) -> [f64; 9] {
    if q == &IDENTITY {
        return [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
    }
    let (q00, q01, q02, q03) = (q[0] * q[0], q[0] * q[1], q[0] * q[2], q[0] * q[3]);
    let (q11, q12, q13) = (q[1] * q[1], q[1] * q[2], q[1] * q[3]);
    let (q22, q23, q33) = (q[2] * q[2], q[2] * q[3], q[3] * q[3]);
    [
        q00 + q11 - q22 - q33,
        2.0 * (q12 - q03),
        2.0 * (q13 + q02),
        2.0 * (q12 + q03),
        q00 - q11 + q22 - q33,
        2.0 * (q23 - q01),
        2.0 * (q13 - q02),
        2.0 * (q23 + q01),
        q00 - q11 - q22 + q33,
    ]
}

/// The rotation of `q` as rigid's matrix.
pub(super) fn to_mat3(q: &Quat) -> Mat3 {
    Mat3::from_row_slice(&to_matrix(q))
}

fn cross(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `mjuu_z2quat`: the smallest rotation taking `(0, 0, 1)` to `v`.
pub(super) fn z_to(v: &[f64; 3]) -> Quat {
    let mut axis = cross(&[0.0, 0.0, 1.0], v);
    let s = normalize(&mut axis);
    if s < 1e-10 {
        axis = [1.0, 0.0, 0.0];
    }
    let angle = s.atan2(v[2]);
    let (sh, ch) = (0.5 * angle).sin_cos();
    [ch, axis[0] * sh, axis[1] * sh, axis[2] * sh]
}

/// `mjuu_frame2quat`: the quaternion of the frame whose axes are `x`, `y`, `z`.
fn frame_to_quat(x: &[f64; 3], y: &[f64; 3], z: &[f64; 3]) -> Quat {
    let m = [x, y, z]; // m[c][r]
    let mut q = if m[0][0] + m[1][1] + m[2][2] > 0.0 {
        let w = 0.5 * (1.0 + m[0][0] + m[1][1] + m[2][2]).sqrt();
        [
            w,
            0.25 * (m[1][2] - m[2][1]) / w,
            0.25 * (m[2][0] - m[0][2]) / w,
            0.25 * (m[0][1] - m[1][0]) / w,
        ]
    } else if m[0][0] > m[1][1] && m[0][0] > m[2][2] {
        let x = 0.5 * (1.0 + m[0][0] - m[1][1] - m[2][2]).sqrt();
        [
            0.25 * (m[1][2] - m[2][1]) / x,
            x,
            0.25 * (m[1][0] + m[0][1]) / x,
            0.25 * (m[2][0] + m[0][2]) / x,
        ]
    } else if m[1][1] > m[2][2] {
        let y = 0.5 * (1.0 - m[0][0] + m[1][1] - m[2][2]).sqrt();
        [
            0.25 * (m[2][0] - m[0][2]) / y,
            0.25 * (m[1][0] + m[0][1]) / y,
            y,
            0.25 * (m[2][1] + m[1][2]) / y,
        ]
    } else {
        let z = 0.5 * (1.0 - m[0][0] - m[1][1] + m[2][2]).sqrt();
        [
            0.25 * (m[0][1] - m[1][0]) / z,
            0.25 * (m[2][0] + m[0][2]) / z,
            0.25 * (m[2][1] + m[1][2]) / z,
            z,
        ]
    };
    normalize(&mut q);
    q
}

/// How an element writes its orientation (MJCF's "orientation alternatives"): at most one of
/// them per element, `quat` otherwise.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Alternative {
    /// `axisangle = "x y z angle"`.
    AxisAngle([f64; 4]),
    /// `xyaxes = "x1 x2 x3 y1 y2 y3"`: the frame's x axis, and a vector in its x-y plane.
    XyAxes([f64; 6]),
    /// `zaxis = "z1 z2 z3"`: the smallest rotation taking the z axis there.
    ZAxis([f64; 3]),
    /// `euler = "a b c"`: three rotations about the axes of the compiler's `eulerseq`.
    Euler([f64; 3]),
}

/// The quaternion of an orientation alternative (MuJoCo's `ResolveOrientation`): angles in
/// degrees when `degree`; `eulerseq` is three of `xyzXYZ`, lower case for the axes of the frame
/// being rotated (intrinsic: post-multiplied), upper case for the fixed axes (extrinsic:
/// pre-multiplied).
///
/// # Errors
/// The message MuJoCo gives: a zero axis, parallel `xyaxes`, a bad `eulerseq`.
pub(super) fn resolve(alt: &Alternative, degree: bool, eulerseq: &[u8; 3]) -> Result<Quat, String> {
    let to_rad = |a: f64| {
        if degree {
            a / 180.0 * std::f64::consts::PI
        } else {
            a
        }
    };
    match *alt {
        Alternative::AxisAngle(a) => {
            let mut axis = [a[0], a[1], a[2]];
            if normalize(&mut axis) < EPS {
                return Err("axisangle: the axis is zero (or too long)".into());
            }
            let (s, c) = (0.5 * to_rad(a[3])).sin_cos();
            Ok([c, s * axis[0], s * axis[1], s * axis[2]])
        }
        Alternative::XyAxes(v) => {
            let mut x = [v[0], v[1], v[2]];
            if normalize(&mut x) < EPS {
                return Err("xyaxes: the x axis is zero (or too long)".into());
            }
            let d = dot(&x, &[v[3], v[4], v[5]]);
            let mut y = [v[3] - x[0] * d, v[4] - x[1] * d, v[5] - x[2] * d];
            if normalize(&mut y) < EPS {
                return Err("xyaxes: the y axis is zero, parallel to x (or too long)".into());
            }
            let mut z = cross(&x, &y);
            if normalize(&mut z) < EPS {
                return Err("xyaxes: cross(x, y) is too small".into());
            }
            Ok(frame_to_quat(&x, &y, &z))
        }
        Alternative::ZAxis(v) => {
            let mut z = v;
            if normalize(&mut z) < EPS {
                return Err("zaxis is zero (or too long)".into());
            }
            Ok(z_to(&z))
        }
        Alternative::Euler(e) => {
            let mut q = IDENTITY;
            for (i, &axis) in eulerseq.iter().enumerate() {
                let (s, c) = (0.5 * to_rad(e[i])).sin_cos();
                let mut r = [c, 0.0, 0.0, 0.0];
                match axis.to_ascii_lowercase() {
                    b'x' => r[1] = s,
                    b'y' => r[2] = s,
                    b'z' => r[3] = s,
                    _ => return Err("eulerseq can only contain x, y, z, X, Y, Z".into()),
                }
                q = if axis.is_ascii_lowercase() {
                    mul(&q, &r) // moving axes: post-multiply
                } else {
                    mul(&r, &q) // fixed axes: pre-multiply
                };
            }
            normalize(&mut q);
            Ok(q)
        }
    }
}

/// A frame in its parent: position and orientation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Pose {
    /// Position in the parent frame.
    pub pos: [f64; 3],
    /// Orientation in the parent frame.
    pub quat: Quat,
}

impl Pose {
    /// The identity.
    pub const IDENTITY: Self = Self {
        pos: [0.0; 3],
        quat: IDENTITY,
    };

    /// `mjuu_frameaccum`: the pose of `child` (given in this frame) in this frame's parent.
    pub fn then(&self, child: &Self) -> Self {
        let m = to_matrix(&self.quat);
        let c = &child.pos;
        Self {
            pos: [
                self.pos[0] + m[0] * c[0] + m[1] * c[1] + m[2] * c[2],
                self.pos[1] + m[3] * c[0] + m[4] * c[1] + m[5] * c[2],
                self.pos[2] + m[6] * c[0] + m[7] * c[1] + m[8] * c[2],
            ],
            quat: mul(&self.quat, &child.quat),
        }
    }

    /// `mjuu_frameinvert`: the parent seen from this frame.
    pub fn inverse(&self) -> Self {
        let q = [self.quat[0], -self.quat[1], -self.quat[2], -self.quat[3]];
        let p = rotate(&self.pos, &q);
        Self {
            pos: [-p[0], -p[1], -p[2]],
            quat: q,
        }
    }

    /// The same pose as rigid's transform (the rotation normalised first, as MuJoCo's
    /// `mju_quat2Mat` expects a unit quaternion).
    pub fn transform(&self) -> Transform {
        let mut q = self.quat;
        let n = (q.iter().map(|x| x * x).sum::<f64>()).sqrt();
        if n > 0.0 {
            q.iter_mut().for_each(|x| *x /= n);
        }
        Transform::new(to_mat3(&q), Vec3::from(self.pos))
    }
}

/// The eigenvalues (descending) and eigenvector frame of the symmetric matrix `m` (row-major),
/// by MuJoCo's cyclic Jacobi iteration (`mjuu_eig3`, `src/user/user_util.cc`): starting from the
/// identity, each step zeroes the largest off-diagonal entry of `Rᵀ M R` by a rotation about the
/// third axis, accumulated as a quaternion; the eigenvalues are then sorted by quarter turns. The
/// frame MuJoCo reports (`body_iquat`, `mesh_quat`) is the one this reaches. MuJoCo 3 stopped at
/// an absolute `1e-12` (or a rotation of about `1.4e-6` rad), MuJoCo 4 diagonalises to machine
/// precision: here the iteration stops when the largest off-diagonal entry is at most
/// `8 ε max|M|`, and the half-angle of each rotation is computed without cancellation.
pub(super) fn eig3(m: &[f64; 9]) -> ([f64; 3], Quat) {
    let scale = m.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut quat = IDENTITY;
    let mut eigval = [m[0], m[4], m[8]];
    for _ in 0..500 {
        let d = rtmr(&to_matrix(&quat), m);
        eigval = [d[0], d[4], d[8]];
        let (rk, ck, rotk) = if d[1].abs() > d[2].abs() && d[1].abs() > d[5].abs() {
            (0, 1, 2)
        } else if d[2].abs() > d[5].abs() {
            (0, 2, 1)
        } else {
            (1, 2, 0)
        };
        let off = d[3 * rk + ck];
        if off.abs() <= 8.0 * f64::EPSILON * scale {
            break;
        }
        let tau = (d[4 * ck] - d[4 * rk]) / (2.0 * off);
        let t = if tau >= 0.0 {
            1.0 / (tau + (1.0 + tau * tau).sqrt())
        } else {
            -1.0 / (-tau + (1.0 + tau * tau).sqrt())
        };
        let c = 1.0 / (1.0 + t * t).sqrt();
        let mut step = [0.0; 4];
        // sin(θ/2) with tan θ = t, as |s| / √(2 (1 + c)): MuJoCo 3's √(½ - ½ c) cancels to 0
        // for the small last rotations
        let half = t.abs() * c / (2.0 * (1.0 + c)).sqrt();
        step[rotk + 1] = if tau >= 0.0 { -half } else { half };
        if rotk == 1 {
            step[rotk + 1] = -step[rotk + 1];
        }
        step[0] = (1.0 - step[rotk + 1] * step[rotk + 1]).sqrt();
        normalize(&mut step);
        quat = mul(&quat, &step);
        normalize(&mut quat);
    }
    // descending order (bubble sort 0, 1, 0), each swap a quarter turn of the frame
    for j in 0..3 {
        let j1 = j % 2;
        if eigval[j1] + 1e-12 < eigval[j1 + 1] {
            eigval.swap(j1, j1 + 1);
            let mut step = [0.0; 4];
            #[allow(clippy::approx_constant)] // MuJoCo's literal (normalised just after)
            {
                step[0] = 0.707_106_781_186_548;
            }
            step[(j1 + 2) % 3 + 1] = step[0];
            quat = mul(&quat, &step);
            normalize(&mut quat);
        }
    }
    (eigval, quat)
}

/// `Rᵀ M R` for row-major 3x3 matrices.
fn rtmr(r: &[f64; 9], m: &[f64; 9]) -> [f64; 9] {
    let mut rt = [0.0; 9];
    for i in 0..3 {
        for j in 0..3 {
            rt[3 * i + j] = r[3 * j + i];
        }
    }
    matmul(&matmul(&rt, m), r)
}

fn matmul(a: &[f64; 9], b: &[f64; 9]) -> [f64; 9] {
    let mut out = [0.0; 9];
    for i in 0..3 {
        for j in 0..3 {
            out[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < tol)
    }

    #[test]
    fn euler_case_decides_between_moving_and_fixed_axes() {
        // intrinsic x then z: R = Rx(a) Rz(b); extrinsic X then Z: R = Rz(b) Rx(a)
        let (a, b) = (0.3, 1.1);
        let intrinsic = resolve(&Alternative::Euler([a, b, 0.0]), false, b"xzy").unwrap();
        let extrinsic = resolve(&Alternative::Euler([a, b, 0.0]), false, b"XZY").unwrap();
        let rx = crate::spatial::so3::exp(&(Vec3::x() * a));
        let rz = crate::spatial::so3::exp(&(Vec3::z() * b));
        assert!((to_mat3(&intrinsic) - rx * rz).norm() < 1e-15);
        assert!((to_mat3(&extrinsic) - rz * rx).norm() < 1e-15);
    }

    #[test]
    fn every_alternative_names_the_same_quarter_turn_about_z() {
        let want = [0.5f64.sqrt(), 0.0, 0.0, 0.5f64.sqrt()];
        for alt in [
            Alternative::AxisAngle([0.0, 0.0, 2.0, 90.0]),
            Alternative::XyAxes([0.0, 1.0, 0.0, -1.0, 0.0, 0.0]),
            Alternative::Euler([0.0, 0.0, 90.0]),
        ] {
            let q = resolve(&alt, true, b"xyz").unwrap();
            assert!(close(&q, &want, 1e-15), "{alt:?}: {q:?}");
        }
        let q = resolve(&Alternative::ZAxis([1.0, 0.0, 0.0]), true, b"xyz").unwrap();
        assert!(close(
            &rotate(&[0.0, 0.0, 1.0], &q),
            &[1.0, 0.0, 0.0],
            1e-15
        ));
    }

    #[test]
    fn degenerate_alternatives_are_errors() {
        for alt in [
            Alternative::AxisAngle([0.0; 4]),
            Alternative::XyAxes([1.0, 0.0, 0.0, 2.0, 0.0, 0.0]),
            Alternative::ZAxis([0.0; 3]),
        ] {
            assert!(resolve(&alt, true, b"xyz").is_err(), "{alt:?}");
        }
        assert!(resolve(&Alternative::Euler([1.0; 3]), true, b"xyw").is_err());
    }

    #[test]
    fn eig3_diagonalises_to_round_off_with_mujocos_frame() {
        let q = resolve(&Alternative::Euler([10.0, 20.0, 30.0]), true, b"xyz").unwrap();
        let r = to_matrix(&q);
        let d = [3.0, 0.0, 0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0];
        let mut rt = [0.0; 9];
        for i in 0..3 {
            for j in 0..3 {
                rt[3 * i + j] = r[3 * j + i];
            }
        }
        let m = matmul(&matmul(&r, &d), &rt);
        let (l, v) = eig3(&m);
        assert!(close(&l, &[3.0, 2.0, 1.0], 1e-14), "{l:?}");
        let back = rtmr(&to_matrix(&v), &m);
        assert!(close(&back, &d, 1e-14), "{back:?}");
        // the frame reached from the identity is the one the matrix was built with
        let same = close(&v, &q, 1e-12) || close(&v, &q.map(|x| -x), 1e-12);
        assert!(same, "{v:?} vs {q:?}");
    }

    #[test]
    fn pose_composition_and_inverse_cancel() {
        let a = Pose {
            pos: [0.1, -0.2, 0.3],
            quat: resolve(&Alternative::Euler([0.4, 0.5, 0.6]), false, b"xyz").unwrap(),
        };
        let id = a.then(&a.inverse());
        assert!(close(&id.pos, &[0.0; 3], 1e-15) && close(&id.quat, &IDENTITY, 1e-15));
    }
}
