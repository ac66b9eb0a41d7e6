//! `rigid convert IN OUT [--floating]`: a robot file (URDF, MJCF, or a built-in model) written
//! as MJCF (`OUT.xml`) or URDF (`OUT.urdf`, its meshes in `OUT_meshes/`), with a note for each
//! thing the target cannot express ([`rigid::io::write::save`]).

use crate::load::{load_any, urdf_path, LoadArgs};
use clap::Args;
use rigid::io::write::{save, Format};
use std::path::PathBuf;

/// Arguments of `rigid convert`.
#[derive(Args)]
pub struct ConvertArgs {
    /// The robot to convert: a URDF file, an MJCF file (`.xml`), an SDF file (`.sdf`), or a
    /// built-in model name.
    pub input: String,
    /// The file to write: `.xml` for MJCF, `.urdf` for URDF.
    pub output: PathBuf,
    #[command(flatten)]
    pub load: LoadArgs,
}

/// Runs `rigid convert`: the notes on stderr, one line of summary on stdout.
///
/// # Errors
/// The input cannot be loaded, or as [`save`].
pub fn run(args: &ConvertArgs) -> Result<(), String> {
    let loaded = load_any(&args.input, &args.load)?;
    let source = match (&loaded.mjcf, &loaded.sdf) {
        (Some(m), _) => m.path.clone(),
        (None, Some(s)) => s.path.clone(),
        (None, None) => urdf_path(&args.input),
    };
    let notes = save(&loaded.model, source.as_deref(), &args.output)
        .map_err(|e| format!("{}: {e}", args.input))?;
    for n in &notes {
        eprintln!("note: {n}");
    }
    let m = &loaded.model;
    let format = Format::of_path(&args.output).map_or("", Format::name);
    println!(
        "wrote {} ({format}): {} joints, nq {}, nv {}",
        args.output.display(),
        m.njoints(),
        m.nq(),
        m.nv(),
    );
    Ok(())
}
