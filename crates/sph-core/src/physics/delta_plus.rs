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
use crate::neighbours::{CellGrid, GROUPS};
use crate::particles::KIND_EXCLUDED;

/// Below this smallest eigenvalue of the renormalisation matrix a particle is on the free
/// surface and is not shifted (about 0.5 on a flat surface, 1 in the bulk; Marrone et al. 2010
/// take 0.2 for the particles certainly on it and test those up to 0.75 further).
pub const LAMBDA_SURFACE: Real = 0.4;
/// Above this one a particle is inside the water and shifted in full; between the two its
/// shift keeps only its part along the surface (Sun et al. 2017, Eq. 17).
pub const LAMBDA_BULK: Real = 0.75;
/// `R` and `n` of the anti-clustering factor `1 + R (W_ab / W(dp))^n` (Sun et al. 2017 after
/// Monaghan 2000), which pushes apart pairs closer than dp.
pub const ANTI_CLUSTER_R: Real = 0.2;
pub const ANTI_CLUSTER_N: i32 = 4;

/// The shift direction `s_a` of each fluid particle (the sweep moves it by `-A h U_max dt s_a`)
/// and the smallest eigenvalue `lambda_a` of its renormalisation matrix
/// `B_a = sum_b (r_b - r_a) (x) grad_a W_ab V_b`, over wall and fluid neighbours in the grid's
/// fixed order (walls, paddle, fluid); returns `U_max`, the largest fluid speed (a maximum:
/// the same for any thread count). With `g_a = sum_b [1 + R (W_ab/W(dp))^n] grad_a W_ab V_b`:
/// `s_a = 0` for `lambda_a < LAMBDA_SURFACE`, `(I - n n) g_a` up to `LAMBDA_BULK` with the
/// outward normal `n = -B_a^-1 grad C_a / |B_a^-1 grad C_a|` (Marrone et al. 2010, `grad C_a =
/// sum_b grad_a W_ab V_b`), `g_a` above. Excluded particles get zeros.
pub fn delta_plus_fields<D: Dim, K: Kernel>(
    c: &Constants,
    kernel: &K,
    grid: &CellGrid<D>,
    f: Fields<'_, D>,
    dir: &mut [D::V],
    lambda: &mut [Real],
) -> Real {
    let support2 = c.support * c.support;
    let inv_w_dp = 1.0 / kernel.w(c.dp);
    dir.par_iter_mut()
        .zip(lambda.par_iter_mut())
        .enumerate()
        .with_max_len(NEIGHBOUR_TASK)
        .map(|(i, (dir_a, lambda_a))| {
            let a = f.fluid_start + i;
            *dir_a = D::V::ZERO;
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
            *dir_a = if lam < LAMBDA_SURFACE {
                D::V::ZERO
            } else if lam <= LAMBDA_BULK {
                // B is positive definite here (lambda >= 0.4), so its adjugate gives the
                // direction of B^-1 grad C; the normal's sign does not matter to (I - n n)
                let nu = D::sym_adjugate_dot(&b, grad_c);
                let n2 = nu.length_squared();
                if n2 > 0.0 {
                    g - nu * (nu.dot(g) / n2)
                } else {
                    g
                }
            } else {
                g
            };
            f.vel[a].length()
        })
        .reduce(|| 0.0, Real::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::WendlandC2;
    use crate::math::Dim2;
    use crate::scene::Scene;
    use glam::DVec2;

    /// A 2D lattice block of water 20 x 12 dp, one particle displaced: the bulk's eigenvalue is
    /// 1, the surface row's about 0.5 with no shift across the surface, a corner's below 0.4
    /// with none at all, and the displaced particle is pushed back towards its lattice site.
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
            fluid_start: 0,
        };
        let (mut dir, mut lambda) = (vec![DVec2::ZERO; pos.len()], vec![0.0; pos.len()]);
        let u_max = delta_plus_fields(&c, &kernel, &grid, f, &mut dir, &mut lambda);
        assert_eq!(u_max, 0.25);
        // a bulk particle far from the edges and the displaced one
        let bulk = slot_of(6 * nx + 4);
        assert!((lambda[bulk] - 1.0).abs() < 0.02, "{}", lambda[bulk]);
        // the displaced particle moves back (-dir points to -x)
        let d = dir[slot_of(moved)];
        assert!(d.x > 0.0 && d.x.abs() > 10.0 * d.y.abs(), "{d}");
        // the top row (a flat surface: lambda about 0.5) keeps only the shift along the
        // surface, none on a regular lattice, where its whole shift would be normal
        let top = slot_of((ny - 1) * nx + 10);
        assert!((LAMBDA_SURFACE..=LAMBDA_BULK).contains(&lambda[top]), "{}", lambda[top]);
        assert!(dir[top].length() < 1e-9 * d.length(), "{}", dir[top]);
        // a corner has a quarter of its neighbours: free surface, no shift
        let corner = slot_of((ny - 1) * nx);
        assert!(lambda[corner] < LAMBDA_SURFACE, "{}", lambda[corner]);
        assert_eq!(dir[corner], DVec2::ZERO);
    }
}
