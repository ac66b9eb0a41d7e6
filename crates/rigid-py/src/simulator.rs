//! `rigid.Simulator`: the time-stepping simulation one step at a time from any state, with an
//! open-loop torque, and the derivatives of that step (`rigid::simulation::Simulator`,
//! `step_derivatives`). Parses, calls the library, prints.

use crate::convert::{value_error, vector};
use crate::model::{Model, ModelCore};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rigid::io::collision::WorldOptions;
use rigid::simulation::{OpenLoop, Scenario, Simulator as RigidSimulator};

/// `(q, v)` as two arrays.
type State<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// One step at a time of the time-stepping scheme with contacts (see the stub).
#[pyclass(name = "Simulator", module = "rigid")]
pub struct Simulator {
    model: Py<Model>,
    sim: RigidSimulator<OpenLoop>,
}

impl Simulator {
    /// `(q, v, tau)` from the model's layout into rigid's, loaded into the simulator.
    fn load(
        &mut self,
        py: Python<'_>,
        func: &str,
        q: &Bound<'_, PyAny>,
        v: &Bound<'_, PyAny>,
        tau: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let model = self.model.borrow(py);
        let core: &ModelCore = &model.inner;
        let (mut qr, mut vr, mut tr) = (Vec::new(), Vec::new(), Vec::new());
        core.q_into(&vector(q, func, "q", "nq", core.nq())?, &mut qr, func, "q")?;
        core.v_into(&vector(v, func, "v", "nv", core.nv())?, &mut vr, func, "v")?;
        core.v_into(
            &vector(tau, func, "tau", "nv", core.nv())?,
            &mut tr,
            func,
            "tau",
        )?;
        // a step that does not continue the last one starts its contacts cold (no warm start,
        // no rebound of an impact from another state)
        if qr != self.sim.q() || vr != self.sim.v() {
            self.sim.forget_contacts();
        }
        self.sim
            .set_state(&qr, &vr)
            .map_err(|e| value_error(func, e))?;
        self.sim.control_mut().0 = tr;
        Ok(())
    }
}

#[pymethods]
impl Simulator {
    #[new]
    #[pyo3(signature = (model, dt = None, ground = None, friction = None, restitution = None, self_collision = false, contact_solver = "pgs", polish = true))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        model: Py<Model>,
        dt: Option<f64>,
        ground: Option<f64>,
        friction: Option<f64>,
        restitution: Option<f64>,
        self_collision: bool,
        contact_solver: &str,
        polish: bool,
    ) -> PyResult<Self> {
        let func = "Simulator";
        let sim = {
            let m = model.borrow(py);
            let core: &ModelCore = &m.inner;
            let options = WorldOptions {
                ground,
                friction,
                restitution,
                self_collision,
            };
            let world = crate::simulation::world(py, func, core, &options)?;
            if world.collision.is_none() {
                return Err(value_error(
                    func,
                    "nothing can touch: give ground=<height> (and collision geometry in the \
                     file), or a model whose file has a floor",
                ));
            }
            let mut scenario = Scenario::in_world(core.model.clone(), world);
            if let Some(dt) = dt {
                scenario.options.dt = dt;
            }
            scenario.contact.solver = contact_solver.parse().map_err(|e| value_error(func, e))?;
            scenario.contact.polish = polish;
            let nv = core.model.nv();
            scenario
                .build_with(OpenLoop(vec![0.0; nv]))
                .map_err(|e| value_error(func, e))?
        };
        Ok(Self { model, sim })
    }

    /// The step (s).
    #[getter]
    fn dt(&self) -> f64 {
        self.sim.options().dt
    }

    fn step<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
    ) -> PyResult<State<'py>> {
        let func = "Simulator.step";
        self.load(py, func, q, v, tau)?;
        self.sim.step().map_err(|e| value_error(func, e))?;
        let model = self.model.borrow(py);
        let core: &ModelCore = &model.inner;
        Ok((core.q_out(py, self.sim.q()), core.v_out(py, self.sim.v())))
    }

    fn step_derivatives<'py>(
        &mut self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
        v: &Bound<'py, PyAny>,
        tau: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let func = "Simulator.step_derivatives";
        if self.model.borrow(py).inner.mujoco_free().is_some() {
            return Err(value_error(
                func,
                "not available in the mujoco layout for a model with a free joint (its velocity \
                 map depends on q); use layout=\"rigid\"",
            ));
        }
        self.load(py, func, q, v, tau)?;
        let d = self
            .sim
            .step_derivatives()
            .map_err(|e| value_error(func, e))?;
        let model = self.model.borrow(py);
        let core: &ModelCore = &model.inner;
        let out = PyDict::new(py);
        out.set_item("dq_dq", core.matrix_out(py, &d.dq_dq))?;
        out.set_item("dq_dv", core.matrix_out(py, &d.dq_dv))?;
        out.set_item("dq_dtau", core.matrix_out(py, &d.dq_dtau))?;
        out.set_item("dv_dq", core.matrix_out(py, &d.dv_dq))?;
        out.set_item("dv_dv", core.matrix_out(py, &d.dv_dv))?;
        out.set_item("dv_dtau", core.matrix_out(py, &d.dv_dtau))?;
        out.set_item("q_next", core.q_out(py, &d.q_next))?;
        out.set_item("v_next", core.v_out(py, &d.v_next))?;
        let modes: Vec<&str> = d.modes.iter().map(|m| m.name()).collect();
        out.set_item("modes", modes)?;
        out.set_item("at_switch", d.at_switch.clone())?;
        out.set_item("held_normal", d.held_normal.clone())?;
        let points: Vec<[f64; 3]> = d
            .contacts
            .iter()
            .map(|c| [c.point.x, c.point.y, c.point.z])
            .collect();
        out.set_item("contact_points", points)?;
        out.set_item("scaled", d.scaled)?;
        Ok(out)
    }
}
