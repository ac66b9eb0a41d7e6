//! Closed triangle meshes: volume, centre of mass and rotational inertia of the uniform solid they
//! bound, by the divergence theorem.
//!
//! The solid is cut into the signed tetrahedra `(0, a, b, c)`, one per triangle `(a, b, c)`,
//! with the apex at a reference point `o` (the centre of the bounding box, to keep the sums well
//! conditioned). With `d = (a - o)·((b - o)×(c - o))` (six times the signed volume), the exact
//! integrals over one tetrahedron with vertices `0, a, b, c` (coordinates relative to `o`) are
//! (Tonon 2004, *J. Math. Stat.* 1(1); Eberly, "Polyhedral Mass Properties"):
//!
//! - `∫ dV = d / 6`
//! - `∫ x dV = d / 24 (a + b + c)`
//! - `∫ x xᵀ dV = d / 120 (a aᵀ + b bᵀ + c cᵀ + s sᵀ)` with `s = a + b + c`
//!
//! Summed over the triangles of a closed, consistently oriented surface with outward normals,
//! they give the volume `V`, the first moment `V c` and the second moment `C = ∫ r rᵀ dV`; the
//! inertia of unit density about `o` is `tr(C) 1 - C`, and Steiner moves it to the CoM.

use super::RotationalInertia;
use crate::spatial::{Mat3, Vec3};
use std::collections::HashMap;
use thiserror::Error;

/// A triangle mesh: vertex positions (m) and triangles as vertex indices, counter-clockwise
/// seen from outside (normals by the right-hand rule point out of the solid).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriMesh {
    /// The vertex positions.
    pub vertices: Vec<Vec3>,
    /// The triangles, each three indices into `vertices`.
    pub triangles: Vec<[usize; 3]>,
}

/// What makes a mesh unfit to bound a solid.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MeshError {
    /// No triangles.
    #[error("mesh has no triangles")]
    Empty,
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// The vertex index.
        vertex: usize,
    },
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {vertex}, but there are only {count} vertices")]
    BadIndex {
        /// The triangle index.
        triangle: usize,
        /// The missing vertex index.
        vertex: usize,
        /// The number of vertices.
        count: usize,
    },
    /// A triangle with a repeated vertex or (almost) zero area.
    #[error("triangle {triangle} is degenerate (zero area or a repeated vertex)")]
    Degenerate {
        /// The triangle index.
        triangle: usize,
    },
    /// An edge used by only one triangle: the surface has a hole.
    #[error(
        "mesh is not closed: edge between vertices {a} and {b} belongs to only one triangle (at {at:?})"
    )]
    Open {
        /// One end of the edge.
        a: usize,
        /// The other end.
        b: usize,
        /// The position of vertex `a`.
        at: [f64; 3],
    },
    /// An edge shared by more than two triangles.
    #[error(
        "mesh is not a manifold: edge between vertices {a} and {b} belongs to {count} triangles"
    )]
    NonManifold {
        /// One end of the edge.
        a: usize,
        /// The other end.
        b: usize,
        /// How many triangles use it.
        count: usize,
    },
    /// Two triangles that share an edge run along it in the same direction: one of them is
    /// wound the other way.
    #[error(
        "mesh is not consistently oriented: the two triangles on edge {a}-{b} both run from {a} to {b}"
    )]
    Inconsistent {
        /// One end of the edge.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// All triangles are wound clockwise seen from outside: the enclosed volume comes out
    /// negative. Reverse the winding ([`TriMesh::flipped`]) or fix the exporter.
    #[error("mesh normals point inward (signed volume {volume:.6e} m³ < 0); reverse the triangle winding")]
    InwardNormals {
        /// The signed volume found.
        volume: f64,
    },
    /// The enclosed volume is zero (a flat or collapsed surface).
    #[error("mesh encloses no volume (signed volume {volume:.6e} m³)")]
    ZeroVolume {
        /// The signed volume found.
        volume: f64,
    },
}

/// The mass properties of the uniform solid a closed mesh bounds, per unit density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshMassProperties {
    /// The volume `V` (m³).
    pub volume: f64,
    /// The centroid `c` (= CoM for uniform density) in the mesh's coordinates.
    pub com: Vec3,
    /// The rotational inertia about `c` of the solid with density 1 kg/m³ (mesh axes).
    pub unit_inertia_com: RotationalInertia,
}

impl MeshMassProperties {
    /// The inertia about the CoM of the solid with total mass `m`: `(m / V) × unit inertia`.
    #[must_use]
    pub fn inertia_com(&self, mass: f64) -> RotationalInertia {
        self.unit_inertia_com * (mass / self.volume)
    }

    /// The inertia about the CoM of the solid with density `ρ` (kg/m³).
    #[must_use]
    pub fn inertia_com_density(&self, density: f64) -> RotationalInertia {
        self.unit_inertia_com * density
    }
}

impl TriMesh {
    /// A mesh from its vertices and triangles (nothing is checked; see [`TriMesh::check`]).
    #[must_use]
    pub fn new(vertices: Vec<Vec3>, triangles: Vec<[usize; 3]>) -> Self {
        Self {
            vertices,
            triangles,
        }
    }

    /// The same mesh with every triangle's winding reversed (normals flipped).
    #[must_use]
    pub fn flipped(&self) -> Self {
        Self {
            vertices: self.vertices.clone(),
            triangles: self.triangles.iter().map(|t| [t[0], t[2], t[1]]).collect(),
        }
    }

    /// Merges vertices with bit-identical coordinates (`-0.0` equals `0.0`) and drops the unused
    /// ones, renumbering the triangles. STL files repeat each vertex once per facet; after this
    /// the facets share their vertices and the edges can be matched.
    pub fn merge_duplicate_vertices(&mut self) {
        let key = |v: &Vec3| v.map(|x| if x == 0.0 { 0u64 } else { x.to_bits() });
        let mut first: HashMap<[u64; 3], usize> = HashMap::new();
        let mut new_index = vec![usize::MAX; self.vertices.len()];
        let mut kept = Vec::new();
        let used: Vec<bool> = {
            let mut u = vec![false; self.vertices.len()];
            for t in &self.triangles {
                for &i in t {
                    if i < u.len() {
                        u[i] = true;
                    }
                }
            }
            u
        };
        for (i, v) in self.vertices.iter().enumerate() {
            if !used[i] {
                continue;
            }
            let k = key(v);
            let j = *first.entry([k.x, k.y, k.z]).or_insert_with(|| {
                kept.push(*v);
                kept.len() - 1
            });
            new_index[i] = j;
        }
        for t in &mut self.triangles {
            for i in t.iter_mut() {
                if *i < new_index.len() {
                    *i = new_index[*i];
                }
            }
        }
        self.vertices = kept;
    }

    /// Checks that the mesh bounds a solid: at least one triangle, finite vertices, valid
    /// indices, no degenerate triangle (area below `1e-12 ×` the squared bounding-box diagonal),
    /// and every undirected edge used by exactly two triangles, once in each direction.
    ///
    /// # Errors
    /// The first problem found, as a [`MeshError`].
    pub fn check(&self) -> Result<(), MeshError> {
        if self.triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(vertex) = self
            .vertices
            .iter()
            .position(|v| v.iter().any(|x| !x.is_finite()))
        {
            return Err(MeshError::NonFinite { vertex });
        }
        let count = self.vertices.len();
        for (triangle, t) in self.triangles.iter().enumerate() {
            if let Some(&vertex) = t.iter().find(|&&i| i >= count) {
                return Err(MeshError::BadIndex {
                    triangle,
                    vertex,
                    count,
                });
            }
        }
        let diag2 = self.bounding_box_diagonal().powi(2);
        for (triangle, t) in self.triangles.iter().enumerate() {
            let [a, b, c] = t.map(|i| self.vertices[i]);
            let twice_area = (b - a).cross(&(c - a)).norm();
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || twice_area <= 2e-12 * diag2 {
                return Err(MeshError::Degenerate { triangle });
            }
        }
        // Every edge as (low, high, runs low -> high), sorted: a closed, consistently oriented
        // surface has each (low, high) exactly twice, once in each direction. Sorting (rather
        // than hashing) is fast and reports the bad edge with the smallest indices.
        let mut edges: Vec<(usize, usize, bool)> = self
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |k| (t[k], t[(k + 1) % 3])))
            .map(|(a, b)| (a.min(b), a.max(b), a < b))
            .collect();
        edges.sort_unstable();
        for group in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let (lo, hi, up) = group[0];
            let (a, b) = if up { (lo, hi) } else { (hi, lo) };
            match group.len() {
                1 => {
                    let v = self.vertices[a];
                    return Err(MeshError::Open {
                        a,
                        b,
                        at: [v.x, v.y, v.z],
                    });
                }
                2 if group[1].2 == up => return Err(MeshError::Inconsistent { a, b }),
                2 => {}
                count => {
                    return Err(MeshError::NonManifold {
                        a: lo,
                        b: hi,
                        count,
                    })
                }
            }
        }
        Ok(())
    }

    /// The length of the diagonal of the axis-aligned bounding box (0 for no vertex).
    #[must_use]
    pub fn bounding_box_diagonal(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (hi - lo).norm()
    }

    fn bounds(&self) -> (Vec3, Vec3) {
        let mut lo = Vec3::repeat(f64::INFINITY);
        let mut hi = Vec3::repeat(f64::NEG_INFINITY);
        for v in &self.vertices {
            lo = lo.inf(v);
            hi = hi.sup(v);
        }
        if self.vertices.is_empty() {
            (Vec3::zeros(), Vec3::zeros())
        } else {
            (lo, hi)
        }
    }

    /// The signed integrals `(V, ∫ r dV, ∫ r rᵀ dV)` relative to `o`, without any check.
    fn moments(&self, o: &Vec3) -> (f64, Vec3, Mat3) {
        let mut vol = 0.0;
        let mut first = Vec3::zeros();
        let mut second = Mat3::zeros();
        for t in &self.triangles {
            let [a, b, c] = t.map(|i| self.vertices[i] - o);
            let d = a.dot(&b.cross(&c));
            let s = a + b + c;
            vol += d / 6.0;
            first += s * (d / 24.0);
            second +=
                (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose())
                    * (d / 120.0);
        }
        (vol, first, second)
    }

    /// The signed enclosed volume `Σ d/6` without any check (negative when the normals point
    /// inward).
    #[must_use]
    pub fn signed_volume(&self) -> f64 {
        let (lo, hi) = self.bounds();
        self.moments(&((lo + hi) * 0.5)).0
    }

    /// Checks the mesh ([`TriMesh::check`]) and computes the volume, centroid and unit-density
    /// inertia about the centroid of the solid it bounds (see the module documentation).
    ///
    /// # Errors
    /// Any error of [`TriMesh::check`], [`MeshError::InwardNormals`] when the enclosed volume is
    /// negative (the mesh is not flipped for you) and [`MeshError::ZeroVolume`] when it is zero
    /// relative to the bounding box.
    pub fn mass_properties(&self) -> Result<MeshMassProperties, MeshError> {
        self.check()?;
        let (lo, hi) = self.bounds();
        let o = (lo + hi) * 0.5;
        let (volume, first, second) = self.moments(&o);
        let scale = (hi - lo).norm().powi(3);
        if volume.abs() <= 1e-12 * scale {
            return Err(MeshError::ZeroVolume { volume });
        }
        if volume < 0.0 {
            return Err(MeshError::InwardNormals { volume });
        }
        let c = first / volume;
        // Unit-density inertia about o: tr(C) 1 - C; then Steiner back to the centroid.
        let i_o = Mat3::identity() * second.trace() - second;
        let unit_inertia_com =
            RotationalInertia::from_matrix_unchecked(&i_o).steiner_to_com(volume, &c);
        Ok(MeshMassProperties {
            volume,
            com: c + o,
            unit_inertia_com,
        })
    }

    /// The enclosed volume (m³), after the checks of [`TriMesh::mass_properties`].
    ///
    /// # Errors
    /// As [`TriMesh::mass_properties`].
    pub fn volume(&self) -> Result<f64, MeshError> {
        Ok(self.mass_properties()?.volume)
    }

    /// The centroid of the enclosed solid.
    ///
    /// # Errors
    /// As [`TriMesh::mass_properties`].
    pub fn com(&self) -> Result<Vec3, MeshError> {
        Ok(self.mass_properties()?.com)
    }

    /// The inertia about the centroid of the enclosed uniform solid of total mass `m`.
    ///
    /// ```
    /// use rigid::mass::TriMesh;
    /// use rigid::spatial::Vec3;
    /// // The unit tetrahedron (0, e1, e2, e3), outward normals.
    /// let mesh = TriMesh::new(
    ///     vec![Vec3::zeros(), Vec3::x(), Vec3::y(), Vec3::z()],
    ///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    /// );
    /// assert!((mesh.volume().unwrap() - 1.0 / 6.0).abs() < 1e-15);
    /// assert!((mesh.com().unwrap() - Vec3::repeat(0.25)).norm() < 1e-15);
    /// // Mass 1 (density 6): I_xx about 0 is 6 ∫(y² + z²) dV = 6 (1/60 + 1/60) = 0.2, and
    /// // Steiner to the centroid (1/4, 1/4, 1/4) removes 1 · (1/16 + 1/16): 0.075.
    /// let i = mesh.inertia_com(1.0).unwrap();
    /// assert!((i.matrix()[(0, 0)] - 0.075).abs() < 1e-12);
    /// ```
    ///
    /// # Errors
    /// As [`TriMesh::mass_properties`].
    pub fn inertia_com(&self, mass: f64) -> Result<RotationalInertia, MeshError> {
        Ok(self.mass_properties()?.inertia_com(mass))
    }
}
