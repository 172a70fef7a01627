//! `watersim._core`: a thin PyO3 binding of `sph-core`.
//!
//! It converts (JSON scene in, NumPy views out), releases the GIL around runs and maps the core's
//! errors to Python exceptions. No physics and no validation logic lives here.

use numpy::ndarray::{ArrayView1, ArrayView2};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use std::sync::atomic::Ordering;
use std::sync::{Arc, Mutex, MutexGuard, TryLockError};
use std::time::Duration;

use pyo3::create_exception;
use pyo3::exceptions::{PyKeyboardInterrupt, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use sph_core::{Error, Simulation as CoreSimulation, SnapshotExchange};

create_exception!(_core, SceneError, PyValueError, "A scene field is invalid; the message names the field.");
create_exception!(
    _core,
    InstabilityError,
    PyRuntimeError,
    "The run went unstable. Attributes: kind, step, time, particle, position."
);

fn to_py_err(py: Python<'_>, e: Error) -> PyErr {
    match e {
        Error::InvalidScene { .. } => SceneError::new_err(e.to_string()),
        // the stop flag is only set by `interruptible`, which raises the signal's own exception
        Error::Interrupted { .. } => PyKeyboardInterrupt::new_err(e.to_string()),
        Error::Instability { kind, step, time, particle, ref position, ref message } => {
            let err = InstabilityError::new_err(e.to_string());
            let value = err.value(py);
            let set = || -> PyResult<()> {
                value.setattr("kind", kind.name())?;
                value.setattr("step", step)?;
                value.setattr("time", time)?;
                value.setattr("particle", particle)?;
                value.setattr("position", position.clone())?;
                value.setattr("message", message.clone())?;
                Ok(())
            };
            match set() {
                Ok(()) => err,
                Err(other) => other,
            }
        }
    }
}

/// A WCSPH simulation built from a JSON scene (see `watersim.scenes`).
///
/// Frozen, its core behind a mutex: a call that steps holds the core for its whole length with
/// the GIL released, and a call from another Python thread meanwhile is refused at once
/// (`try_lock`, never a wait that could hold the GIL the stepping thread needs for its signal
/// checks), except `snapshot()`, which the stepping thread answers between two steps.
#[pyclass(module = "watersim._core", frozen)]
struct Simulation {
    inner: Mutex<Box<dyn CoreSimulation>>,
    snapshots: Arc<SnapshotExchange>,
}

type Core<'a> = MutexGuard<'a, Box<dyn CoreSimulation>>;

impl Simulation {
    /// The core, unless another thread is stepping it.
    fn core(&self) -> PyResult<Core<'_>> {
        match self.inner.try_lock() {
            Ok(core) => Ok(core),
            // a panic in an earlier call left the state as a failed step leaves it: readable
            Err(TryLockError::Poisoned(e)) => Ok(e.into_inner()),
            Err(TryLockError::WouldBlock) => Err(PyRuntimeError::new_err(
                "the simulation is stepping on another thread; snapshot() gives a consistent copy of its state meanwhile",
            )),
        }
    }
}

/// Read-only NumPy view of memory owned by the `Simulation` object `owner`.
///
/// Sound because the core allocates its particle arrays once and never reallocates them, and the
/// view keeps `owner` alive. The contents change with every step, and a step on another thread
/// writes them while the view is read (documented in the stub: `snapshot()` copies instead).
fn view_2d<'py>(owner: &Bound<'py, Simulation>, data: &[f64], dim: usize) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let view = ArrayView2::from_shape((data.len() / dim, dim), data)
        .map_err(|e| PyRuntimeError::new_err(format!("bad array shape: {e}")))?;
    // SAFETY: see the function's doc comment.
    let arr = unsafe { PyArray2::borrow_from_array(&view, owner.clone().into_any()) };
    arr.call_method1("setflags", ((), (), false))?;
    Ok(arr)
}

fn view_1d<'py, T: numpy::Element>(owner: &Bound<'py, Simulation>, data: &[T]) -> PyResult<Bound<'py, PyArray1<T>>> {
    let view = ArrayView1::from(data);
    // SAFETY: as in `view_2d`.
    let arr = unsafe { PyArray1::borrow_from_array(&view, owner.clone().into_any()) };
    arr.call_method1("setflags", ((), (), false))?;
    Ok(arr)
}

/// How often the calling thread looks for a pending signal while the core steps.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs `work` on the core with the GIL released, on a thread of its own, while the calling
/// thread (Python's main thread, the one that runs signal handlers) looks for pending signals
/// every [`SIGNAL_POLL`]. A handler that raises (Ctrl-C's KeyboardInterrupt, the CLI's SIGTERM)
/// sets the core's stop flag: the core stops before its next step, within one step of the
/// signal, and the handler's exception is raised with the state whole after that step (a
/// checkpoint of it resumes the run bit for bit).
fn interruptible<W>(py: Python<'_>, inner: &mut Box<dyn CoreSimulation>, work: W) -> PyResult<()>
where
    W: FnOnce(&mut dyn CoreSimulation) -> Result<(), Error> + Send,
{
    let stop = inner.stop_flag();
    stop.store(false, Ordering::Relaxed);
    let caller = std::thread::current();
    let (result, signal) = py.detach(|| {
        std::thread::scope(|scope| {
            let worker = scope.spawn(|| {
                let result = work(inner.as_mut());
                caller.unpark();
                result
            });
            let mut signal = Ok(());
            while !worker.is_finished() {
                std::thread::park_timeout(SIGNAL_POLL);
                if signal.is_ok() && !worker.is_finished() {
                    signal = Python::attach(|py| py.check_signals());
                    if signal.is_err() {
                        stop.store(true, Ordering::Relaxed);
                    }
                }
            }
            let result = worker.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (result, signal)
        })
    });
    stop.store(false, Ordering::Relaxed);
    signal?;
    result.map_err(|e| to_py_err(py, e))
}

#[pymethods]
impl Simulation {
    #[new]
    fn new(py: Python<'_>, scene_json: &str) -> PyResult<Self> {
        let inner = py.detach(|| sph_core::build_from_json(scene_json)).map_err(|e| to_py_err(py, e))?;
        let snapshots = inner.snapshot_exchange();
        Ok(Self { inner: Mutex::new(inner), snapshots })
    }

    #[getter]
    fn dim(&self) -> PyResult<usize> {
        Ok(self.core()?.dim())
    }
    #[getter]
    fn n_particles(&self) -> PyResult<usize> {
        Ok(self.core()?.n_particles())
    }
    #[getter]
    fn n_fluid(&self) -> PyResult<usize> {
        Ok(self.core()?.n_fluid())
    }
    #[getter]
    fn n_boundary(&self) -> PyResult<usize> {
        let core = self.core()?;
        Ok(core.n_particles() - core.n_fluid())
    }
    /// Simulated time [s].
    #[getter]
    fn time(&self) -> PyResult<f64> {
        Ok(self.core()?.time())
    }
    #[getter]
    fn steps(&self) -> PyResult<u64> {
        Ok(self.core()?.steps())
    }
    /// Last time step [s].
    #[getter]
    fn dt(&self) -> PyResult<f64> {
        Ok(self.core()?.dt())
    }

    /// Advances `n` steps (the GIL is released): on rayon's global pool, or with `threads` on
    /// a pool of that many threads (built once, then reused).
    #[pyo3(signature = (n = 1, threads = None))]
    fn step(&self, py: Python<'_>, n: u64, threads: Option<usize>) -> PyResult<()> {
        let mut core = self.core()?;
        match threads {
            None => interruptible(py, &mut core, |inner| inner.step(n)),
            Some(t) => interruptible(py, &mut core, |inner| sph_core::on_threads(t, || inner.step(n)).and_then(|r| r)),
        }
    }

    /// Advances until `time >= until` [s] (the GIL is released).
    fn run(&self, py: Python<'_>, until: f64) -> PyResult<()> {
        let mut core = self.core()?;
        interruptible(py, &mut core, |inner| inner.run_until(until))
    }

    /// Copies of the state at one instant: a dict of `time`, `steps`, `dt`, `n_excluded` and
    /// NumPy arrays `positions`, `velocities` (N, dim), `densities`, `kinds`, `ids` (N,), in
    /// storage order. Callable from any thread: while another thread steps this simulation,
    /// the stepping thread makes the copies between two steps (the GIL is released meanwhile).
    fn snapshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let snapshot = loop {
            match self.inner.try_lock() {
                Ok(core) => break core.snapshot(),
                Err(TryLockError::Poisoned(e)) => break e.into_inner().snapshot(),
                Err(TryLockError::WouldBlock) => {
                    let exchange = &self.snapshots;
                    if let Some(s) = py.detach(|| exchange.request(SIGNAL_POLL)) {
                        break s;
                    }
                    // not answered: the other thread is between two calls or in a long step
                    py.check_signals()?;
                }
            }
        };
        let n = snapshot.densities.len();
        let dim = snapshot.positions.len().checked_div(n).unwrap_or(1);
        let d = PyDict::new(py);
        d.set_item("time", snapshot.time)?;
        d.set_item("steps", snapshot.steps)?;
        d.set_item("dt", snapshot.dt)?;
        d.set_item("n_excluded", snapshot.n_excluded)?;
        d.set_item("positions", PyArray1::from_vec(py, snapshot.positions).reshape([n, dim])?)?;
        d.set_item("velocities", PyArray1::from_vec(py, snapshot.velocities).reshape([n, dim])?)?;
        d.set_item("densities", PyArray1::from_vec(py, snapshot.densities))?;
        d.set_item("kinds", PyArray1::from_vec(py, snapshot.kinds))?;
        d.set_item("ids", PyArray1::from_vec(py, snapshot.ids))?;
        Ok(d)
    }

    #[getter]
    fn positions<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let core = slf.get().core()?;
        view_2d(slf, core.positions(), core.dim())
    }
    #[getter]
    fn velocities<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let core = slf.get().core()?;
        view_2d(slf, core.velocities(), core.dim())
    }
    #[getter]
    fn densities<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        view_1d(slf, slf.get().core()?.densities())
    }
    #[getter]
    fn pressures<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        // computed from the densities on each access (the core does not store pressure)
        Ok(PyArray1::from_vec(slf.py(), slf.get().core()?.pressures()))
    }
    #[getter]
    fn kinds<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<u8>>> {
        view_1d(slf, slf.get().core()?.kinds())
    }
    #[getter]
    fn ids<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyArray1<u32>>> {
        view_1d(slf, slf.get().core()?.ids())
    }

    /// Bytes of the solver's own arrays.
    fn memory_bytes(&self) -> PyResult<usize> {
        Ok(self.core()?.memory_bytes())
    }

    /// Fluid pairs within the support at the present positions (one force evaluation's work).
    fn fluid_pairs(&self, py: Python<'_>) -> PyResult<u64> {
        let core = self.core()?;
        let inner = &**core;
        Ok(py.detach(|| inner.fluid_pairs()))
    }

    /// Fluid force evaluations per step (2 Symplectic, 1 Verlet).
    fn force_evaluations_per_step(&self) -> PyResult<u32> {
        Ok(self.core()?.force_evaluations_per_step())
    }

    /// Derived parameters (h, c0, mass, ...) as a dict.
    fn params<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let params = self.core()?.params();
        to_python(py, &params)
    }

    /// Shepard-normalised interpolation of fluid fields at `points` (M, dim):
    /// dict of `kernel_sum`, `density`, `pressure` (M,) and `velocity` (M, dim).
    fn interpolate<'py>(
        &self,
        py: Python<'py>,
        points: numpy::PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let core = self.core()?;
        let dim = core.dim();
        let arr = points.as_array();
        if arr.ncols() != dim {
            return Err(SceneError::new_err(format!("points: must have shape (M, {dim}), got {:?}", arr.shape())));
        }
        let flat: Vec<f64> = arr.iter().copied().collect();
        let inner = &**core;
        let out = py.detach(|| inner.interpolate(&flat)).map_err(|e| to_py_err(py, e))?;
        let m = out.kernel_sum.len();
        let d = PyDict::new(py);
        d.set_item("kernel_sum", PyArray1::from_vec(py, out.kernel_sum))?;
        d.set_item("density", PyArray1::from_vec(py, out.density))?;
        d.set_item("pressure", PyArray1::from_vec(py, out.pressure))?;
        d.set_item("velocity", PyArray1::from_vec(py, out.velocity).reshape([m, dim])?)?;
        Ok(d)
    }

    /// Gauge records: a list of dicts with `name`, `type`, `t` (n,) and one array per column
    /// the gauge declares (`GaugeSpec::columns`), (n,) for a gauge on a line (`z` of elevation
    /// and run-up) or (n, points) with `points` (points, dim) for a gauge at points (`velocity`
    /// and `kernel_sum` of velocity probes and windows); a column of several components gains
    /// a last axis (`velocity` (n, points, dim)). Windows also give `shape`, the grid counts per
    /// axis, x fastest.
    fn gauges<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let core = self.core()?;
        let dim = core.dim();
        let mut out = Vec::new();
        for g in core.gauges() {
            let d = PyDict::new(py);
            d.set_item("name", &g.name)?;
            d.set_item("type", g.kind)?;
            let n = g.t.len();
            d.set_item("t", PyArray1::from_slice(py, &g.t))?;
            let m = g.points.len() / dim;
            let stride: usize = g.columns.iter().map(|c| c.size).sum();
            let mut offset = 0;
            for col in &g.columns {
                let mut values = Vec::with_capacity(n * m.max(1) * col.size);
                for point in g.values.chunks_exact(stride) {
                    values.extend_from_slice(&point[offset..offset + col.size]);
                }
                let mut shape = vec![n];
                if m > 0 {
                    shape.push(m);
                }
                if col.size > 1 {
                    shape.push(col.size);
                }
                d.set_item(col.name, PyArray1::from_vec(py, values).reshape(shape)?)?;
                offset += col.size;
            }
            if m > 0 {
                d.set_item("points", PyArray1::from_slice(py, &g.points).reshape([m, dim])?)?;
            }
            if !g.shape.is_empty() {
                d.set_item("shape", g.shape.clone())?;
            }
            out.push(d);
        }
        Ok(out)
    }

    /// Fluid particles excluded after leaving the domain.
    #[getter]
    fn n_excluded(&self) -> PyResult<usize> {
        Ok(self.core()?.n_excluded())
    }

    /// The full state needed to continue this run exactly, as a dict of NumPy arrays and
    /// scalars (see `watersim.Simulation.save_checkpoint`).
    fn checkpoint<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let c = self.core()?.checkpoint();
        let d = PyDict::new(py);
        d.set_item("time", c.time)?;
        d.set_item("steps", c.steps)?;
        d.set_item("dt", c.dt)?;
        d.set_item("positions", PyArray1::from_vec(py, c.positions))?;
        d.set_item("velocities", PyArray1::from_vec(py, c.velocities))?;
        d.set_item("densities", PyArray1::from_vec(py, c.densities))?;
        d.set_item("ids", PyArray1::from_vec(py, c.ids))?;
        d.set_item("kinds", PyArray1::from_vec(py, c.kinds))?;
        d.set_item("velocities_prev", PyArray1::from_vec(py, c.velocities_prev))?;
        d.set_item("densities_prev", PyArray1::from_vec(py, c.densities_prev))?;
        d.set_item("n_excluded", c.n_excluded)?;
        d.set_item("energy0", (c.energy0.0, c.energy0.1))?;
        let gauges = PyList::empty(py);
        for g in &c.gauges {
            let gd = PyDict::new(py);
            gd.set_item("t", PyArray1::from_slice(py, &g.t))?;
            gd.set_item("values", PyArray1::from_slice(py, &g.values))?;
            gd.set_item("next_time", g.next_time)?;
            if !g.crossings.past.is_empty() {
                gd.set_item("crossings_past", PyArray1::from_slice(py, &g.crossings.past))?;
                gd.set_item("crossings_net", g.crossings.net)?;
            }
            gauges.append(gd)?;
        }
        d.set_item("gauges", gauges)?;
        d.set_item("paddle_correction", c.paddle_correction)?;
        Ok(d)
    }

    /// Continues from `checkpoint()` of a run of the same scene.
    fn restore(&self, py: Python<'_>, checkpoint: &Bound<'_, PyDict>) -> PyResult<()> {
        fn item<'py, T: FromPyObjectOwned<'py>>(d: &Bound<'py, PyDict>, key: &str) -> PyResult<T> {
            let v = d.get_item(key)?.ok_or_else(|| SceneError::new_err(format!("checkpoint.{key}: missing")))?;
            v.extract::<T>().map_err(Into::into).map_err(|e: PyErr| SceneError::new_err(format!("checkpoint.{key}: {e}")))
        }
        let mut core = self.core()?;
        let mut c = core.checkpoint();
        c.time = item(checkpoint, "time")?;
        c.steps = item(checkpoint, "steps")?;
        c.dt = item(checkpoint, "dt")?;
        c.positions = item(checkpoint, "positions")?;
        c.velocities = item(checkpoint, "velocities")?;
        c.densities = item(checkpoint, "densities")?;
        c.ids = item(checkpoint, "ids")?;
        c.kinds = item(checkpoint, "kinds")?;
        c.velocities_prev = item(checkpoint, "velocities_prev")?;
        c.densities_prev = item(checkpoint, "densities_prev")?;
        c.n_excluded = item(checkpoint, "n_excluded")?;
        c.energy0 = item(checkpoint, "energy0")?;
        let gauges: Vec<Bound<'_, PyDict>> = item(checkpoint, "gauges")?;
        if gauges.len() != c.gauges.len() {
            return Err(SceneError::new_err(format!(
                "checkpoint.gauges: has {} gauges, this scene has {}",
                gauges.len(),
                c.gauges.len()
            )));
        }
        for (rec, gd) in c.gauges.iter_mut().zip(&gauges) {
            rec.t = item(gd, "t")?;
            rec.values = item(gd, "values")?;
            rec.next_time = item(gd, "next_time")?;
            // an overtopping gauge's sides, once it has sampled
            if gd.contains("crossings_past")? {
                rec.crossings.past = item(gd, "crossings_past")?;
                rec.crossings.net = item(gd, "crossings_net")?;
            }
        }
        c.paddle_correction = match checkpoint.get_item("paddle_correction")? {
            Some(v) if !v.is_none() => Some(item(checkpoint, "paddle_correction")?),
            _ => None,
        };
        core.restore(&c).map_err(|e| to_py_err(py, e))
    }

    fn __repr__(&self) -> PyResult<String> {
        let core = self.core()?;
        let p = core.params();
        Ok(format!(
            "Simulation(dim={}, n_particles={}, n_fluid={}, kernel={}, viscosity={}, diffusion={}, t={:.4} s, steps={})",
            p.dim,
            core.n_particles(),
            core.n_fluid(),
            p.kernel,
            p.viscosity,
            p.diffusion,
            core.time(),
            core.steps()
        ))
    }
}

/// The scene as the core runs it: parsed, checked (raising `SceneError` naming the field) and
/// returned as JSON with every default filled in.
#[pyfunction]
fn resolve_scene(py: Python<'_>, scene_json: &str) -> PyResult<String> {
    sph_core::Scene::from_json(scene_json).map(|s| s.to_json()).map_err(|e| to_py_err(py, e))
}

/// The core's default of every optional scene key, as nested dicts laid out as the scene
/// (`scene_defaults()["viscosity"]["nu"]` is the default of `viscosity.nu`).
#[pyfunction]
fn scene_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    to_python(py, &sph_core::scene::Defaults::default())
}

/// A serde value as Python objects (dicts, lists, floats, ints, strings, None), through JSON:
/// floats keep every bit (shortest round-trip digits both ways).
fn to_python<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyRuntimeError::new_err(format!("serialising: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Simulation>()?;
    m.add_function(wrap_pyfunction!(resolve_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene_defaults, m)?)?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("InstabilityError", m.py().get_type::<InstabilityError>())?;
    Ok(())
}
