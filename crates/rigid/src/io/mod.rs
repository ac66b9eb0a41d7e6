//! Reading files: triangle meshes (STL, OBJ, COLLADA), the body specs of `rigid mass` (TOML),
//! URDF robots and MuJoCo's MJCF models.

pub mod cases;
pub mod collada;
pub mod mesh_file;
pub mod mjcf;
pub mod spec;
pub mod urdf;
