//! Overtopping: the fluid that has crossed a vertical section `x = x0` towards +x
//! ([`super::GaugeSpec::Overtopping`]).
//!
//! Each fluid particle's side of the section is kept per particle id from one sample to the
//! next ([`Crossings`]). At each sample the particles that are now past the section and were
//! not count +1, those that came back -1; a particle that crossed and came back between two
//! samples counts 0, which is its net crossing. The net count times the particle volume
//! `m / rho0` is the crossed volume (per unit width in 2D, where the mass is per unit width).
//! The count is an integer, so the volume does not depend on the order of the particles or on
//! the thread count. A particle that left the domain stays on the side it was last seen on.

use super::ProbeView;
use crate::kernel::Kernel;
use crate::math::{Dim, Real, Vector};
use crate::particles::KIND_EXCLUDED;

/// What an overtopping gauge carries from one sample to the next (and in a checkpoint).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Crossings {
    /// Per particle id, 1 if the particle was past the section (`x > x0`) at the last sample;
    /// empty before the first sample.
    pub past: Vec<u8>,
    /// Particles that crossed in +x since the first sample, net of those that came back.
    pub net: i64,
}

impl Crossings {
    /// Samples the section `x0` at time `t`: updates the sides and the net count, and returns
    /// the crossed volume and the discharge since the previous sample (`last`: its time and
    /// volume; the discharge is 0 at the first sample).
    pub fn sample<D: Dim, K: Kernel>(&mut self, view: &ProbeView<'_, D, K>, x0: Real, t: Real, last: Option<(Real, Real)>) -> [Real; 2] {
        let p = view.p;
        let fs = p.fluid_start();
        let first = self.past.is_empty();
        if first {
            self.past = vec![0; p.len()];
        }
        let mut change = 0_i64;
        for a in fs..p.len() {
            if p.kind[a] == KIND_EXCLUDED {
                continue;
            }
            let past = u8::from(p.pos[a].get(0) > x0);
            let slot = &mut self.past[p.id[a] as usize];
            if !first {
                change += i64::from(past) - i64::from(*slot);
            }
            *slot = past;
        }
        self.net += change;
        let volume = self.net as Real * (view.c.mass / view.c.rho0);
        let discharge = match last {
            Some((t_last, v_last)) if t > t_last => (volume - v_last) / (t - t_last),
            _ => 0.0,
        };
        [volume, discharge]
    }
}
