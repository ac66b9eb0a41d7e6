//! Reading files: closed triangle meshes (STL, OBJ) and the body specs of `rigid mass` (TOML).

pub mod mesh_file;
pub mod spec;
