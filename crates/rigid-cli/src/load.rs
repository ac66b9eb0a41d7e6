//! Finding a model from the command line: a URDF file or a built-in model name.

use rigid::io::urdf;
use rigid::multibody::{builtin, builtin_names, Model};
use std::path::Path;

/// True when `spec` names a file (or looks like a URDF path) rather than a built-in model.
pub fn is_file(spec: &str) -> bool {
    let p = Path::new(spec);
    p.exists() || spec.ends_with(".urdf") || spec.ends_with(".xml") || spec.contains('/')
}

/// The model named by `spec`: a URDF file, loaded with a free-flyer root if `floating`, or a
/// built-in model.
///
/// # Errors
/// The URDF error (with its file, link or joint and line), an unknown built-in name, or
/// `--floating` asked of a built-in model.
pub fn load_model(spec: &str, floating: bool) -> Result<Model, String> {
    if is_file(spec) {
        return urdf::load_urdf(spec, floating).map_err(|e| format!("{spec}: {e}"));
    }
    let model = builtin(spec).ok_or_else(|| {
        format!(
            "unknown model \"{spec}\": not a file, and not a built-in model ({})",
            builtin_names().join(", ")
        )
    })?;
    if floating {
        return Err(format!(
            "--floating applies to URDF models; the built-in model \"{spec}\" has a fixed base"
        ));
    }
    Ok(model)
}
