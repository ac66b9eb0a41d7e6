//! Reading files: triangle meshes (STL, OBJ, COLLADA), the body specs of `rigid mass` (TOML) and
//! URDF robots.

pub mod cases;
pub mod collada;
pub mod constraints;
pub mod mesh_file;
pub mod spec;
pub mod urdf;
