//! `rigid model FILE.xml`: the summary of an MJCF model: what MuJoCo's file holds (bodies,
//! joints by type, geoms, sites, equality constraints, tendons, bodies with gravity
//! compensation), the multibody model built from it, and every warning.

use super::{print_model, print_report, ModelArgs};
use rigid::io::mjcf::{load_mjcf, MjcfJointKind};

/// Runs `rigid model` on an MJCF file.
///
/// # Errors
/// The file cannot be read or built (the message names the element and line), or `--floating`.
pub fn run(args: &ModelArgs) -> Result<(), String> {
    let spec = &args.model;
    if args.load.floating {
        return Err(format!(
            "--floating applies to URDF models; the MJCF file \"{spec}\" declares its free joints \
             itself"
        ));
    }
    let m = load_mjcf(spec).map_err(|e| format!("{spec}: {e}"))?;
    let count = |k| m.joints.iter().filter(|j| j.kind == k).count();
    println!(
        "MJCF {spec}: model \"{}\", {} bodies, {} joints ({} free, {} ball, {} hinge, {} slide), \
         {} geoms, {} sites, {} equality constraints, {} tendons",
        m.model.name(),
        m.bodies.len() - 1,
        m.joints.len(),
        count(MjcfJointKind::Free),
        count(MjcfJointKind::Ball),
        count(MjcfJointKind::Hinge),
        count(MjcfJointKind::Slide),
        m.geoms.len(),
        m.sites.len(),
        m.equalities.len(),
        m.tendons.len()
    );
    print_model(&m.model);
    let static_mass: f64 = m
        .bodies
        .iter()
        .filter(|b| b.joint.is_none())
        .map(|b| b.mass)
        .sum();
    if static_mass > 0.0 {
        println!("bodies fixed to the world: {static_mass:.6} kg (not part of the dynamics)");
    }
    for b in m.bodies.iter().filter(|b| b.gravcomp != 0.0) {
        println!(
            "gravity compensation: body \"{}\" (line {}): gravcomp = {} (a passive force in \
             MuJoCo, not in its qfrc_bias nor in rigid's dynamics)",
            b.name, b.line, b.gravcomp
        );
    }
    println!(
        "{} warning(s){}",
        m.warnings.len(),
        if m.warnings.is_empty() { "" } else { ":" }
    );
    for w in &m.warnings {
        println!("  warning: {w}");
    }
    // the bodies MuJoCo declares (not the massless links between the joints of one body)
    let joints = m.model.joints();
    let carriers: Vec<usize> = m
        .bodies
        .iter()
        .filter_map(|b| b.joint.map(|j| j.0))
        .collect();
    let issues: Vec<String> = m
        .model
        .inertia_issues()
        .into_iter()
        .filter(|(j, _)| carriers.contains(&j.0))
        .map(|(j, e)| format!("warning: body of joint \"{}\": {e}", joints[j.0].name))
        .collect();
    print_report(&issues, carriers.len(), "moving bodies");
    Ok(())
}
