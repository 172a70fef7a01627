//! Gauges computed in the core, each at its own sampling interval (DESIGN.md section 4).
//!
//! A gauge samples at the end of the first step whose time reaches its next sample time (and at
//! t = 0), and records the actual time. Interpolation is Shepard-normalised SPH over fluid
//! particles: `f(x) = sum_b V_b W(x - x_b) f_b / sum_b V_b W(x - x_b)`, `V_b = m / rho_b`.

mod body_force;
mod overtopping;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::neighbours::{CellGrid, GROUP_FIXED, GROUP_FLUID, GROUP_MOVING};
use crate::particles::Particles;
use crate::physics::eos::pressure;
use crate::physics::Constants;
use crate::scene::BoxSpec;

pub use body_force::{body_force, NO_BODY};
pub use overtopping::Crossings;

/// How a free-surface gauge finds the surface (default: `Defaults::gauges`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceMethod {
    /// Highest point of a vertical line (samples every dp/2) where the fluid's kernel volume
    /// sum `sum_b V_b W` fills half the space the walls leave free (`S_fluid / (1 - S_wall)
    /// >= 0.5`, which is `S_fluid >= 0.5` away from walls), linearly interpolated between samples.
    Kernel,
    /// Highest fluid particle within 0.75 dp of the line, plus dp/2 (the particle's half-spacing,
    /// so that still water reads its depth); seed 001 uses a band of dp/2, which can miss the
    /// column between two particles.
    Particle,
}

/// How a run-up gauge finds the wet front on the slope (default: `Defaults::gauges`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RunupMethod {
    /// The last point along the segment where the kernel volume sum marks water
    /// ([`SurfaceMethod::Kernel`]'s test): it sees only water as deep as the segment lies
    /// above the bed.
    Kernel,
    /// The highest fluid particle within 1.5 dp of the segment.
    Particle,
    /// The wet front on the bed: the highest fluid particle that touches the bed, i.e. has a
    /// fixed wall particle within [`WET_FRONT_CONTACT`] dp, among those within
    /// [`WET_FRONT_BAND`] dp of the segment whose projection falls on it. Water one particle
    /// thin counts, which a line above the bed cannot see (issue 30: the swash tip decides the
    /// run-up). Records the particle's centre, which lies about dp/2 off the bed (the flume
    /// zeroes its run-up on the reading at rest, so that offset cancels).
    WetFront,
}

/// A fluid particle touches the bed when a fixed wall particle lies within this many dp of it:
/// on a lattice the first fluid layer lies dp from the walls' first, so a thin swash layer
/// touches and the layer above it (2 dp off) does not.
pub const WET_FRONT_CONTACT: Real = 1.5;
/// The wet front is looked for this many dp either side of a run-up segment, enough to reach
/// the bed from a segment laid up to 2 dp above it, as the flume lays its run-up gauge (1.5 dp).
pub const WET_FRONT_BAND: Real = 3.0;

/// One gauge of a scene. Positions are full `dim`-vectors unless stated.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum GaugeSpec {
    /// Free-surface elevation: records the surface height z [m] on the vertical line through
    /// `position` (its vertical component is ignored).
    Elevation {
        name: String,
        position: Vec<Real>,
        #[serde(default = "crate::scene::serde_default::elevation_method")]
        method: SurfaceMethod,
        interval: Real,
    },
    /// Velocity (and kernel volume sum) at fixed points.
    Velocity { name: String, points: Vec<Vec<Real>>, interval: Real },
    /// PIV-like window: a regular grid of `n` points per axis spanning `[min, max]` (in 3D a
    /// vertical plane when one axis has 1 point), sampled like velocity probes.
    Window { name: String, min: Vec<Real>, max: Vec<Real>, n: Vec<usize>, interval: Real },
    /// Run-up: the highest wet point along the segment `start -> end` (laid just above the beach,
    /// `end` uphill), sampled every dp/2; records its vertical position z [m].
    Runup {
        name: String,
        start: Vec<Real>,
        end: Vec<Real>,
        #[serde(default = "crate::scene::serde_default::runup_method")]
        method: RunupMethod,
        interval: Real,
    },
    /// Fluid pressure at fixed points: the Shepard-normalised kernel interpolation of the fluid
    /// particles' Tait pressures (the module's formula with `f_b = P(rho_b)`), as DualSPHysics
    /// measures pressure at a point; records per point the pressure [Pa] and the kernel volume
    /// sum (below 0.5 the point is out of the water). With `on_wall`, the points are sensors on
    /// a wall or a body: each must lie within dp of the tank's floor or sides or of an
    /// obstacle's surface (refused at the build otherwise), and is sampled moved along that
    /// surface's normal to dp/2 inside the fluid (a wall particle's half spacing: the fluid's
    /// first layer), and the record's points are those sampled.
    Pressure {
        name: String,
        points: Vec<Vec<Real>>,
        interval: Real,
        #[serde(default, skip_serializing_if = "std::ops::Not::not")]
        on_wall: bool,
    },
    /// Force and moment of the fluid on one obstacle (`obstacle`: its index in the scene's
    /// `obstacles`): the sum over the obstacle's wall particles of the pair forces of their
    /// fluid neighbours (see [`body_force`]), and its moment about `point`. Records the force
    /// [N in 3D, N/m in 2D] and the moment [N m, N m/m]: in 2D about the y axis,
    /// `M_y = r_z F_x - r_x F_z` (`r` from `point` to the wall particle).
    Force {
        name: String,
        #[serde(default)]
        obstacle: Option<usize>,
        point: Vec<Real>,
        interval: Real,
    },
    /// Overtopping: the volume of fluid that has crossed the vertical section at `x` towards +x
    /// since the first sample, net of what came back [m^3 in 3D, m^2 (per unit width) in 2D],
    /// and the discharge over the last interval [m^3/s, m^2/s] (see [`Crossings`]).
    Overtopping { name: String, x: Real, interval: Real },
}

impl GaugeSpec {
    pub fn name(&self) -> &str {
        match self {
            GaugeSpec::Elevation { name, .. }
            | GaugeSpec::Velocity { name, .. }
            | GaugeSpec::Window { name, .. }
            | GaugeSpec::Runup { name, .. }
            | GaugeSpec::Pressure { name, .. }
            | GaugeSpec::Force { name, .. }
            | GaugeSpec::Overtopping { name, .. } => name,
        }
    }

    pub fn interval(&self) -> Real {
        match self {
            GaugeSpec::Elevation { interval, .. }
            | GaugeSpec::Velocity { interval, .. }
            | GaugeSpec::Window { interval, .. }
            | GaugeSpec::Runup { interval, .. }
            | GaugeSpec::Pressure { interval, .. }
            | GaugeSpec::Force { interval, .. }
            | GaugeSpec::Overtopping { interval, .. } => *interval,
        }
    }

    pub fn kind(&self) -> &'static str {
        match self {
            GaugeSpec::Elevation { .. } => "elevation",
            GaugeSpec::Velocity { .. } => "velocity",
            GaugeSpec::Window { .. } => "window",
            GaugeSpec::Runup { .. } => "runup",
            GaugeSpec::Pressure { .. } => "pressure",
            GaugeSpec::Force { .. } => "force",
            GaugeSpec::Overtopping { .. } => "overtopping",
        }
    }

    /// The quantities the gauge records, in the order of a sample's values (each point's
    /// columns in turn): elevation and run-up, z [m] (NaN when no water is found); velocity
    /// probe and window, per point the velocity [m/s] then the kernel volume sum; pressure, per
    /// point the pressure [Pa] then the kernel volume sum; force, the force then the moment
    /// (one component in 2D, three in 3D); overtopping, the crossed volume then the discharge.
    pub fn columns(&self, dim: usize) -> Vec<Column> {
        match self {
            GaugeSpec::Elevation { .. } | GaugeSpec::Runup { .. } => vec![Column { name: "z", size: 1 }],
            GaugeSpec::Velocity { .. } | GaugeSpec::Window { .. } => {
                vec![Column { name: "velocity", size: dim }, Column { name: "kernel_sum", size: 1 }]
            }
            GaugeSpec::Pressure { .. } => {
                vec![Column { name: "pressure", size: 1 }, Column { name: "kernel_sum", size: 1 }]
            }
            GaugeSpec::Force { .. } => {
                vec![Column { name: "force", size: dim }, Column { name: "moment", size: if dim == 2 { 1 } else { 3 } }]
            }
            GaugeSpec::Overtopping { .. } => vec![Column { name: "volume", size: 1 }, Column { name: "discharge", size: 1 }],
        }
    }

    /// The points a point gauge samples (none for a gauge on a line).
    pub fn sample_points(&self, dim: usize) -> Vec<Vec<Real>> {
        match self {
            GaugeSpec::Velocity { points, .. } | GaugeSpec::Pressure { points, .. } => points.clone(),
            GaugeSpec::Window { min, max, n, .. } => {
                let mut out = Vec::new();
                let coord = |k: usize, i: usize| {
                    if n[k] <= 1 {
                        0.5 * (min[k] + max[k])
                    } else {
                        min[k] + (max[k] - min[k]) * i as Real / (n[k] - 1) as Real
                    }
                };
                let nz = if dim == 3 { n[2] } else { 1 };
                for iz in 0..nz {
                    for iy in 0..n[1] {
                        for ix in 0..n[0] {
                            let mut p = vec![coord(0, ix), coord(1, iy)];
                            if dim == 3 {
                                p.push(coord(2, iz));
                            }
                            out.push(p);
                        }
                    }
                }
                out
            }
            _ => Vec::new(),
        }
    }

    /// Checks the gauge against the scene's dimension, the domain `[lo, hi]` and the number of
    /// the scene's obstacles.
    pub fn validate(&self, field: &str, dim: usize, lo: &[Real], hi: &[Real], n_obstacles: usize) -> Result<()> {
        let interval = self.interval();
        if !interval.is_finite() || interval <= 0.0 {
            return Err(Error::invalid(format!("{field}.interval"), format!("must be > 0, got {interval}")));
        }
        if self.name().is_empty() {
            return Err(Error::invalid(format!("{field}.name"), "must not be empty"));
        }
        let check_point = |f: String, p: &[Real], horizontal_only: bool| -> Result<()> {
            if p.len() != dim {
                return Err(Error::invalid(f, format!("must have {dim} components, got {}", p.len())));
            }
            let axes = if horizontal_only { dim - 1 } else { dim };
            for k in 0..axes {
                if !p[k].is_finite() || p[k] < lo[k] || p[k] > hi[k] {
                    return Err(Error::invalid(
                        f,
                        format!("component {k} = {} is outside the domain [{}, {}]", p[k], lo[k], hi[k]),
                    ));
                }
            }
            Ok(())
        };
        match self {
            GaugeSpec::Elevation { position, .. } => check_point(format!("{field}.position"), position, true)?,
            GaugeSpec::Velocity { points, .. } | GaugeSpec::Pressure { points, .. } => {
                if points.is_empty() {
                    return Err(Error::invalid(format!("{field}.points"), "needs at least one point"));
                }
                for (i, p) in points.iter().enumerate() {
                    check_point(format!("{field}.points[{i}]"), p, false)?;
                }
            }
            GaugeSpec::Window { min, max, n, .. } => {
                check_point(format!("{field}.min"), min, false)?;
                check_point(format!("{field}.max"), max, false)?;
                if n.len() != dim || n.contains(&0) {
                    return Err(Error::invalid(format!("{field}.n"), format!("needs {dim} counts >= 1, got {n:?}")));
                }
                if n.iter().product::<usize>() > 1_000_000 {
                    return Err(Error::invalid(format!("{field}.n"), "more than 1e6 points per sample"));
                }
            }
            GaugeSpec::Runup { start, end, .. } => {
                check_point(format!("{field}.start"), start, false)?;
                check_point(format!("{field}.end"), end, false)?;
                if start == end {
                    return Err(Error::invalid(format!("{field}.end"), "must differ from start"));
                }
            }
            GaugeSpec::Force { obstacle, point, .. } => {
                let f = format!("{field}.obstacle");
                match obstacle {
                    None => return Err(Error::invalid(f, "a force gauge needs the index of the obstacle it measures")),
                    Some(i) if *i >= n_obstacles => {
                        return Err(Error::invalid(f, format!("no obstacle {i}: the scene has {n_obstacles} obstacles")))
                    }
                    Some(i) if *i >= NO_BODY as usize => {
                        return Err(Error::invalid(f, format!("force gauges measure the first {NO_BODY} obstacles, got {i}")))
                    }
                    Some(_) => {}
                }
                if point.len() != dim || point.iter().any(|x| !x.is_finite()) {
                    return Err(Error::invalid(format!("{field}.point"), format!("must be {dim} finite numbers, got {point:?}")));
                }
            }
            GaugeSpec::Overtopping { x, .. } => {
                if !x.is_finite() || *x < lo[0] || *x > hi[0] {
                    return Err(Error::invalid(format!("{field}.x"), format!("{x} is outside the domain [{}, {}]", lo[0], hi[0])));
                }
            }
        }
        Ok(())
    }
}

/// One quantity of a gauge's samples: its name in the record and its values per point (per
/// sample for a gauge without points).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Column {
    pub name: &'static str,
    pub size: usize,
}

/// Samples recorded by one gauge.
#[derive(Clone, Debug, Default)]
pub struct GaugeRecord {
    pub name: String,
    pub kind: &'static str,
    /// Sample times [s].
    pub t: Vec<Real>,
    /// Values, `width` per sample: for each point (once for a gauge without points) the
    /// `columns` in turn.
    pub values: Vec<Real>,
    pub width: usize,
    /// What a sample holds, in order ([`GaugeSpec::columns`]).
    pub columns: Vec<Column>,
    /// Sampled points (flattened, `dim` per point); empty for a gauge on a line.
    pub points: Vec<Real>,
    /// Window grid shape (`n`), empty otherwise.
    pub shape: Vec<usize>,
    pub next_time: Real,
    /// An overtopping gauge's particle sides and net count (empty for the other gauges).
    pub crossings: Crossings,
}

impl GaugeRecord {
    /// An empty record of the gauge `g` in a scene of dimension `dim`.
    pub fn new(g: &GaugeSpec, dim: usize) -> Self {
        let points = g.sample_points(dim);
        let columns = g.columns(dim);
        let width = points.len().max(1) * columns.iter().map(|c| c.size).sum::<usize>();
        GaugeRecord {
            name: g.name().to_string(),
            kind: g.kind(),
            t: Vec::new(),
            values: Vec::new(),
            width,
            columns,
            points: points.into_iter().flatten().collect(),
            shape: if let GaugeSpec::Window { n, .. } = g { n.clone() } else { Vec::new() },
            next_time: 0.0,
            crossings: Crossings::default(),
        }
    }
}

trait NanIfInfinite {
    fn pipe_nan(self) -> Self;
}
impl NanIfInfinite for Real {
    /// `-inf` (an empty maximum) becomes NaN: "no water here".
    fn pipe_nan(self) -> Self {
        if self.is_finite() {
            self
        } else {
            Real::NAN
        }
    }
}

/// Half-width, in dp, of the band around a particle-method gauge line. Seed 001 uses dp/2, but a
/// band exactly one spacing wide misses the column whenever two particles straddle the line at
/// a hair more than dp/2; 0.75 dp always holds one.
const PARTICLE_GAUGE_HALF_WIDTH: Real = 0.75;

/// What the gauges read, and nothing they could change: the particles, their cell grid (sorted
/// at the last force evaluation), the kernel, the run's constants, the tank and the obstacle
/// each fixed wall particle belongs to. A motion law can read a gauge through it before the
/// paddle moves (active absorption).
pub struct ProbeView<'a, D: Dim, K: Kernel> {
    pub p: &'a Particles<D>,
    pub grid: &'a CellGrid<D>,
    pub kernel: &'a K,
    pub c: &'a Constants,
    pub tank: &'a BoxSpec,
    /// Per fixed wall slot, the index of the obstacle it was sampled from ([`NO_BODY`] for the
    /// tank's walls); empty in a scene without force gauges.
    pub wall_body: &'a [u16],
}

impl<D: Dim, K: Kernel> ProbeView<'_, D, K> {
    /// Shepard sums at `x`: kernel volume sum, and the normalised density, pressure, velocity.
    pub fn shepard(&self, x: D::V) -> (Real, Real, Real, D::V) {
        let support2 = self.c.support * self.c.support;
        let p = &self.p;
        let (mut w_sum, mut rho, mut pr, mut vel) = (0.0, 0.0, 0.0, D::V::ZERO);
        self.grid.for_each_near(GROUP_FLUID, x, |b| {
            let r2 = (x - p.pos[b]).length_squared();
            if r2 >= support2 {
                return;
            }
            let vw = self.c.mass / p.rho[b] * self.kernel.w(r2.sqrt());
            w_sum += vw;
            rho += vw * p.rho[b];
            pr += vw * pressure(self.c, p.rho[b]);
            vel += p.vel[b] * vw;
        });
        if w_sum > 0.0 {
            (w_sum, rho / w_sum, pr / w_sum, vel * (1.0 / w_sum))
        } else {
            (0.0, 0.0, 0.0, D::V::ZERO)
        }
    }

    /// Kernel volume sum `sum_b (m_b / rho_b) W(x - x_b)` over the particles of the groups `groups`.
    fn volume_sum(&self, groups: &[usize], x: D::V) -> Real {
        let support2 = self.c.support * self.c.support;
        let p = &self.p;
        let mut sum = 0.0;
        for &g in groups {
            self.grid.for_each_near(g, x, |b| {
                let r2 = (x - p.pos[b]).length_squared();
                if r2 < support2 {
                    sum += self.c.mass / p.rho[b] * self.kernel.w(r2.sqrt());
                }
            });
        }
        sum
    }

    /// How full of water the space at `x` is: the fluid's kernel volume sum over the share of the
    /// kernel that the walls leave free, `S_fluid / (1 - S_wall)`. Away from walls this is the
    /// plain fluid sum of DESIGN.md section 4 (surface where it is 0.5); next to a side wall or
    /// a bed the walls' particles fill up to half of the kernel (a quarter is left in the corner
    /// of two walls), and the plain sum would read a full column there as half empty. The free
    /// share is floored at that corner's 1/4 so that points inside a wall do not turn wet on a
    /// trace of fluid.
    fn wet_fraction(&self, x: D::V) -> Real {
        let fluid = self.volume_sum(&[GROUP_FLUID], x);
        if fluid <= 0.0 {
            return 0.0;
        }
        let wall = self.volume_sum(&[GROUP_FIXED, GROUP_MOVING], x);
        fluid / (1.0 - wall).max(0.25)
    }

    /// The free surface on the vertical through `x` (its vertical component ignored), from the
    /// tank's floor to its top: [`Self::last_wet_along`] that line.
    pub fn surface_above(&self, x: D::V) -> Real {
        let up = D::DIM - 1;
        let (mut foot, mut top) = (x, x);
        foot.set(up, self.tank.min[up]);
        top.set(up, self.tank.max[up]);
        self.last_wet_along(foot, top)
    }

    /// Along the points `a + (b - a) s`, s from 0 to 1 every dp/2, the last point (from `b`
    /// backwards) where the wet fraction ([`Self::wet_fraction`]) reaches 0.5, linearly
    /// interpolated; returns that point's vertical coordinate, or NaN if no point is wet.
    pub fn last_wet_along(&self, a: D::V, b: D::V) -> Real {
        let len = (b - a).length();
        let n = ((len / (0.5 * self.c.dp)).ceil() as usize).max(1);
        let at = |i: usize| a + (b - a) * (i as Real / n as Real);
        let top = self.wet_fraction(at(n));
        if top >= 0.5 {
            return at(n).vertical();
        }
        let mut above = (at(n), top);
        for i in (0..n).rev() {
            let x = at(i);
            let w = self.wet_fraction(x);
            if w >= 0.5 {
                let s = (w - 0.5) / (w - above.1).max(Real::EPSILON);
                return (x + (above.0 - x) * s.clamp(0.0, 1.0)).vertical();
            }
            above = (x, w);
        }
        Real::NAN
    }

    /// Highest vertical coordinate of fluid particles accepted by `near`, or NaN.
    fn highest_fluid(&self, near: impl Fn(D::V) -> bool + Sync) -> Real {
        let fs = self.p.fluid_start();
        self.p.pos[fs..]
            .par_iter()
            .filter(|&&x| near(x))
            .map(|x| x.vertical())
            .reduce(|| Real::NEG_INFINITY, Real::max)
            .pipe_nan()
    }

    /// [`RunupMethod::WetFront`] on the segment `a -> b`: the highest fluid particle within
    /// [`WET_FRONT_BAND`] dp of the segment, its projection on it, with a fixed wall particle
    /// within [`WET_FRONT_CONTACT`] dp; NaN if none.
    pub fn wet_front(&self, a: D::V, b: D::V) -> Real {
        let dp = self.c.dp;
        let (band2, contact2) = ((WET_FRONT_BAND * dp).powi(2), (WET_FRONT_CONTACT * dp).powi(2));
        let ab = b - a;
        let inv = 1.0 / ab.length_squared();
        let walls = &self.p.pos[..self.p.n_fixed];
        self.highest_fluid(|x| {
            let s = (x - a).dot(ab) * inv;
            if !(0.0..=1.0).contains(&s) || (x - (a + ab * s)).length_squared() > band2 {
                return false;
            }
            let mut touches = false;
            self.grid.for_each_near(GROUP_FIXED, x, |w| touches |= (x - walls[w]).length_squared() <= contact2);
            touches
        })
    }

    /// The Shepard sums ([`Self::shepard`]) at each of `points` (flattened, `dim` per point),
    /// each point's turned into its values by `read`, in the points' order.
    fn at_points<R>(&self, points: &[Real], read: R) -> Vec<Real>
    where
        R: Fn((Real, Real, Real, D::V)) -> Vec<Real> + Sync + Send,
    {
        points.par_chunks(D::DIM).flat_map_iter(|pt| read(self.shepard(D::V::from_slice(pt)))).collect()
    }

    /// Samples every gauge of `specs` whose next sample time has come at time `t` into its
    /// record (`records` in the order of `specs`).
    pub fn sample_due(&self, specs: &[GaugeSpec], records: &mut [GaugeRecord], t: Real) {
        let up = D::DIM - 1;
        let half = 0.5 * self.c.dp;
        for (rec, spec) in records.iter_mut().zip(specs) {
            if t < rec.next_time {
                continue;
            }
            match spec {
                GaugeSpec::Elevation { position, method, .. } => {
                    let foot = D::V::from_slice(position);
                    let z = match method {
                        SurfaceMethod::Kernel => self.surface_above(foot),
                        SurfaceMethod::Particle => {
                            let h2 = PARTICLE_GAUGE_HALF_WIDTH * PARTICLE_GAUGE_HALF_WIDTH * self.c.dp * self.c.dp;
                            let z = self.highest_fluid(|x| {
                                let mut d = x - foot;
                                d.set(up, 0.0);
                                d.length_squared() <= h2
                            });
                            z + half
                        }
                    };
                    rec.values.push(z);
                }
                GaugeSpec::Runup { start, end, method, .. } => {
                    let (a, b) = (D::V::from_slice(start), D::V::from_slice(end));
                    let z = match method {
                        RunupMethod::Kernel => self.last_wet_along(a, b),
                        RunupMethod::Particle => {
                            let band2 = (3.0 * half) * (3.0 * half);
                            let ab = b - a;
                            let inv = 1.0 / ab.length_squared();
                            self.highest_fluid(|x| {
                                let s = ((x - a).dot(ab) * inv).clamp(0.0, 1.0);
                                (x - (a + ab * s)).length_squared() <= band2
                            })
                        }
                        RunupMethod::WetFront => self.wet_front(a, b),
                    };
                    rec.values.push(z);
                }
                GaugeSpec::Velocity { .. } | GaugeSpec::Window { .. } => {
                    let values = self.at_points(&rec.points, |(w, _, _, v)| {
                        v.as_slice().iter().copied().chain(std::iter::once(w)).collect()
                    });
                    rec.values.extend_from_slice(&values);
                }
                GaugeSpec::Pressure { .. } => {
                    let values = self.at_points(&rec.points, |(w, _, pr, _)| vec![pr, w]);
                    rec.values.extend_from_slice(&values);
                }
                GaugeSpec::Force { obstacle, point, .. } => {
                    let body = obstacle.map_or(NO_BODY, |i| i as u16);
                    let (force, moment) = body_force(self, body, D::V::from_slice(point));
                    rec.values.extend_from_slice(force.as_slice());
                    rec.values.extend_from_slice(&moment[..if D::DIM == 2 { 1 } else { 3 }]);
                }
                GaugeSpec::Overtopping { x, .. } => {
                    let last = rec.t.last().map(|&t_last| (t_last, rec.values[rec.values.len() - rec.width]));
                    let sample = rec.crossings.sample(self, *x, t, last);
                    rec.values.extend_from_slice(&sample);
                }
            }
            rec.t.push(t);
            let interval = spec.interval();
            // bounded: the build keeps `interval` above the time step floor and a restore keeps
            // `next_time` finite; past the resolution of t the gauge samples every step
            while rec.next_time <= t && rec.next_time + interval > rec.next_time {
                rec.next_time += interval;
            }
        }
    }
}
