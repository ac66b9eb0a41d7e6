//! The robot simulator's `--plot` figure: joint angles, joint velocities, torques and total
//! energy against time (one panel each), and with contacts their normal force and the energy
//! they took.

use crate::plotting::{color, save, Panel};
use plotters::style::BLACK;
use rigid::multibody::Model;
use std::path::Path;

/// Decimated time series of the 1-dof joints (and the energy).
pub struct Samples {
    names: Vec<String>,
    /// `(index in q, index in v)` of each 1-dof joint.
    dofs: Vec<(usize, usize)>,
    t: Vec<f64>,
    q: Vec<Vec<f64>>,
    v: Vec<Vec<f64>>,
    tau: Vec<Vec<f64>>,
    energy: Vec<f64>,
    /// With contacts: the sum of their normal forces (N) and the kinetic energy they took (J).
    normal: Vec<f64>,
    taken: Vec<f64>,
}

impl Samples {
    /// Empty series for the 1-dof joints of `model`.
    pub fn new(model: &Model) -> Self {
        let joints: Vec<_> = model
            .joints()
            .iter()
            .filter(|j| j.nq == 1 && j.nv == 1)
            .collect();
        let n = joints.len();
        Self {
            names: joints.iter().map(|j| j.name.clone()).collect(),
            dofs: joints.iter().map(|j| (j.idx_q, j.idx_v)).collect(),
            t: Vec::new(),
            q: vec![Vec::new(); n],
            v: vec![Vec::new(); n],
            tau: vec![Vec::new(); n],
            energy: Vec::new(),
            normal: Vec::new(),
            taken: Vec::new(),
        }
    }

    /// Records one state; `contact` is `(normal force sum, energy taken by the contacts so far)`
    /// when there are contacts.
    pub fn push(
        &mut self,
        t: f64,
        q: &[f64],
        v: &[f64],
        tau: &[f64],
        energy: f64,
        contact: Option<(f64, f64)>,
    ) {
        if let Some((normal, taken)) = contact {
            self.normal.push(normal);
            self.taken.push(taken);
        }
        self.t.push(t);
        for (k, &(iq, iv)) in self.dofs.iter().enumerate() {
            self.q[k].push(q[iq]);
            self.v[k].push(v[iv]);
            self.tau[k].push(tau[iv]);
        }
        self.energy.push(energy);
    }

    fn curves(&self, x: &[Vec<f64>]) -> Vec<(String, Vec<f64>, plotters::style::RGBColor)> {
        x.iter()
            .enumerate()
            .map(|(k, y)| (self.names[k].clone(), y.clone(), color(k)))
            .collect()
    }

    /// Draws the panels into `path` (SVG or PNG).
    pub fn draw(&self, path: &Path) -> Result<(), String> {
        let mut panels = Vec::new();
        // a model without 1-dof joints (a free body) has no joint panels
        if !self.names.is_empty() {
            panels.extend([
                Panel {
                    title: "joint positions (1-dof joints)".into(),
                    y_label: "q (rad or m)".into(),
                    curves: self.curves(&self.q),
                },
                Panel {
                    title: "joint velocities".into(),
                    y_label: "v (rad/s or m/s)".into(),
                    curves: self.curves(&self.v),
                },
                Panel {
                    title: "control torques".into(),
                    y_label: "τ (N·m or N)".into(),
                    curves: self.curves(&self.tau),
                },
            ]);
        }
        if self.normal.len() == self.t.len() && !self.t.is_empty() {
            // the kinetic energy the contact impulses took, cumulative (J, never decreasing):
            // without control K + U falls by it, but for the time stepping's O(h) (at rest each
            // step's free velocity, −g h, is taken again)
            panels.push(Panel {
                title: "energy: K + U, and the energy the contacts took since the start".into(),
                y_label: "E (J)".into(),
                curves: vec![
                    ("K + U".into(), self.energy.clone(), BLACK),
                    ("taken by contacts".into(), self.taken.clone(), color(1)),
                ],
            });
            panels.push(Panel {
                title: "contacts: sum of the normal forces".into(),
                y_label: "N".into(),
                curves: vec![(String::new(), self.normal.clone(), color(0))],
            });
        } else {
            panels.push(Panel {
                title: "total energy K + U".into(),
                y_label: "E (J)".into(),
                curves: vec![(String::new(), self.energy.clone(), BLACK)],
            });
        }
        save(path, &self.t, &panels)
    }
}
