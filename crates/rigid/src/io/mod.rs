//! Reading files: closed triangle meshes (STL, OBJ), the body specs of `rigid mass` (TOML) and
//! URDF robots.

pub mod mesh_file;
pub mod spec;
pub mod urdf;
