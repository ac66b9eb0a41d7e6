//! Mass and inertia from geoms, as MuJoCo's compiler computes them (`mjCGeom::GetVolume`,
//! `mjCGeom::SetInertia`, `mjCBody::InertiaFromGeom`, `src/user/user_objects.cc`).
//!
//! A geom's mass is its `mass`, or `density × volume`; its inertia is diagonal in the geom frame
//! (`a, b, c` the half-sizes, `r` the radius, `h = 2 × half-length`):
//!
//! | geom | volume | `(I_x, I_y, I_z) / m` |
//! | --- | --- | --- |
//! | sphere | `4/3 π r³` | `2/5 r²` (each) |
//! | box | `8 a b c` | `((b² + c²), (a² + c²), (a² + b²)) / 3` |
//! | ellipsoid | `4/3 π a b c` | `((b² + c²), (a² + c²), (a² + b²)) / 5` |
//! | cylinder | `π r² h` | `(3 r² + h²) / 12`, the same, `r² / 2` |
//! | capsule | `π (r² h + 4/3 r³)` | a cylinder of mass `m_c` and two hemispheres of mass `m_s` |
//! | mesh | the solid's volume ([`mesh`](super::mesh)) | the box of equal principal moments |
//!
//! For the capsule, `m_s = m 4r / (4r + 3h)` (the spheres' share of the volume) and
//! `m_c = m - m_s`; `I_x = I_y = m_c (3r² + h²)/12 + 2/5 m_s r² + m_s h (3r + 2h)/8` and
//! `I_z = m_c r²/2 + 2/5 m_s r²`: exact, since each hemisphere (mass `m_s / 2`, centre of mass
//! `3r/8` beyond its end of the cylinder, `83/320 (m_s/2) r²` about it) adds
//! `(m_s/2)(2/5 r² + (h/2)² + 3/8 h r)` about the capsule's centre. With
//! `shellinertia="true"` the mass lies on the surface: MuJoCo's shell formulas, the area in place
//! of the volume.
//!
//! A body's inertia (when taken from geoms) sums the geoms whose `group` lies in the compiler's
//! `inertiagrouprange` and whose mass exceeds `1e-14`: one geom gives its own frame and diagonal
//! inertia; several give the mass-weighted centre of mass and the sum of each
//! `R I Rᵀ + m ((d·d) 1 - d dᵀ)`, which MuJoCo then diagonalises (to machine precision in
//! MuJoCo 4; rigid keeps the matrix).

use super::mesh::MeshProps;
use super::orientation::{to_mat3, to_matrix, Pose, Quat, EPS};
use crate::spatial::{Mat3, Vec3};
use std::f64::consts::PI;

/// A geom's shape, for its volume and inertia (sizes as MuJoCo's `geom_size`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Solid {
    /// Radius.
    Sphere(f64),
    /// Radius, half-length.
    Capsule(f64, f64),
    /// Radius, half-length.
    Cylinder(f64, f64),
    /// Semi-axes.
    Ellipsoid([f64; 3]),
    /// Half-sizes (also a height field's box).
    Box([f64; 3]),
    /// A mesh asset's properties.
    Mesh(MeshProps),
    /// A plane or anything without volume.
    None,
}

impl Solid {
    /// MuJoCo's `GetVolume`: the volume, or the area for a shell.
    pub fn volume(&self, shell: bool) -> f64 {
        match *self {
            Self::Sphere(r) if shell => 4.0 * PI * r * r,
            Self::Sphere(r) => 4.0 * PI * r * r * r / 3.0,
            Self::Capsule(r, hh) => {
                let h = 2.0 * hh;
                if shell {
                    4.0 * PI * r * r + 2.0 * PI * r * h
                } else {
                    PI * (r * r * h + 4.0 * r * r * r / 3.0)
                }
            }
            Self::Cylinder(r, hh) => {
                let h = 2.0 * hh;
                if shell {
                    2.0 * PI * r * r + 2.0 * PI * r * h
                } else {
                    PI * r * r * h
                }
            }
            Self::Ellipsoid(s) if shell => {
                // Thomsen's approximation of the surface area
                let p = 1.6075;
                let t = (s[0] * s[1]).powf(p) + (s[1] * s[2]).powf(p) + (s[2] * s[0]).powf(p);
                4.0 * PI * (t / 3.0).powf(1.0 / p)
            }
            Self::Ellipsoid(s) => 4.0 * PI * s[0] * s[1] * s[2] / 3.0,
            Self::Box(s) if shell => 8.0 * (s[0] * s[1] + s[1] * s[2] + s[2] * s[0]),
            Self::Box(s) => s[0] * s[1] * s[2] * 8.0,
            Self::Mesh(p) => p.volume,
            Self::None => 0.0,
        }
    }

    /// The geom's mass distribution in the body frame, for mass `m` and the geom frame `pose`: a
    /// primitive's diagonal inertia turned by `pose`; a mesh's (its inertia per unit volume times
    /// `m`, about its centre of mass, in the mesh frame) turned and moved by `pose` (MuJoCo puts
    /// the geom frame at the mesh's principal axes and gives it the box of equal moments, the
    /// same inertia to round-off).
    pub fn inertial(&self, m: f64, shell: bool, pose: &Pose) -> Inertial {
        match self {
            Self::Mesh(p) => {
                let unit = p.full.map(|x| x * m / p.volume);
                let c = super::orientation::rotate(&p.com, &pose.quat);
                Inertial {
                    mass: m,
                    com: [pose.pos[0] + c[0], pose.pos[1] + c[1], pose.pos[2] + c[2]],
                    full: rotated(&unit, &pose.quat),
                    axes: Some(super::orientation::mul(&pose.quat, &p.quat)),
                }
            }
            _ => Inertial::principal(m, pose, &self.inertia(m, shell)),
        }
    }

    /// MuJoCo's `SetInertia`: the diagonal inertia of mass `m` in the geom frame.
    pub fn inertia(&self, m: f64, shell: bool) -> [f64; 3] {
        match *self {
            Self::Sphere(r) => {
                [if shell {
                    2.0 * m * r * r / 3.0
                } else {
                    2.0 * m * r * r / 5.0
                }; 3]
            }
            Self::Capsule(r, hh) if shell => {
                let h = 2.0 * hh;
                let a_sphere = 4.0 * PI * r * r;
                let a_total = a_sphere + 2.0 * PI * r * h;
                let ms = m * a_sphere / a_total;
                let mc = m - ms;
                let side = mc * (6.0 * r * r + h * h) / 12.0;
                let si = 2.0 * ms * r * r / 3.0;
                let (com, pos) = (r / 2.0, hh + r / 2.0);
                let shift = ms * (pos * pos - com * com);
                [side + si + shift, side + si + shift, mc * r * r + si]
            }
            Self::Capsule(r, hh) => {
                let h = 2.0 * hh;
                let ms = m * 4.0 * r / (4.0 * r + 3.0 * h);
                let mc = m - ms;
                let side = mc * (3.0 * r * r + h * h) / 12.0;
                let si = 2.0 * ms * r * r / 5.0;
                let shift = ms * h * (3.0 * r + 2.0 * h) / 8.0;
                [side + si + shift, side + si + shift, mc * r * r / 2.0 + si]
            }
            Self::Cylinder(r, hh) if shell => {
                let h = 2.0 * hh;
                let a_disk = PI * r * r;
                let a_total = 2.0 * a_disk + 2.0 * PI * r * h;
                let md = m * a_disk / a_total;
                let mc = m - 2.0 * md;
                let side = mc * (6.0 * r * r + h * h) / 12.0;
                let dx = md * r * r / 4.0 + md * hh * hh;
                let dz = md * r * r / 2.0;
                [side + 2.0 * dx, side + 2.0 * dx, mc * r * r + 2.0 * dz]
            }
            Self::Cylinder(r, hh) => {
                let h = 2.0 * hh;
                let side = m * (3.0 * r * r + h * h) / 12.0;
                [side, side, m * r * r / 2.0]
            }
            Self::Ellipsoid(s) if shell => {
                // the shell as the difference of two solid ellipsoids 1e-6 apart
                let eps = 1e-6;
                let va = 4.0 * PI * s[0] * s[1] * s[2] / 3.0;
                let (ae, be, ce) = (s[0] + eps, s[1] + eps, s[2] + eps);
                let vb = 4.0 * PI * ae * be * ce / 3.0;
                let density = m / (vb - va);
                let (ma, mb) = (va * density, vb * density);
                let (s00, s11, s22) = (s[0] * s[0], s[1] * s[1], s[2] * s[2]);
                [
                    mb * (be * be + ce * ce) / 5.0 - ma * (s11 + s22) / 5.0,
                    mb * (ae * ae + ce * ce) / 5.0 - ma * (s00 + s22) / 5.0,
                    mb * (ae * ae + be * be) / 5.0 - ma * (s00 + s11) / 5.0,
                ]
            }
            Self::Ellipsoid(s) => {
                let (s00, s11, s22) = (s[0] * s[0], s[1] * s[1], s[2] * s[2]);
                [
                    m * (s11 + s22) / 5.0,
                    m * (s00 + s22) / 5.0,
                    m * (s00 + s11) / 5.0,
                ]
            }
            Self::Box(s) if shell => box_shell(m, &s),
            Self::Box(s) => {
                let (s00, s11, s22) = (s[0] * s[0], s[1] * s[1], s[2] * s[2]);
                [
                    m * (s11 + s22) / 3.0,
                    m * (s00 + s22) / 3.0,
                    m * (s00 + s11) / 3.0,
                ]
            }
            // a mesh's inertia is not diagonal in the geom frame: see `inertial`
            Self::Mesh(_) | Self::None => [0.0; 3],
        }
    }
}

/// A box's six faces, each a thin plate of mass proportional to its area.
fn box_shell(m: f64, s: &[f64; 3]) -> [f64; 3] {
    let (lx, ly, lz) = (2.0 * s[0], 2.0 * s[1], 2.0 * s[2]);
    let (a0, a1, a2) = (lx * ly, ly * lz, lz * lx);
    let total = 2.0 * (a0 + a1 + a2);
    let (m0, m1, m2) = (m * a0 / total, m * a1 / total, m * a2 / total);
    let (s00, s11, s22) = (s[0] * s[0], s[1] * s[1], s[2] * s[2]);
    let ix = [
        m0 * ly * ly / 12.0,
        m1 * (ly * ly + lz * lz) / 12.0,
        m2 * lz * lz / 12.0,
    ];
    let iy = [
        m0 * lx * lx / 12.0,
        m1 * lz * lz / 12.0,
        m2 * (lx * lx + lz * lz) / 12.0,
    ];
    let iz = [
        m0 * (lx * lx + ly * ly) / 12.0,
        m1 * ly * ly / 12.0,
        m2 * lx * lx / 12.0,
    ];
    [
        2.0 * (m0 * s22 + m2 * s11 + ix[0] + ix[1] + ix[2]),
        2.0 * (m0 * s22 + m1 * s00 + iy[0] + iy[1] + iy[2]),
        2.0 * (m1 * s00 + m2 * s11 + iz[0] + iz[1] + iz[2]),
    ]
}

/// The mass distribution of a body or geom in the body frame: mass, centre of mass and the full
/// inertia about it, `(xx, yy, zz, xy, xz, yz)` (MuJoCo's `fullinertia` order). MuJoCo stores
/// the principal moments and axes instead; MuJoCo 4 decomposes to machine precision, so that
/// keeping the full matrix is its inertia to round-off.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Inertial {
    /// Mass (kg).
    pub mass: f64,
    /// Centre of mass in the body frame.
    pub com: [f64; 3],
    /// Inertia about the centre of mass in the body frame's axes (kg·m²).
    pub full: [f64; 6],
    /// The principal frame MuJoCo copies (one geom's frame, an `<inertial>`'s orientation), or
    /// `None` when it diagonalises `full` ([`eig3`](super::orientation::eig3)).
    pub axes: Option<Quat>,
}

impl Inertial {
    /// No mass, at the body origin.
    pub const ZERO: Self = Self {
        mass: 0.0,
        com: [0.0; 3],
        full: [0.0; 6],
        axes: None,
    };

    /// Mass `m` at `frame` with principal moments `diag` along its axes.
    pub fn principal(mass: f64, frame: &Pose, diag: &[f64; 3]) -> Self {
        Self {
            mass,
            com: frame.pos,
            full: global(diag, &frame.quat),
            axes: Some(frame.quat),
        }
    }

    /// MuJoCo's principal frame (`body_iquat`).
    pub fn frame(&self) -> Quat {
        self.axes.unwrap_or_else(|| {
            let f = &self.full;
            super::orientation::eig3(&[f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2]]).1
        })
    }

    /// The inertia about the centre of mass as rigid's matrix.
    pub fn matrix(&self) -> Mat3 {
        let f = &self.full;
        Mat3::new(f[0], f[3], f[4], f[3], f[1], f[5], f[4], f[5], f[2])
    }

    /// The principal moments (MuJoCo's `body_inertia`) and the rotation whose columns are the
    /// principal axes (MuJoCo's `body_iquat`).
    pub fn principal_axes(&self) -> ([f64; 3], Mat3) {
        let r = to_mat3(&self.frame());
        let d = r.transpose() * self.matrix() * r;
        ([d[(0, 0)], d[(1, 1)], d[(2, 2)]], r)
    }

    /// The same inertia with principal moments `f(λ)` on the same axes.
    pub fn map_moments(&self, f: impl Fn(f64) -> f64) -> Self {
        let (l, r) = self.principal_axes();
        let d = Mat3::from_diagonal(&Vec3::new(f(l[0]), f(l[1]), f(l[2])));
        Self {
            full: crate::mass::RotationalInertia::from_matrix_unchecked(&d)
                .rotated_by(&r)
                .entries(),
            ..*self
        }
    }
}

/// `mjuu_globalinertia`: `R diag(d) Rᵀ` as `(xx, yy, zz, xy, xz, yz)`.
fn global(d: &[f64; 3], q: &Quat) -> [f64; 6] {
    let m = to_matrix(q);
    let t = [
        m[0] * d[0],
        m[3] * d[0],
        m[6] * d[0],
        m[1] * d[1],
        m[4] * d[1],
        m[7] * d[1],
        m[2] * d[2],
        m[5] * d[2],
        m[8] * d[2],
    ];
    [
        m[0] * t[0] + m[1] * t[3] + m[2] * t[6],
        m[3] * t[1] + m[4] * t[4] + m[5] * t[7],
        m[6] * t[2] + m[7] * t[5] + m[8] * t[8],
        m[0] * t[1] + m[1] * t[4] + m[2] * t[7],
        m[0] * t[2] + m[1] * t[5] + m[2] * t[8],
        m[3] * t[2] + m[4] * t[5] + m[5] * t[8],
    ]
}

/// `R I Rᵀ` for a full inertia `(xx, yy, zz, xy, xz, yz)`.
pub(super) fn rotated(full: &[f64; 6], q: &Quat) -> [f64; 6] {
    let r = to_mat3(q);
    let i = Inertial {
        full: *full,
        ..Inertial::ZERO
    }
    .matrix();
    let m = r * i * r.transpose();
    [
        m[(0, 0)],
        m[(1, 1)],
        m[(2, 2)],
        m[(0, 1)],
        m[(0, 2)],
        m[(1, 2)],
    ]
}

/// MuJoCo's `InertiaFromGeom`: the body's mass distribution from its geoms' (each in the body
/// frame): the total mass, the mass-weighted centre of mass, and the sum of each geom's inertia
/// `I_g + m_g ((d·d) 1 - d dᵀ)` moved to it; `None` when no geom has mass above `1e-14`.
///
/// # Errors
/// A total mass too small to locate the centre of mass.
pub(super) fn from_geoms(geoms: &[Inertial]) -> Result<Option<Inertial>, String> {
    let sel: Vec<&Inertial> = geoms.iter().filter(|g| g.mass > EPS).collect();
    match sel.as_slice() {
        [] => Ok(None),
        [one] => Ok(Some(**one)),
        many => {
            let mass: f64 = many.iter().map(|g| g.mass).sum();
            let mut com = [0.0; 3];
            for g in many {
                (0..3).for_each(|k| com[k] += g.mass * g.com[k]);
            }
            if mass < EPS {
                return Err("body mass is too small to compute its centre of mass".into());
            }
            com.iter_mut().for_each(|c| *c /= mass);
            let mut full = [0.0; 6];
            for g in many {
                let d = [g.com[0] - com[0], g.com[1] - com[1], g.com[2] - com[2]];
                let shift = offcenter(g.mass, &d);
                (0..6).for_each(|k| full[k] = full[k] + g.full[k] + shift[k]);
            }
            Ok(Some(Inertial {
                mass,
                com,
                full,
                axes: None,
            }))
        }
    }
}

/// `mjuu_offcenter`: `m ((d·d) 1 - d dᵀ)` as `(xx, yy, zz, xy, xz, yz)`.
fn offcenter(m: f64, d: &[f64; 3]) -> [f64; 6] {
    [
        m * (d[1] * d[1] + d[2] * d[2]),
        m * (d[0] * d[0] + d[2] * d[2]),
        m * (d[0] * d[0] + d[1] * d[1]),
        -m * d[0] * d[1],
        -m * d[0] * d[2],
        -m * d[1] * d[2],
    ]
}

/// MuJoCo's check of a full inertia: its smallest principal moment at least `1e-14` ("inertia
/// must have positive eigenvalues").
///
/// # Errors
/// A smaller moment.
pub(super) fn check_positive(full: &[f64; 6]) -> Result<(), String> {
    let i = Inertial {
        full: *full,
        ..Inertial::ZERO
    };
    let (l, _) = i.principal_axes();
    if l[2] < EPS {
        return Err(format!(
            "the inertia must have positive principal moments (smallest {:e})",
            l[2]
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capsule_is_a_cylinder_and_a_sphere_in_volume() {
        let (r, hh) = (0.1, 0.3);
        let v = Solid::Capsule(r, hh).volume(false);
        let want = Solid::Cylinder(r, hh).volume(false) + Solid::Sphere(r).volume(false);
        assert!((v - want).abs() < 1e-15);
        // the axial moment is the cylinder's and sphere's, each with its own mass
        let m = 2.0;
        let i = Solid::Capsule(r, hh).inertia(m, false);
        let ms = m * Solid::Sphere(r).volume(false) / v;
        let want_z = (m - ms) * r * r / 2.0 + 2.0 / 5.0 * ms * r * r;
        assert!((i[2] - want_z).abs() < 1e-15);
    }

    #[test]
    fn two_equal_spheres_apart_add_the_parallel_axis_terms() {
        let sphere = |x: f64| {
            let at = Pose {
                pos: [x, 0.0, 0.0],
                quat: super::super::orientation::IDENTITY,
            };
            Inertial::principal(1.0, &at, &[0.1; 3])
        };
        let b = from_geoms(&[sphere(1.0), sphere(-1.0)]).unwrap().unwrap();
        assert_eq!(b.mass, 2.0);
        assert_eq!(b.full, [0.2, 2.2, 2.2, 0.0, 0.0, 0.0]);
        let (l, r) = b.principal_axes();
        assert!(
            (l[0] - 2.2).abs() < 1e-12 && (l[2] - 0.2).abs() < 1e-12,
            "{l:?}"
        );
        assert!((r.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn massless_geoms_leave_the_body_without_inertia() {
        assert_eq!(from_geoms(&[Inertial::ZERO, Inertial::ZERO]).unwrap(), None);
    }
}
