//! Mass properties of closed triangle meshes: fine tessellations converge to the closed forms,
//! the file readers (binary STL, ASCII STL, OBJ) give back the same solid, and broken meshes are
//! rejected with the right error.

use rigid::io::mesh_file::{read_mesh, MeshFileError};
use rigid::mass::{MeshError, Shape, TriMesh};
use rigid::spatial::{so3, Mat3, Vec3};
use std::f64::consts::PI;
use std::path::PathBuf;

/// A box of edge lengths `s`, each face split into `n × n` squares (two triangles each),
/// outward normals. Face vertices are computed identically on shared edges, then merged.
fn box_mesh(s: Vec3, n: usize) -> TriMesh {
    let mut mesh = TriMesh::default();
    let coord = |k: usize, l: f64| -l / 2.0 + l * k as f64 / n as f64;
    // For each axis a and side ±: the face's (u, v) axes so that u × v = ± e_a.
    for a in 0..3 {
        let (u, v) = ((a + 1) % 3, (a + 2) % 3);
        for side in [-1.0f64, 1.0] {
            let base = mesh.vertices.len();
            for i in 0..=n {
                for j in 0..=n {
                    let mut p = Vec3::zeros();
                    p[a] = side * s[a] / 2.0;
                    p[u] = coord(i, s[u]);
                    p[v] = coord(j, s[v]);
                    mesh.vertices.push(p);
                }
            }
            let id = |i: usize, j: usize| base + i * (n + 1) + j;
            for i in 0..n {
                for j in 0..n {
                    let (p, q, r, t) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                    if side > 0.0 {
                        mesh.triangles.extend([[p, q, r], [p, r, t]]);
                    } else {
                        mesh.triangles.extend([[p, r, q], [p, t, r]]);
                    }
                }
            }
        }
    }
    mesh.merge_duplicate_vertices();
    mesh
}

/// An inscribed prism with `n` sides approximating a cylinder (axis z), outward normals.
fn cylinder_mesh(r: f64, l: f64, n: usize) -> TriMesh {
    let mut v = vec![Vec3::new(0.0, 0.0, -l / 2.0), Vec3::new(0.0, 0.0, l / 2.0)];
    for i in 0..n {
        let t = 2.0 * PI * i as f64 / n as f64;
        v.push(Vec3::new(r * t.cos(), r * t.sin(), -l / 2.0));
        v.push(Vec3::new(r * t.cos(), r * t.sin(), l / 2.0));
    }
    let (b, t) = (|i: usize| 2 + 2 * (i % n), |i: usize| 3 + 2 * (i % n));
    let mut tri = Vec::new();
    for i in 0..n {
        tri.extend([[b(i), b(i + 1), t(i + 1)], [b(i), t(i + 1), t(i)]]);
        tri.push([1, t(i), t(i + 1)]);
        tri.push([0, b(i + 1), b(i)]);
    }
    TriMesh::new(v, tri)
}

/// An inscribed UV sphere with `m` latitude bands and `2m` meridians, outward normals.
fn sphere_mesh(r: f64, m: usize) -> TriMesh {
    let k = 2 * m;
    let mut v = vec![Vec3::new(0.0, 0.0, r), Vec3::new(0.0, 0.0, -r)];
    for j in 1..m {
        let th = PI * j as f64 / m as f64;
        for i in 0..k {
            let ph = 2.0 * PI * i as f64 / k as f64;
            v.push(Vec3::new(
                r * th.sin() * ph.cos(),
                r * th.sin() * ph.sin(),
                r * th.cos(),
            ));
        }
    }
    let p = |j: usize, i: usize| match j {
        0 => 0,
        _ if j == m => 1,
        _ => 2 + (j - 1) * k + i % k,
    };
    let mut tri = Vec::new();
    for j in 0..m {
        for i in 0..k {
            let (a, b, c, d) = (p(j, i), p(j + 1, i), p(j + 1, i + 1), p(j, i + 1));
            if j == 0 {
                tri.push([a, b, c]); // a = d = north pole
            } else if j + 1 == m {
                tri.push([a, b, d]); // b = c = south pole
            } else {
                tri.extend([[a, b, c], [a, c, d]]);
            }
        }
    }
    TriMesh::new(v, tri)
}

/// Relative errors (volume, largest inertia entry) of a mesh against a closed form, mass 1.
fn errors(mesh: &TriMesh, shape: Shape) -> (f64, f64) {
    let p = mesh.mass_properties().unwrap();
    let i = *shape.inertia_com(1.0).matrix();
    assert!(p.com.norm() < 1e-12, "centroid {}", p.com);
    (
        (p.volume - shape.volume()).abs() / shape.volume(),
        (p.inertia_com(1.0).matrix() - i).amax() / i.amax(),
    )
}

#[test]
fn box_mesh_is_exact_at_every_refinement() {
    let s = Vec3::new(0.4, 0.1, 0.25);
    for n in [1, 2, 5] {
        let (ev, ei) = errors(&box_mesh(s, n), Shape::Box { size: s });
        assert!(ev < 1e-13 && ei < 1e-13, "n = {n}: {ev:e}, {ei:e}");
    }
}

fn assert_converges(name: &str, errs: &[(usize, (f64, f64))], finest: f64) {
    for w in errs.windows(2) {
        let ((n0, (v0, i0)), (n1, (v1, i1))) = (w[0], w[1]);
        println!("{name}: n={n0} -> {n1}: volume error {v0:.2e} -> {v1:.2e}, inertia {i0:.2e} -> {i1:.2e}");
        // Inscribed polygons: errors fall like 1/n², so doubling n divides them by about 4.
        assert!(
            v1 < v0 / 3.0 && i1 < i0 / 3.0,
            "{name} does not converge at n = {n1}"
        );
    }
    let (_, (v, i)) = errs[errs.len() - 1];
    assert!(
        v < finest && i < finest,
        "{name}: finest errors {v:e}, {i:e}"
    );
}

#[test]
fn cylinder_tessellations_converge_to_the_closed_form() {
    let (r, l) = (0.1, 0.3);
    let errs: Vec<_> = [16, 32, 64, 128, 256]
        .iter()
        .map(|&n| {
            (
                n,
                errors(
                    &cylinder_mesh(r, l, n),
                    Shape::Cylinder {
                        radius: r,
                        length: l,
                    },
                ),
            )
        })
        .collect();
    assert_converges("cylinder", &errs, 2e-4);
}

#[test]
fn sphere_tessellations_converge_to_the_closed_form() {
    let r = 0.2;
    let errs: Vec<_> = [8, 16, 32, 64, 128]
        .iter()
        .map(|&m| (m, errors(&sphere_mesh(r, m), Shape::Sphere { radius: r })))
        .collect();
    assert_converges("sphere", &errs, 1e-3);
}

#[test]
fn moved_mesh_has_moved_com_and_rotated_inertia() {
    // Rotating a body by R and translating it by p: c' = R c + p, I' = R I Rᵀ; far from the
    // origin the bounding-box reference point keeps the result accurate.
    let s = Vec3::new(0.4, 0.1, 0.25);
    let r = so3::from_rpy(0.3, -1.1, 2.0);
    let p = Vec3::new(1000.0, -2000.0, 500.0);
    let mut mesh = box_mesh(s, 2);
    for v in &mut mesh.vertices {
        *v = r * *v + p;
    }
    let props = mesh.mass_properties().unwrap();
    let i = Shape::Box { size: s }.inertia_com(3.0).rotated_by(&r);
    assert!(
        (props.com - p).norm() < 1e-10 * p.norm(),
        "{}",
        props.com - p
    );
    assert!((props.inertia_com(3.0).matrix() - i.matrix()).amax() < 1e-9 * i.matrix().amax());
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rigid-mesh-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Binary STL with the header `header` (padded to 80 bytes): 80-byte header, u32 count, then per facet a normal and 3 vertices (f32 LE) and a
/// u16 attribute. Every facet repeats its vertices.
fn write_binary_stl(mesh: &TriMesh, path: &PathBuf, header: &[u8]) {
    let mut out = header.to_vec();
    out.resize(80, b' ');
    out.extend((mesh.triangles.len() as u32).to_le_bytes());
    for t in &mesh.triangles {
        for v in [
            Vec3::zeros(),
            mesh.vertices[t[0]],
            mesh.vertices[t[1]],
            mesh.vertices[t[2]],
        ] {
            for x in v.iter() {
                out.extend((*x as f32).to_le_bytes());
            }
        }
        out.extend([0u8, 0]);
    }
    std::fs::write(path, out).unwrap();
}

fn write_ascii_stl(mesh: &TriMesh, path: &PathBuf, first_line: &str) {
    let mut s = format!("{first_line}\n");
    for t in &mesh.triangles {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for &i in t {
            let v = mesh.vertices[i].map(|x| x as f32);
            s += &format!("      vertex {} {} {}\n", v.x, v.y, v.z);
        }
        s += "    endloop\n  endfacet\n";
    }
    s += "endsolid test\n";
    std::fs::write(path, s).unwrap();
}

fn write_obj(mesh: &TriMesh, path: &PathBuf) {
    let mut s = String::from("# test mesh\no test\n");
    for v in &mesh.vertices {
        s += &format!("v {} {} {}\n", v.x, v.y, v.z);
    }
    for t in &mesh.triangles {
        s += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    std::fs::write(path, s).unwrap();
}

#[test]
fn stl_and_obj_files_read_back_the_same_solid() {
    // A coarse sphere away from the origin; STL stores f32, so the STL results agree to f32
    // precision (1e-6 relative), the OBJ (full f64 text) to rounding.
    let mut mesh = sphere_mesh(0.2, 12);
    for v in &mut mesh.vertices {
        *v += Vec3::new(0.5, -0.25, 0.125);
    }
    let want = mesh.mass_properties().unwrap();
    // Also the awkward variants real exporters write: a binary header that starts with "solid",
    // an ASCII file that opens with a bare "solid".
    let cases = [
        ("sphere_bin.stl", 1e-6),
        ("sphere_bin_solid_header.stl", 1e-6),
        ("sphere_ascii.stl", 1e-6),
        ("sphere_ascii_bare_solid.stl", 1e-6),
        ("sphere.obj", 1e-12),
    ];
    write_binary_stl(&mesh, &temp(cases[0].0), b"binary");
    write_binary_stl(&mesh, &temp(cases[1].0), b"solid exported by CAD");
    write_ascii_stl(&mesh, &temp(cases[2].0), "solid test");
    write_ascii_stl(&mesh, &temp(cases[3].0), "solid");
    write_obj(&mesh, &temp(cases[4].0));
    for (file, tol) in cases {
        let read = read_mesh(&temp(file)).unwrap();
        assert_eq!(
            read.vertices.len(),
            mesh.vertices.len(),
            "{file}: vertices not merged"
        );
        assert_eq!(read.triangles.len(), mesh.triangles.len());
        let got = read.mass_properties().unwrap();
        assert!(
            (got.volume - want.volume).abs() < tol * want.volume,
            "{file}"
        );
        assert!((got.com - want.com).norm() < tol, "{file}");
        let di = (got.inertia_com(1.0).matrix() - want.inertia_com(1.0).matrix()).amax();
        assert!(
            di < tol * want.inertia_com(1.0).matrix().amax(),
            "{file}: {di:e}"
        );
    }
}

#[test]
fn obj_quads_are_triangulated() {
    let path = temp("cube_quads.obj");
    let obj =
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
               f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    std::fs::write(&path, obj).unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.triangles.len(), 12);
    let (ev, ei) = errors(
        &mesh,
        Shape::Box {
            size: Vec3::repeat(2.0),
        },
    );
    assert!(ev < 1e-14 && ei < 1e-14);
}

#[test]
fn obj_with_several_objects_is_one_solid() {
    // The cube of the previous test, its faces split between two objects and two groups: the
    // shared vertices are merged back and the surface is closed.
    let path = temp("cube_objects.obj");
    let obj = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
               o bottom\nf 1 4 3 2\nf 5 6 7 8\ng sides\nf 1 2 6 5\no rest\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
    std::fs::write(&path, obj).unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.vertices.len(), 8);
    let (ev, ei) = errors(
        &mesh,
        Shape::Box {
            size: Vec3::repeat(2.0),
        },
    );
    assert!(ev < 1e-14 && ei < 1e-14);
}

/// Texture and normal indices are never read (only positions and faces make mass properties):
/// a normal index that tobj's bounds check would wrap around (`vn * 3 + 2` overflowing to 0, then
/// an out-of-bounds read; found by fuzzing, `fuzz/regressions/obj/`) is harmless, and so is a
/// texture index off its range on a `vt` line whose keyword ends in a vertical tab (tobj splits
/// on Unicode whitespace); the solid loads as written.
#[test]
fn obj_texture_and_normal_indices_are_ignored() {
    let path = temp("tetra_wrapping_normal.obj");
    // (vn - 1) * 3 + 2 ≡ 0 (mod 2^64) for the normal index -6148914691236517207 with one `vn`
    let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0.5 0.5\n\
               f 1/-9223372036854775808/-6148914691236517207 3//-6148914691236517207 2/1/1\n\
               f 1 2 4\nf 1 4 3\n  vn 1 0 0\nvt\x0b\t0 0\nf 2/-7 3 4\n";
    std::fs::write(&path, obj).unwrap();
    let mesh = read_mesh(&path).unwrap();
    assert_eq!(mesh.triangles.len(), 4);
    assert!((mesh.volume().unwrap() - tetrahedron().volume().unwrap()).abs() < 1e-15);
}

fn tetrahedron() -> TriMesh {
    TriMesh::new(
        vec![Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()],
        vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    )
}

#[test]
fn open_mesh_is_rejected() {
    let mut m = cylinder_mesh(1.0, 1.0, 8);
    m.triangles.pop();
    assert!(matches!(m.mass_properties(), Err(MeshError::Open { .. })));
    assert!(m.check().unwrap_err().to_string().contains("not closed"));
}

#[test]
fn one_flipped_triangle_is_an_inconsistent_orientation() {
    let mut m = tetrahedron();
    m.triangles[3] = [1, 3, 2];
    let e = m.mass_properties().unwrap_err();
    assert!(matches!(e, MeshError::Inconsistent { .. }), "{e}");
    assert!(e.to_string().contains("not consistently oriented"));
}

#[test]
fn inward_normals_are_rejected_and_flipping_fixes_them() {
    let m = sphere_mesh(1.0, 6).flipped();
    let e = m.mass_properties().unwrap_err();
    assert!(
        matches!(e, MeshError::InwardNormals { volume } if volume < 0.0),
        "{e}"
    );
    assert!(e.to_string().contains("inward"));
    assert!(m.flipped().mass_properties().is_ok());
}

#[test]
fn degenerate_empty_nonmanifold_and_bad_index_meshes_are_rejected() {
    let mut m = tetrahedron();
    m.triangles.push([0, 0, 1]);
    assert!(matches!(
        m.check(),
        Err(MeshError::Degenerate { triangle: 4 })
    ));

    let mut flat = tetrahedron();
    flat.vertices[3] = Vec3::new(0.25, 0.25, 0.0); // all four in the plane z = 0

    assert!(matches!(
        flat.mass_properties(),
        Err(MeshError::ZeroVolume { .. })
    ));

    assert!(matches!(TriMesh::default().check(), Err(MeshError::Empty)));

    let mut bad = tetrahedron();
    bad.triangles[0][1] = 9;
    assert!(matches!(
        bad.check(),
        Err(MeshError::BadIndex { vertex: 9, .. })
    ));

    // Two tetrahedra sharing only the edge 0-1: it belongs to four triangles.
    let mut two = tetrahedron();
    let far = [Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, 0.0, -1.0)];
    two.vertices.extend(far);
    two.triangles
        .extend([[0, 4, 1], [0, 1, 5], [0, 5, 4], [1, 4, 5]]);
    let e = two.check().unwrap_err();
    assert!(matches!(e, MeshError::NonManifold { count: 4, .. }), "{e}");

    let mut nan = tetrahedron();
    nan.vertices[2].y = f64::NAN;
    assert!(matches!(
        nan.check(),
        Err(MeshError::NonFinite { vertex: 2 })
    ));
}

#[test]
fn unreadable_and_unknown_mesh_files_are_errors() {
    assert!(matches!(
        read_mesh(&temp("missing.stl")),
        Err(MeshFileError::Io(_))
    ));
    let txt = temp("mesh.ply");
    std::fs::write(&txt, "ply").unwrap();
    assert!(matches!(
        read_mesh(&txt),
        Err(MeshFileError::UnknownFormat(_))
    ));
    let junk = temp("junk.stl");
    std::fs::write(&junk, [1u8, 2, 3]).unwrap();
    assert!(read_mesh(&junk).is_err());
    let junk_obj = temp("junk.obj");
    std::fs::write(&junk_obj, "v 1 2\nf 1 2 x\n").unwrap();
    assert!(read_mesh(&junk_obj).is_err());
}

#[test]
fn tetrahedron_unit_density_inertia_matches_the_textbook() {
    // Tonon 2004 example-style check: for the tetrahedron (0, e1, e2, e3), ∫x² dV = 1/60 and
    // ∫xy dV = 1/120, so about the origin (density 1) I_xx = 1/30 and I_xy = -1/120.
    let p = tetrahedron().mass_properties().unwrap();
    let c = Vec3::repeat(0.25);
    let i_o = p.unit_inertia_com.steiner_from_com(p.volume, &c);
    let want = Mat3::new(
        1.0 / 30.0,
        -1.0 / 120.0,
        -1.0 / 120.0,
        -1.0 / 120.0,
        1.0 / 30.0,
        -1.0 / 120.0,
        -1.0 / 120.0,
        -1.0 / 120.0,
        1.0 / 30.0,
    );
    assert!((i_o.matrix() - want).amax() < 1e-15);
}
