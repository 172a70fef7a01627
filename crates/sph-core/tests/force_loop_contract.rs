//! The public force loop (`physics::forces::fluid_forces`) reaches the batched loop, whose gather
//! reads without bounds checks: arrays that do not fit together must panic before any read,
//! never read out of bounds, in release builds as in debug ones.

use std::panic::{catch_unwind, AssertUnwindSafe};

use sph_core::math::Dim2;
use sph_core::neighbours::{CellGrid, GROUP_FLUID};
use sph_core::physics::forces::{fluid_forces, Fields};
use sph_core::physics::{DIFF_FOURTAKAS, VISC_ARTIFICIAL};
use sph_core::{Kernel, Scene, Solver, WendlandC2};

type V = <Dim2 as sph_core::Dim>::V;

#[test]
fn fluid_forces_refuses_arrays_that_do_not_cover_the_grid() {
    let json = r#"{"dim": 2, "dp": 0.05, "tank": {"min": [0, 0], "max": [1, 1]}, "fluid": [{"min": [0, 0], "max": [0.5, 0.5]}]}"#;
    let solver = Solver::<Dim2, WendlandC2>::new(
        Scene::from_json(json).expect("scene"),
    )
    .expect("solver");
    let c = *solver.constants();
    let p = solver.particles();
    let n = p.pos.len();
    let kernel = WendlandC2::new(c.h, 2);
    // every particle in the fluid group, the lattice sorted as it is (the test needs slots, not
    // physics)
    let mut grid = CellGrid::<Dim2>::new(V::new(-1.0, -1.0), V::new(2.0, 3.0), c.support, 2);
    let (mut perm, mut keys) = (vec![0u32; n], vec![0u32; n]);
    grid.sort_group(GROUP_FLUID, 0..n, &p.pos, &mut perm, &mut keys);
    let pos: Vec<V> = perm.iter().map(|&i| p.pos[i as usize]).collect();
    let vel = vec![V::ZERO; n];
    let rho = vec![c.rho0; n];
    let kind = vec![0u8; n];
    let run = |pos: &[V], vel: &[V], rho: &[f64], kind: &[u8], n_out: usize| {
        let f = Fields {
            pos,
            vel,
            rho,
            kind,
            tau: &[],
            kgc: &[],
            fluid_start: 0,
            split: None,
        };
        let (mut acc, mut drho) = (vec![V::ZERO; n_out], vec![0.0; n_out]);
        catch_unwind(AssertUnwindSafe(|| {
            fluid_forces::<Dim2, _, VISC_ARTIFICIAL, DIFF_FOURTAKAS>(
                &c, &kernel, &grid, f, &mut acc, &mut drho,
            )
        }))
    };
    let short = n - 7;
    assert!(
        run(&pos, &vel, &rho, &kind, n).is_ok(),
        "arrays that fit are accepted"
    );
    assert!(
        run(&pos, &vel[..short], &rho, &kind, short).is_err(),
        "short velocities"
    );
    assert!(
        run(&pos, &vel, &rho[..short], &kind, short).is_err(),
        "short densities"
    );
    assert!(
        run(&pos, &vel, &rho, &kind[..short], short).is_err(),
        "short kinds"
    );
    assert!(
        run(
            &pos[..short],
            &vel[..short],
            &rho[..short],
            &kind[..short],
            short
        )
        .is_err(),
        "the grid's slots beyond the positions"
    );
    assert!(
        run(&pos, &vel, &rho, &kind, n + 1).is_err(),
        "a fluid range beyond the positions"
    );
}
