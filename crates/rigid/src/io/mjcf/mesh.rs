//! Mesh assets: the file (STL, OBJ or MuJoCo's binary MSH) read into single-precision vertices as
//! MuJoCo stores them, and the volume, centre of mass and principal inertia of the solid (or
//! shell) by MuJoCo's rules (`mjCMesh::Process`, `ComputeVolume`, `ComputeInertia`,
//! `src/user/user_mesh.cc`):
//!
//! 1. the vertices (float32, from the file) are moved by `refpos`, turned by `refquat`
//!    (`v ← R(refquat)ᵀ (v - refpos)`) and scaled by `scale`, in double precision;
//! 2. the area-weighted centroid of the faces `f` is the apex of one pyramid per triangle, of
//!    volume `V_t = n_t · (c_t - f) A_t / 3` (`n_t` the unit normal, `c_t` the centroid, `A_t` the
//!    area), whose centre of mass is `¾ c_t + ¼ f`; with the default `inertia="legacy"` each
//!    `V_t` counts as `|V_t|` (so that a mesh with inconsistently wound triangles still has a
//!    volume, and a non-convex one has too much), with `"exact"` as signed;
//! 3. about that centre of mass `c`, each triangle `(D, E, F)` (coordinates relative to `c`) adds
//!    the second moments of the tetrahedron `(c, D, E, F)`:
//!    `P_jk += V_t / 20 (2 (D_j D_k + E_j E_k + F_j F_k) + D_j E_k + D_k E_j + D_j F_k + D_k F_j
//!    + E_j F_k + E_k F_j)` (Tonon 2004), with `V_t` recomputed with the apex at `c`, and the
//!    volume is their sum again; the inertia per unit density is `I = tr(P) 1 - P`;
//! 4. `inertia="shell"` uses the area instead of the volume (`C = 12` instead of 20).
//!
//! MuJoCo then turns the mesh to its principal axes and gives a geom made of it the box of equal
//! principal moments (`mjCGeom::SetInertia`): the same inertia, to round-off, as the matrix kept
//! here.

use super::orientation::{to_matrix, Quat};
use std::path::Path;

/// MuJoCo's `mjMINVAL`.
const MINVAL: f64 = 1e-15;

/// How the solid's inertia is computed (`<mesh inertia>`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeshInertia {
    /// MuJoCo's default: each triangle's pyramid counted with a positive volume.
    Legacy,
    /// Signed volumes (a closed, consistently wound surface).
    Exact,
    /// A thin shell: areas instead of volumes.
    Shell,
    /// The solid bounded by the vertices' convex hull.
    Convex,
}

/// A mesh file as MuJoCo stores it: float32 vertices and triangles.
#[derive(Clone, Debug, Default)]
pub(super) struct MeshData {
    pub vertices: Vec<[f32; 3]>,
    pub faces: Vec<[usize; 3]>,
}

/// The mass properties of a mesh per unit density, in the mesh frame after `refpos`, `refquat`
/// and `scale`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct MeshProps {
    /// Volume (or area, for a shell).
    pub volume: f64,
    /// Centre of mass.
    pub com: [f64; 3],
    /// Inertia per unit density about the centre of mass, `(xx, yy, zz, xy, xz, yz)`.
    pub full: [f64; 6],
    /// Its principal frame (MuJoCo's `mesh_quat`).
    pub quat: Quat,
}

/// Reads a mesh file by extension (case-insensitive): `.stl`, `.obj`, `.msh`.
///
/// # Errors
/// A message saying what failed.
pub(super) fn read(path: &Path) -> Result<MeshData, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    let f32_of = |m: crate::mass::TriMesh| MeshData {
        // STL holds float32 already; OBJ is read as double and rounded as MuJoCo's reader does
        vertices: m
            .vertices
            .iter()
            .map(|v| [v.x as f32, v.y as f32, v.z as f32])
            .collect(),
        faces: m.triangles,
    };
    match ext.as_str() {
        "stl" => crate::io::mesh_file::read_stl(path)
            .map(f32_of)
            .map_err(|e| e.to_string()),
        "obj" => crate::io::mesh_file::read_obj(path)
            .map(f32_of)
            .map_err(|e| e.to_string()),
        "msh" => {
            let bytes = std::fs::read(path).map_err(|e| format!("cannot read: {e}"))?;
            parse_msh(&bytes)
        }
        _ => Err(format!(
            "unknown mesh file type \"{ext}\" (rigid reads .stl, .obj and .msh)"
        )),
    }
}

/// A mesh file as the importer reads it (STL, OBJ or MSH, by the extension), as a triangle mesh
/// (for drawing; its mass properties are MuJoCo's through the importer).
///
/// # Errors
/// An unreadable or malformed file: a message saying what failed.
pub fn read_trimesh(path: &Path) -> Result<crate::mass::TriMesh, String> {
    let m = read(path)?;
    let vertices = m
        .vertices
        .iter()
        .map(|v| crate::spatial::Vec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
        .collect();
    Ok(crate::mass::TriMesh::new(vertices, m.faces))
}

/// MuJoCo's binary MSH: four `i32` counts (vertices, normals, texture coordinates, faces), then
/// `3 nv` floats of positions, `3 nn` of normals, `2 nt` of texture coordinates and `3 nf` `i32`
/// vertex indices, all little-endian (`mjCMesh::LoadMSH`).
///
/// # Errors
/// A short or inconsistent file, or an index out of range.
pub(super) fn parse_msh(b: &[u8]) -> Result<MeshData, String> {
    let int = |i: usize| -> i64 {
        i64::from(i32::from_le_bytes([
            b[4 * i],
            b[4 * i + 1],
            b[4 * i + 2],
            b[4 * i + 3],
        ]))
    };
    if b.len() < 16 {
        return Err("MSH file has no header".into());
    }
    let (nv, nn, nt, nf) = (int(0), int(1), int(2), int(3));
    if nv < 4 || nf < 0 || nn < 0 || nt < 0 || (nn > 0 && nn != nv) || (nt > 0 && nt != nv) {
        return Err(format!(
            "invalid sizes in MSH file ({nv} vertices, {nn} normals, {nt} texcoords, {nf} faces)"
        ));
    }
    let words = 4 + 3 * nv + 3 * nn + 2 * nt + 3 * nf;
    if words.checked_mul(4) != Some(b.len() as i64) {
        return Err(format!(
            "MSH file has {} bytes, its header announces {}",
            b.len(),
            words.saturating_mul(4)
        ));
    }
    let float = |i: usize| f32::from_le_bytes([b[4 * i], b[4 * i + 1], b[4 * i + 2], b[4 * i + 3]]);
    let nv = nv as usize;
    let vertices = (0..nv)
        .map(|k| [float(4 + 3 * k), float(5 + 3 * k), float(6 + 3 * k)])
        .collect();
    let start = 4 + 3 * nv + 3 * nn as usize + 2 * nt as usize;
    let mut faces = Vec::with_capacity(nf as usize);
    for k in 0..nf as usize {
        let mut f = [0usize; 3];
        for (j, slot) in f.iter_mut().enumerate() {
            let i = int(start + 3 * k + j);
            if i < 0 || i as usize >= nv {
                return Err(format!("face {k} has vertex index {i}, out of range"));
            }
            *slot = i as usize;
        }
        faces.push(f);
    }
    Ok(MeshData { vertices, faces })
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// MuJoCo's `triangle`: area, unit normal and centroid of `(a, b, c)` (area 0 and no normal
/// below `mjMINVAL`).
fn triangle(a: &[f64; 3], b: &[f64; 3], c: &[f64; 3]) -> (f64, [f64; 3], [f64; 3]) {
    let center = [
        (a[0] + b[0] + c[0]) / 3.0,
        (a[1] + b[1] + c[1]) / 3.0,
        (a[2] + b[2] + c[2]) / 3.0,
    ];
    let (u, v) = (sub(b, a), sub(c, a));
    let mut n = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len < MINVAL {
        return (0.0, [0.0; 3], center);
    }
    n.iter_mut().for_each(|x| *x /= len);
    (0.5 * len, n, center)
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The transforms of the asset: `v ← R(refquat)ᵀ (v - refpos)`, then `v ← scale ∘ v`.
pub(super) fn transformed(
    mesh: &MeshData,
    refpos: &[f64; 3],
    refquat: &Quat,
    scale: &[f64; 3],
) -> Vec<[f64; 3]> {
    let mut q = *refquat;
    super::orientation::normalize(&mut q);
    let m = to_matrix(&q);
    let turn = refquat != &super::orientation::IDENTITY;
    mesh.vertices
        .iter()
        .map(|v| {
            let mut p = [f64::from(v[0]), f64::from(v[1]), f64::from(v[2])];
            p = sub(&p, refpos);
            if turn {
                p = [
                    m[0] * p[0] + m[3] * p[1] + m[6] * p[2],
                    m[1] * p[0] + m[4] * p[1] + m[7] * p[2],
                    m[2] * p[0] + m[5] * p[1] + m[8] * p[2],
                ];
            }
            [p[0] * scale[0], p[1] * scale[1], p[2] * scale[2]]
        })
        .collect()
}

/// `inertia="convex"`: the solid bounded by the convex hull of the vertices, its outward
/// triangles' pyramids with their signed volumes.
#[cfg(feature = "collision")]
fn convex(vert: &[[f64; 3]]) -> Result<MeshProps, String> {
    let points: Vec<crate::spatial::Vec3> = vert.iter().map(|v| (*v).into()).collect();
    let (hull, faces) = crate::collision::hull_triangles(&points)
        .ok_or("the convex hull of its vertices is flat or degenerate")?;
    let hull: Vec<[f64; 3]> = hull.iter().map(|p| [p.x, p.y, p.z]).collect();
    props(&hull, &faces, MeshInertia::Exact)
}

#[cfg(not(feature = "collision"))]
fn convex(_: &[[f64; 3]]) -> Result<MeshProps, String> {
    Err(
        "inertia=\"convex\" needs the convex hull, which needs the `collision` feature; use \
         \"legacy\", \"exact\" or \"shell\""
            .into(),
    )
}

/// The mass properties of the solid (or shell) bounded by `faces` over `vert`, as MuJoCo's
/// compiler computes them (see the module documentation).
///
/// # Errors
/// No faces, a surface or volume too small, a negative volume (`exact` with inward triangles),
/// principal moments that violate the triangle inequality, or the convex-hull rule.
pub(super) fn props(
    vert: &[[f64; 3]],
    faces: &[[usize; 3]],
    rule: MeshInertia,
) -> Result<MeshProps, String> {
    if rule == MeshInertia::Convex {
        return convex(vert);
    }
    if vert.len() < 4 {
        return Err("a mesh needs at least 4 vertices".into());
    }
    if faces.is_empty() {
        return Err(
            "the mesh has no faces (MuJoCo would use its convex hull, which rigid does \
                    not compute)"
                .into(),
        );
    }
    let tri = |f: &[usize; 3]| triangle(&vert[f[0]], &vert[f[1]], &vert[f[2]]);
    // area-weighted centroid of the faces
    let mut facecen = [0.0; 3];
    let mut area = 0.0;
    for f in faces {
        let (a, _, c) = tri(f);
        (0..3).for_each(|k| facecen[k] += a * c[k]);
        area += a;
    }
    if area < MINVAL {
        return Err("the mesh surface area is too small".into());
    }
    facecen.iter_mut().for_each(|x| *x /= area);
    // volume (or area) and centre of mass
    let mut com = [0.0; 3];
    let mut total = 0.0;
    for f in faces {
        let (a, n, c) = tri(f);
        let mut w = match rule {
            MeshInertia::Shell => a,
            _ => dot(&sub(&c, &facecen), &n) * a / 3.0,
        };
        if rule == MeshInertia::Legacy {
            w = w.abs();
        }
        total += w;
        (0..3).for_each(|k| com[k] += w * (c[k] * 3.0 / 4.0 + facecen[k] / 4.0));
    }
    if total >= MINVAL {
        com.iter_mut().for_each(|x| *x /= total);
    } else if total < 0.0 {
        return Err("the mesh volume is negative (triangles wound inwards)".into());
    } else {
        return Err("the mesh volume is too small (MuJoCo suggests inertia=\"shell\")".into());
    }
    // second moments about the centre of mass
    let centered: Vec<[f64; 3]> = vert.iter().map(|v| sub(v, &com)).collect();
    const K: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];
    let c = if rule == MeshInertia::Shell {
        12.0
    } else {
        20.0
    };
    let mut p = [0.0; 6];
    let mut volume = 0.0;
    for f in faces {
        let (d, e, g) = (&centered[f[0]], &centered[f[1]], &centered[f[2]]);
        let (a, n, center) = triangle(d, e, g);
        let mut w = match rule {
            MeshInertia::Shell => a,
            _ => dot(&center, &n) * a / 3.0,
        };
        if rule == MeshInertia::Legacy {
            w = w.abs();
        }
        volume += w;
        for (j, &(r, s)) in K.iter().enumerate() {
            p[j] += w / c
                * (2.0 * (d[r] * d[s] + e[r] * e[s] + g[r] * g[s])
                    + d[r] * e[s]
                    + d[s] * e[r]
                    + d[r] * g[s]
                    + d[s] * g[r]
                    + e[r] * g[s]
                    + e[s] * g[r]);
        }
    }
    let full = [p[1] + p[2], p[0] + p[2], p[0] + p[1], -p[3], -p[4], -p[5]];
    let (l, quat) = super::orientation::eig3(&[
        full[0], full[3], full[4], full[3], full[1], full[5], full[4], full[5], full[2],
    ]);
    if l[2] <= 0.0 {
        return Err("the mesh inertia has a non-positive eigenvalue".into());
    }
    let bad = |a: f64, b: f64, c: f64| a + b < c * (1.0 - 1e-6) - 1e-9;
    if bad(l[0], l[1], l[2]) || bad(l[0], l[2], l[1]) || bad(l[1], l[2], l[0]) {
        return Err("the mesh's principal moments violate A + B >= C".into());
    }
    Ok(MeshProps {
        volume,
        com,
        full,
        quat,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit cube `[0, 1]³` as 12 outward triangles.
    fn cube() -> (Vec<[f64; 3]>, Vec<[usize; 3]>) {
        let v: Vec<[f64; 3]> = (0..8)
            .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
            .collect();
        let f = vec![
            [0, 2, 1],
            [1, 2, 3],
            [4, 5, 6],
            [5, 7, 6],
            [0, 1, 4],
            [1, 5, 4],
            [2, 6, 3],
            [3, 6, 7],
            [0, 4, 2],
            [2, 4, 6],
            [1, 3, 5],
            [3, 7, 5],
        ];
        (v, f)
    }

    #[test]
    fn a_unit_cube_has_unit_volume_and_the_box_inertia() {
        let (v, f) = cube();
        for rule in [MeshInertia::Legacy, MeshInertia::Exact] {
            let p = props(&v, &f, rule).unwrap();
            assert!((p.volume - 1.0).abs() < 1e-14, "{}", p.volume);
            assert!(p.com.iter().all(|c| (c - 0.5).abs() < 1e-14));
            // unit density: 1/6 about each axis, no products
            let want = [1.0 / 6.0, 1.0 / 6.0, 1.0 / 6.0, 0.0, 0.0, 0.0];
            assert!(
                p.full.iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-14),
                "{:?}",
                p.full
            );
        }
    }

    #[test]
    fn inward_triangles_are_refused_by_the_exact_rule_only() {
        let (v, f) = cube();
        let flipped: Vec<[usize; 3]> = f.iter().map(|t| [t[0], t[2], t[1]]).collect();
        assert!(props(&v, &flipped, MeshInertia::Legacy).is_ok());
        assert!(props(&v, &flipped, MeshInertia::Exact).is_err());
    }

    #[test]
    fn msh_files_are_checked_before_they_are_read() {
        assert!(parse_msh(&[0; 8]).is_err());
        let mut b = Vec::new();
        for n in [4i32, 0, 0, 1] {
            b.extend(n.to_le_bytes());
        }
        b.extend([0u8; 48]); // 12 floats
        for i in [0i32, 1, 7] {
            b.extend(i.to_le_bytes());
        }
        assert!(parse_msh(&b).unwrap_err().contains("out of range"));
    }
}
