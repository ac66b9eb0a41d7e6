//! Triangle mesh files: binary and ASCII STL (through the `stl_io` crate), Wavefront OBJ
//! (through `tobj`) and COLLADA ([`super::collada`]), read into a [`TriMesh`] whose duplicate vertices are merged, so that the
//! facets of an STL file (which repeats every vertex once per facet) share their edges.

use crate::mass::TriMesh;
use crate::spatial::Vec3;
use std::fs::File;
use std::io::{BufReader, Cursor};
use std::path::Path;
use thiserror::Error;

/// A mesh file that cannot be read.
#[derive(Debug, Error)]
pub enum MeshFileError {
    /// The file could not be opened or read.
    #[error("cannot read mesh file: {0}")]
    Io(#[from] std::io::Error),
    /// The extension is none of `.stl`, `.obj`, `.dae`.
    #[error("unknown mesh file extension {0:?}: expected .stl, .obj or .dae")]
    UnknownFormat(String),
    /// The STL reader failed.
    #[error("invalid STL file: {0}")]
    Stl(std::io::Error),
    /// The OBJ reader failed.
    #[error("invalid OBJ file: {0}")]
    Obj(tobj::LoadError),
    /// The COLLADA reader failed.
    #[error("invalid COLLADA file: {0}")]
    Dae(String),
}

/// Reads an STL (binary or ASCII, detected from the content), OBJ or COLLADA file
/// ([`super::collada`]), chosen by the extension (case-insensitive), and merges duplicate vertices. The mesh is not checked: call
/// [`TriMesh::check`] or [`TriMesh::mass_properties`].
///
/// # Errors
/// A [`MeshFileError`] saying what failed.
pub fn read_mesh(path: &Path) -> Result<TriMesh, MeshFileError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
        .unwrap_or_default();
    match ext.as_str() {
        "stl" => read_stl(path),
        "obj" => read_obj(path),
        "dae" => super::collada::parse_dae(&std::fs::read_to_string(path)?),
        _ => Err(MeshFileError::UnknownFormat(ext)),
    }
}

/// Reads a binary or ASCII STL file and merges duplicate vertices.
///
/// The format is decided by the size: a file of exactly `84 + 50 n` bytes, `n` being the
/// facet count stored at byte 80, is binary, even when its 80-byte header starts with `solid`
/// (as some CAD exporters write); anything else is ASCII, whose first line may be a bare `solid`.
///
/// # Errors
/// [`MeshFileError::Io`] if the file cannot be opened, [`MeshFileError::Stl`] if it is not STL.
pub fn read_stl(path: &Path) -> Result<TriMesh, MeshFileError> {
    parse_stl(std::fs::read(path)?)
}

/// As [`read_stl`], from the file's bytes.
///
/// # Errors
/// [`MeshFileError::Stl`] if the bytes are not STL.
pub fn parse_stl(mut bytes: Vec<u8>) -> Result<TriMesh, MeshFileError> {
    let binary = bytes.len() >= 84 && {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        n.checked_mul(50).and_then(|b| b.checked_add(84)) == Some(bytes.len())
    };
    // stl_io takes a file for ASCII exactly when it starts with "solid ": make it so.
    if binary && bytes.starts_with(b"solid") {
        bytes[..5].copy_from_slice(b"     ");
    } else if !binary && bytes.starts_with(b"solid") && !bytes.starts_with(b"solid ") {
        bytes.insert(5, b' ');
    }
    let stl = stl_io::read_stl(&mut Cursor::new(bytes)).map_err(MeshFileError::Stl)?;
    let vertices = stl
        .vertices
        .iter()
        .map(|v| Vec3::new(f64::from(v[0]), f64::from(v[1]), f64::from(v[2])))
        .collect();
    let triangles = stl.faces.iter().map(|f| f.vertices).collect();
    let mut mesh = TriMesh::new(vertices, triangles);
    mesh.merge_duplicate_vertices();
    Ok(mesh)
}

/// Reads a Wavefront OBJ file (all objects and groups, polygons triangulated as fans; materials,
/// normals and texture coordinates ignored) and merges duplicate vertices.
///
/// # Errors
/// [`MeshFileError::Io`] if the file cannot be opened, [`MeshFileError::Obj`] if it is not OBJ.
pub fn read_obj(path: &Path) -> Result<TriMesh, MeshFileError> {
    parse_obj(&mut BufReader::new(File::open(path)?))
}

/// The OBJ text without its `vt` and `vn` lines. Only positions and faces make a body's mass
/// properties; and tobj (4.0) bounds-checks texture and normal indices with unchecked arithmetic
/// (`vn * 3 + 2`), so that a crafted relative index wraps around and indexes out of bounds, a
/// panic that coverage-guided fuzzing found (`fuzz/regressions/obj/`). Without those lines tobj
/// never reads the indices.
fn without_texcoords_and_normals(
    reader: &mut impl std::io::BufRead,
) -> Result<Vec<u8>, MeshFileError> {
    let mut bytes = Vec::new();
    reader.read_to_end(&mut bytes)?;
    let mut out = Vec::with_capacity(bytes.len());
    for line in bytes.split_inclusive(|&b| b == b'\n') {
        // tobj's own reading: lines, then Unicode whitespace (a vertical tab separates too); a
        // line that is not UTF-8 is kept, and tobj refuses the file
        let keyword = std::str::from_utf8(line)
            .ok()
            .and_then(|l| l.split_whitespace().next());
        if !matches!(keyword, Some("vt" | "vn")) {
            out.extend_from_slice(line);
        }
    }
    Ok(out)
}

/// As [`read_obj`], from a reader of the file's text.
///
/// # Errors
/// [`MeshFileError::Obj`] if the text is not OBJ.
pub fn parse_obj(reader: &mut impl std::io::BufRead) -> Result<TriMesh, MeshFileError> {
    // `..Default::default()` covers the fields that tobj's optional features add.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        single_index: false,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let text = without_texcoords_and_normals(reader)?;
    let (models, _materials) =
        tobj::load_obj_buf(&mut std::io::Cursor::new(text), &options, |_| {
            Err(tobj::LoadError::OpenFileFailed)
        })
        .map_err(MeshFileError::Obj)?;
    let mut mesh = TriMesh::default();
    for model in &models {
        let offset = mesh.vertices.len();
        mesh.vertices.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|p| Vec3::new(p[0], p[1], p[2])),
        );
        mesh.triangles
            .extend(model.mesh.indices.chunks_exact(3).map(|t| {
                [
                    offset + t[0] as usize,
                    offset + t[1] as usize,
                    offset + t[2] as usize,
                ]
            }));
    }
    mesh.merge_duplicate_vertices();
    Ok(mesh)
}
