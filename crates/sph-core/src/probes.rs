//! Gauges computed in the core, each at its own sampling interval (DESIGN.md section 4).
//!
//! A gauge samples at the end of the first step whose time reaches its next sample time (and at
//! t = 0), and records the actual time. Interpolation is Shepard-normalised SPH over fluid
//! particles: `f(x) = sum_b V_b W(x - x_b) f_b / sum_b V_b W(x - x_b)`, `V_b = m / rho_b`.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::math::Real;

/// How a free-surface gauge finds the surface.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum SurfaceMethod {
    /// Highest point of a vertical line (samples every dp/2) where the fluid's kernel volume
    /// sum `sum_b V_b W` fills half the space the walls leave free (`S_fluid / (1 - S_wall)
    /// >= 0.5`, which is `S_fluid >= 0.5` away from walls), linearly interpolated between samples.
    #[default]
    Kernel,
    /// Highest fluid particle within 0.75 dp of the line, plus dp/2 (the particle's half-spacing,
    /// so that still water reads its depth); seed 001 uses a band of dp/2, which can miss the
    /// column between two particles.
    Particle,
}

/// One gauge of a scene. Positions are full `dim`-vectors unless stated.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum GaugeSpec {
    /// Free-surface elevation: records the surface height z [m] on the vertical line through
    /// `position` (its vertical component is ignored).
    Elevation {
        name: String,
        position: Vec<Real>,
        #[serde(default)]
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
        #[serde(default)]
        method: SurfaceMethod,
        interval: Real,
    },
}

impl GaugeSpec {
    pub fn name(&self) -> &str {
        match self {
            GaugeSpec::Elevation { name, .. }
            | GaugeSpec::Velocity { name, .. }
            | GaugeSpec::Window { name, .. }
            | GaugeSpec::Runup { name, .. } => name,
        }
    }

    pub fn interval(&self) -> Real {
        match self {
            GaugeSpec::Elevation { interval, .. }
            | GaugeSpec::Velocity { interval, .. }
            | GaugeSpec::Window { interval, .. }
            | GaugeSpec::Runup { interval, .. } => *interval,
        }
    }

    pub fn kind(&self) -> &'static str {
        match self {
            GaugeSpec::Elevation { .. } => "elevation",
            GaugeSpec::Velocity { .. } => "velocity",
            GaugeSpec::Window { .. } => "window",
            GaugeSpec::Runup { .. } => "runup",
        }
    }

    /// The points a velocity probe or window samples.
    pub fn sample_points(&self, dim: usize) -> Vec<Vec<Real>> {
        match self {
            GaugeSpec::Velocity { points, .. } => points.clone(),
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

    /// Checks the gauge against the scene's dimension and the domain `[lo, hi]`.
    pub fn validate(&self, field: &str, dim: usize, lo: &[Real], hi: &[Real]) -> Result<()> {
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
            GaugeSpec::Velocity { points, .. } => {
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
        }
        Ok(())
    }
}

/// Samples recorded by one gauge.
#[derive(Clone, Debug, Default)]
pub struct GaugeRecord {
    pub name: String,
    pub kind: &'static str,
    /// Sample times [s].
    pub t: Vec<Real>,
    /// Values, `width` per sample: elevation and run-up: z [m] (NaN when no water is found);
    /// velocity and window: per point the velocity components then the kernel volume sum.
    pub values: Vec<Real>,
    pub width: usize,
    /// Sampled points of velocity probes and windows (flattened, `dim` per point).
    pub points: Vec<Real>,
    /// Window grid shape (`n`), empty otherwise.
    pub shape: Vec<usize>,
    pub next_time: Real,
}
