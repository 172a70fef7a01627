//! WaterSim's weakly compressible SPH core.
//!
//! A [`Scene`] (plain serde data) is checked and turned by [`build`] into a solver specialised at
//! compile time for its dimension and kernel, whose fluid force loop is specialised for its
//! viscosity model and density diffusion (DESIGN.md section 5): terms a scene does not enable
//! cost no arithmetic in the hot loop and no memory.
//! The solver is driven through the object-safe [`Simulation`] trait.

pub mod absorption;
pub mod boundary;
mod diagnostics;
pub mod error;
pub mod geometry;
pub mod kernel;
pub mod math;
pub mod motion;
pub mod neighbours;
pub mod particles;
pub mod phases;
pub mod physics;
pub mod probes;
pub mod scene;
pub mod simulation;
pub mod threads;

pub use error::{Error, InstabilityKind, Result};
pub use kernel::{CubicSpline, Kernel, KernelKind, WendlandC2, WendlandC4};
pub use math::{Dim, Dim2, Dim3, Real};
pub use motion::{MotionLaw, Paddle, PaddleKind};
pub use probes::{GaugeRecord, GaugeSpec, RunupMethod, SurfaceMethod};
pub use scene::{Damping, Diffusion, Integrator, Obstacle, Scene, Viscosity};
pub use simulation::{Checkpoint, Interpolated, Params, Simulation, Snapshot, SnapshotExchange, Solver};
pub use threads::on_threads;

/// Builds the solver specialised for the scene's options.
pub fn build(scene: Scene) -> Result<Box<dyn Simulation>> {
    scene.validate()?;
    match scene.dim {
        2 => build_dim::<Dim2>(scene),
        _ => build_dim::<Dim3>(scene),
    }
}

/// Parses a JSON scene and builds its solver.
pub fn build_from_json(text: &str) -> Result<Box<dyn Simulation>> {
    build(Scene::from_json(text)?)
}

fn build_dim<D: Dim>(scene: Scene) -> Result<Box<dyn Simulation>> {
    match scene.kernel {
        KernelKind::CubicSpline => build_kernel::<D, CubicSpline>(scene),
        KernelKind::Wendland => build_kernel::<D, WendlandC2>(scene),
        KernelKind::WendlandC4 => build_kernel::<D, WendlandC4>(scene),
    }
}

fn build_kernel<D: Dim, K: Kernel>(scene: Scene) -> Result<Box<dyn Simulation>> {
    Ok(Box::new(Solver::<D, K>::new(scene)?))
}
