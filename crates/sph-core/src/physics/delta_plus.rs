//! The delta-plus-SPH particle shifting (Sun, Colagrossi, Marrone & Zhang 2017, Comput. Methods
//! Appl. Mech. Engrg. 315, 25-49, section 2.3, Eqs. 14-17): each fluid particle's shift
//! direction, with the free surface found and the shift's normal part removed near it. The
//! scene option is [`crate::scene::Shifting`] with `model = "delta_plus"`; the sweep
//! (`simulation/advance.rs`) scales the direction by `-A h U_max dt`.

use rayon::prelude::*;

use super::forces::{for_each_pair, Fields};
use super::{Constants, NEIGHBOUR_TASK};
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUPS, GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::particles::KIND_EXCLUDED;

/// At or below this smallest eigenvalue of the renormalisation matrix a particle is taken to be
/// on the free surface and is not shifted. The eigenvalue is about 0.5 on a flat surface and 1
/// in the bulk; Marrone et al. (2010) take the particles below 0.2 as surely on the surface and
/// test those up to 0.75 further with a scan region along the normal; without that test every
/// particle up to 0.75 counts as on it (an inner particle counted so loses only its own shift
/// and makes its neighbours' tangential: never a push across the surface).
pub const LAMBDA_SURFACE: Real = 0.75;
/// `R` and `n` of the anti-clustering factor `1 + R (W_ab / W(dp))^n` (Sun et al. 2017 after
/// Monaghan 2000), which pushes apart pairs closer than dp.
pub const ANTI_CLUSTER_R: Real = 0.2;
pub const ANTI_CLUSTER_N: i32 = 4;

/// The shift direction `s_a` of each fluid particle (the sweep moves it by `-A h U_max dt s_a`)
/// and the smallest eigenvalue `lambda_a` of its renormalisation matrix
/// `B_a = sum_b (r_b - r_a) (x) grad_a W_ab V_b`, over wall and fluid neighbours in the grid's
/// fixed order (walls, paddle, fluid); returns `U_max`, the largest fluid speed (a maximum:
/// the same for any thread count). `normal` is scratch of the same length as `dir`.
///
/// Sun et al. (2017) Eq. 17 with `g_a = sum_b [1 + R (W_ab/W(dp))^n] grad_a W_ab V_b`:
/// - on the free surface (`lambda_a <= LAMBDA_SURFACE`): `s_a = 0`;
/// - near it (a surface particle within the kernel support, whose truncated kernel makes
///   `g_a` point out of the water): `s_a = (I - n n) g_a`, the part along the surface;
/// - inside the water: `s_a = g_a`.
///
/// The normal `n` near the surface is the surface's: the direction of
/// `sum_{b on the surface} W_ab grad C_b` (`grad C_b = sum_c grad_b W_bc V_c`, which points into
/// the water at the surface; Marrone et al. 2010). Sun et al. take each particle's own
/// `B_a^-1 grad C_a`, which a kernel support below the surface no longer sees the surface in:
/// there a particle's own displacement sets its `grad C`, and removing that direction removed
/// the very shift that would restore it.
///
/// Near a wall (fixed or moving) the part of the move towards the wall is dropped (see below).
///
/// Two passes: the first forms `g`, `grad C` (in `normal`) and `lambda`, the second the
/// surface's normal from the first's `lambda` and `grad C`, and the walls' direction. Excluded
/// particles get zeros.
pub fn delta_plus_fields<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    dir: &mut [D::V],
    normal: &mut [D::V],
    lambda: &mut [Real],
) -> Real {
    let support2 = c.support * c.support;
    let inv_w_dp = 1.0 / kernel.w(c.dp);
    let u_max = dir
        .par_iter_mut()
        .zip(normal.par_iter_mut())
        .zip(lambda.par_iter_mut())
        .enumerate()
        .with_max_len(NEIGHBOUR_TASK)
        .map(|(i, ((dir_a, normal_a), lambda_a))| {
            let a = f.fluid_start + i;
            *dir_a = D::V::ZERO;
            *normal_a = D::V::ZERO;
            // an excluded particle has left the domain: it is not shifted
            *lambda_a = 0.0;
            if f.kind[a] == KIND_EXCLUDED {
                return 0.0;
            }
            let pa = f.pos[a];
            let (mut grad_c, mut g) = (D::V::ZERO, D::V::ZERO);
            let mut b = D::Sym::default();
            for group in 0..GROUPS {
                for_each_pair(grid, support2, group, f.pos, pa, |nb, r, _, dist| {
                    // V_b grad_a W_ab = r_ab V_b F(r)
                    let vf = c.mass / f.rho[nb] * kernel.grad_factor(dist);
                    let gw = r * vf;
                    grad_c += gw;
                    g += gw
                        * (1.0 + ANTI_CLUSTER_R * (kernel.w(dist) * inv_w_dp).powi(ANTI_CLUSTER_N));
                    // (r_b - r_a) (x) r_ab V_b F = -F V_b r_ab (x) r_ab
                    D::sym_add_outer(&mut b, r, r, -vf);
                });
            }
            let lam = D::sym_min_eigenvalue(&b);
            *lambda_a = lam;
            *normal_a = grad_c;
            if lam > LAMBDA_SURFACE {
                *dir_a = g;
            }
            f.vel[a].length()
        })
        .reduce(|| 0.0, Real::max);
    let (lambda, grad_c): (&[Real], &[D::V]) = (lambda, normal);
    dir.par_iter_mut().enumerate().with_max_len(NEIGHBOUR_TASK).for_each(|(i, dir_a)| {
        if lambda[i] <= LAMBDA_SURFACE {
            return; // on the surface (or excluded): already zero
        }
        let (a, mut n, mut towards_walls) = (f.fluid_start + i, D::V::ZERO, D::V::ZERO);
        let pa = f.pos[a];
        for_each_pair(grid, support2, GROUP_FLUID, f.pos, pa, |nb, _, _, dist| {
            let b = nb - f.fluid_start;
            if lambda[b] <= LAMBDA_SURFACE {
                n += grad_c[b] * kernel.w(dist);
            }
        });
        for group in [GROUP_FIXED, GROUP_MOVING] {
            for_each_pair(grid, support2, group, f.pos, pa, |_, r, _, dist| {
                towards_walls += r * kernel.grad_factor(dist);
            });
        }
        let n2 = n.length_squared();
        if n2 > 0.0 {
            // (I - n n) g with n = m / |m|: the sign of the normal does not matter
            *dir_a -= n * (n.dot(*dir_a) / n2);
        }
        // The move is along -s_a; its part towards the walls (the walls' share of grad C points
        // at them) is dropped: a shift never pushes a particle into a wall where the walls'
        // lattice and the fluid's meet (flume2d-long at H/dp 5 lost fluid through the bed at
        // t = 8.1 s without this, docs/physics-options.md).
        let w2 = towards_walls.length_squared();
        let into = dir_a.dot(towards_walls);
        if w2 > 0.0 && into < 0.0 {
            *dir_a -= towards_walls * (into / w2);
        }
    });
    u_max
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::WendlandC2;
    use crate::math::Dim2;
    use crate::scene::Scene;
    use glam::DVec2;

    /// A 2D lattice block of water 20 x 12 dp, one particle displaced: the bulk's eigenvalue is
    /// 1, the surface row's about 0.5 and a corner's less, neither shifted; the rows within the
    /// kernel support below the surface, whose truncated kernel pushes them out of the water,
    /// keep no shift across it; the displaced particle is pushed back towards its site.
    #[test]
    fn lattice_surface_and_bulk() {
        let scene = Scene::from_json(
            r#"{"dim": 2, "dp": 0.01, "coefh": 1.5, "tank": {"min": [0, 0], "max": [1, 1]}, "fluid": [{"min": [0, 0], "max": [0.2, 0.12]}]}"#,
        )
        .expect("scene");
        let c = Constants::new(&scene);
        let kernel = WendlandC2::new(c.h, 2);
        let (nx, ny) = (20, 12);
        let mut pos: Vec<DVec2> = (0..nx * ny)
            .map(|k| DVec2::new((k % nx) as Real + 0.5, (k / nx) as Real + 0.5) * c.dp)
            .collect();
        let moved = 5 * nx + 10;
        pos[moved].x += 0.2 * c.dp;
        let mut vel = vec![DVec2::ZERO; pos.len()];
        vel[3] = DVec2::new(0.0, 0.25);
        let rho = vec![c.rho0; pos.len()];
        let kind = vec![crate::particles::KIND_FLUID; pos.len()];
        let mut grid = CellGrid::<Dim2>::new(DVec2::splat(-0.1), DVec2::splat(0.5), c.support, 2);
        let (mut perm, mut keys) = (vec![0u32; pos.len()], vec![0u32; pos.len()]);
        grid.sort_group(
            crate::neighbours::GROUP_FLUID,
            0..pos.len(),
            &pos,
            &mut perm,
            &mut keys,
        );
        let sorted = |v: &Vec<DVec2>| perm.iter().map(|&k| v[k as usize]).collect::<Vec<_>>();
        let (pos, vel) = (sorted(&pos), sorted(&vel));
        let slot_of = |k: usize| perm.iter().position(|&p| p as usize == k).expect("slot");
        let f = Fields::<Dim2> {
            pos: &pos,
            vel: &vel,
            rho: &rho,
            kind: &kind,
            tau: &[],
            kgc: &[],
            fluid_start: 0,
            split: None,
        };
        let (mut dir, mut normal) = (vec![DVec2::ZERO; pos.len()], vec![DVec2::ZERO; pos.len()]);
        let mut lambda = vec![0.0; pos.len()];
        let u_max = delta_plus_fields(&c, &kernel, &grid, f, &mut dir, &mut normal, &mut lambda);
        assert_eq!(u_max, 0.25);
        // a bulk particle far from the edges and the displaced one
        let bulk = slot_of(6 * nx + 4);
        assert!((lambda[bulk] - 1.0).abs() < 0.02, "{}", lambda[bulk]);
        // the displaced particle moves back (-dir points to -x)
        let d = dir[slot_of(moved)];
        assert!(d.x > 0.0 && d.x.abs() > 10.0 * d.y.abs(), "{d}");
        // the top row (a flat surface: lambda about 0.5) is on the surface and not shifted
        let top = slot_of((ny - 1) * nx + 10);
        assert!(lambda[top] <= LAMBDA_SURFACE && lambda[top] > 0.3, "{}", lambda[top]);
        assert_eq!(dir[top], DVec2::ZERO);
        // the rows below it within the support (h = 2.12 dp, support 4.24 dp): the second row
        // (lambda about 0.68) counts as on the surface too; the next ones are inside the water
        // and their truncated kernels push them up (g along +y), of which only the part along
        // the surface is kept (the x part the displaced particle gives them in this column)
        let depth_of_support = (c.support / c.dp).floor() as usize;
        for below in 1..=depth_of_support + 1 {
            let a = slot_of((ny - 1 - below) * nx + 10);
            if lambda[a] <= LAMBDA_SURFACE {
                assert_eq!(dir[a], DVec2::ZERO, "{below} rows below");
            } else {
                assert!(dir[a].y.abs() < 1e-9 * d.length(), "{below} rows below: {}", dir[a]);
            }
        }
        assert!(lambda[slot_of((ny - 3) * nx + 10)] > LAMBDA_SURFACE);
        // a corner has a quarter of its neighbours: on the surface, no shift
        let corner = slot_of((ny - 1) * nx);
        assert!(lambda[corner] < 0.3, "{}", lambda[corner]);
        assert_eq!(dir[corner], DVec2::ZERO);
    }

    /// Water 20 x 10 dp over a wall 30 x 5 dp whose top row is 1.5 dp below the first row of
    /// water (a gap half a dp wider than the lattice's): the first rows see less concentration
    /// towards the wall, so their raw shift would move them into it; the part towards the wall
    /// is dropped, the part along it kept, and the rows beyond the wall's reach are untouched.
    #[test]
    fn no_shift_into_a_wall() {
        use crate::neighbours::{GROUP_FIXED, GROUP_FLUID};
        use crate::particles::{KIND_FIXED, KIND_FLUID};
        let scene = Scene::from_json(
            r#"{"dim": 2, "dp": 0.01, "coefh": 1.5, "tank": {"min": [0, 0], "max": [1, 1]}, "fluid": [{"min": [0, 0], "max": [0.2, 0.1]}]}"#,
        )
        .expect("scene");
        let c = Constants::new(&scene);
        let kernel = WendlandC2::new(c.h, 2);
        let (nx, ny, wx, wy) = (20usize, 10usize, 30usize, 5usize);
        let mut pos: Vec<DVec2> = (0..wx * wy)
            .map(|k| DVec2::new((k % wx) as Real - 4.5, -((k / wx) as Real) - 0.5) * c.dp)
            .collect();
        let nw = pos.len();
        pos.extend((0..nx * ny).map(|k| DVec2::new((k % nx) as Real + 0.5, (k / nx) as Real + 1.0) * c.dp));
        // one particle of the first row moved along the wall
        let moved = nw + 10;
        pos[moved].x += 0.2 * c.dp;
        let n = pos.len();
        let vel = vec![DVec2::new(0.1, 0.0); n];
        let rho = vec![c.rho0; n];
        let kind: Vec<u8> = (0..n).map(|k| if k < nw { KIND_FIXED } else { KIND_FLUID }).collect();
        let mut grid = CellGrid::<Dim2>::new(DVec2::splat(-0.1), DVec2::splat(0.5), c.support, 2);
        let (mut perm, mut keys) = (vec![0u32; n], vec![0u32; n]);
        grid.sort_group(GROUP_FIXED, 0..nw, &pos, &mut perm[..nw], &mut keys[..nw]);
        grid.sort_group(GROUP_FLUID, nw..n, &pos, &mut perm[nw..], &mut keys[nw..]);
        let pos: Vec<DVec2> = perm.iter().map(|&k| pos[k as usize]).collect();
        let slot_of = |k: usize| perm.iter().position(|&p| p as usize == k).expect("slot") - nw;
        let f = Fields::<Dim2> { pos: &pos, vel: &vel, rho: &rho, kind: &kind, tau: &[], kgc: &[], fluid_start: nw, split: None };
        let (mut dir, mut normal) = (vec![DVec2::ZERO; n - nw], vec![DVec2::ZERO; n - nw]);
        let mut lambda = vec![0.0; n - nw];
        delta_plus_fields(&c, &kernel, &grid, f, &mut dir, &mut normal, &mut lambda);
        // the move is -dir: its part towards the wall (-y) is -dir.y, never positive
        for row in 0..3 {
            let a = slot_of(nw + row * nx + 5);
            assert!(lambda[a] > LAMBDA_SURFACE, "row {row}: lambda {}", lambda[a]);
            assert!(dir[a].y.abs() < 1e-9, "row {row}: {}", dir[a]);
        }
        // the moved particle is still pushed back along the wall, and not towards it
        let d = dir[slot_of(moved)];
        assert!(d.x > 0.0 && d.y <= 1e-9, "{d}");
        // the gap is felt by the first rows only (their raw g points up, away from the wall):
        // the fifth row, beyond the wall's support, keeps its full shift (none on the lattice)
        let fifth = slot_of(nw + 5 * nx + 5);
        assert!(dir[fifth].length() < 1e-9, "{}", dir[fifth]);
    }
}
