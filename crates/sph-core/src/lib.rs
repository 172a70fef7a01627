//! WaterSim's weakly compressible SPH core.
//!
//! A [`Scene`] (plain serde data) is checked and turned by [`build`] into a solver specialised at
//! compile time for its dimension, kernel, viscosity model and density diffusion (DESIGN.md
//! section 5): terms a scene does not enable cost no arithmetic in the hot loop and no memory.
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
pub use kernel::{CubicSpline, Kernel, KernelKind, WendlandC2};
pub use math::{Dim, Dim2, Dim3, Real};
pub use motion::{MotionLaw, Paddle, PaddleKind};
pub use probes::{GaugeRecord, GaugeSpec, SurfaceMethod};
pub use scene::{Damping, Diffusion, Integrator, Obstacle, Scene, Viscosity};
pub use simulation::{Checkpoint, Interpolated, Params, Simulation, Snapshot, SnapshotExchange, Solver};
pub use threads::on_threads;

use physics::{diff_code, visc_code, DIFF_FOURTAKAS, DIFF_MOLTENI, DIFF_NONE, VISC_ARTIFICIAL, VISC_LAMINAR, VISC_LAMINAR_SPS};

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
    }
}

fn build_kernel<D: Dim, K: Kernel>(scene: Scene) -> Result<Box<dyn Simulation>> {
    macro_rules! solver {
        ($v:expr, $d:expr) => {
            Ok(Box::new(Solver::<D, K, { $v }, { $d }>::new(scene)?))
        };
    }
    match (visc_code(&scene.viscosity), diff_code(&scene.diffusion)) {
        (VISC_ARTIFICIAL, DIFF_NONE) => solver!(VISC_ARTIFICIAL, DIFF_NONE),
        (VISC_ARTIFICIAL, DIFF_MOLTENI) => solver!(VISC_ARTIFICIAL, DIFF_MOLTENI),
        (VISC_ARTIFICIAL, DIFF_FOURTAKAS) => solver!(VISC_ARTIFICIAL, DIFF_FOURTAKAS),
        (VISC_LAMINAR, DIFF_NONE) => solver!(VISC_LAMINAR, DIFF_NONE),
        (VISC_LAMINAR, DIFF_MOLTENI) => solver!(VISC_LAMINAR, DIFF_MOLTENI),
        (VISC_LAMINAR, DIFF_FOURTAKAS) => solver!(VISC_LAMINAR, DIFF_FOURTAKAS),
        (VISC_LAMINAR_SPS, DIFF_NONE) => solver!(VISC_LAMINAR_SPS, DIFF_NONE),
        (VISC_LAMINAR_SPS, DIFF_MOLTENI) => solver!(VISC_LAMINAR_SPS, DIFF_MOLTENI),
        (_, _) => solver!(VISC_LAMINAR_SPS, DIFF_FOURTAKAS),
    }
}
