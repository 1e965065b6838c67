//! Shared pieces of the contact acceptance tests: body loads as interactions and mesh helpers.
#![allow(dead_code)]

use twoball::fe::interaction::{Interaction, InteractionEnergy, StepContext};
use twoball::Result;

/// A uniform acceleration field g (m/s²) on a range of nodes, ramped in over `ramp` seconds
/// after `start`: a body force (gravity) or a distributed push. Its energy is reported as the
/// potential −Σ m g·(x − x0), so the solver's closed-system total stays constant.
pub struct UniformLoad {
    pub name: String,
    pub nodes: std::ops::Range<usize>,
    pub g: [f64; 3],
    pub start: f64,
    pub ramp: f64,
    x0: Option<Vec<[f64; 3]>>,
    work: f64,
    prev: f64,
    dt_prev: f64,
    potential: f64,
}

impl UniformLoad {
    pub fn new(
        name: &str,
        nodes: std::ops::Range<usize>,
        g: [f64; 3],
        start: f64,
        ramp: f64,
    ) -> Self {
        UniformLoad {
            name: name.into(),
            nodes,
            g,
            start,
            ramp,
            x0: None,
            work: 0.0,
            prev: 0.0,
            dt_prev: 0.0,
            potential: 0.0,
        }
    }

    fn factor(&self, t: f64) -> f64 {
        if t < self.start {
            0.0
        } else if self.ramp <= 0.0 || t >= self.start + self.ramp {
            1.0
        } else {
            (t - self.start) / self.ramp
        }
    }
}

impl Interaction for UniformLoad {
    fn name(&self) -> &str {
        &self.name
    }

    fn add_forces(&mut self, ctx: &StepContext<'_>, f: &mut [[f64; 3]]) -> Result<()> {
        let s = self.factor(ctx.t);
        // Work over the last step (trapezoid in the load factor).
        let mut p = 0.0;
        for n in self.nodes.clone() {
            let m = ctx.mass[n];
            p += m * (self.g[0] * ctx.v[n][0] + self.g[1] * ctx.v[n][1] + self.g[2] * ctx.v[n][2]);
            for (fk, gk) in f[n].iter_mut().zip(self.g) {
                *fk += s * m * gk;
            }
        }
        self.work += 0.5 * (self.prev + s) * p * self.dt_prev;
        self.prev = s;
        self.dt_prev = ctx.dt;
        Ok(())
    }

    fn stable_time_step(&self, _mass: &[f64], _omega: &[f64]) -> Option<f64> {
        None
    }

    fn energy(&self) -> InteractionEnergy {
        // A conservative load: its potential is minus its work.
        InteractionEnergy {
            stored: -self.work,
            dissipated: 0.0,
            work: self.work,
        }
    }
}

/// Largest relative deviation of a series from its first value.
pub fn max_drift(series: &[f64]) -> f64 {
    let e0 = series[0];
    series
        .iter()
        .map(|e| (e - e0).abs() / e0.abs())
        .fold(0.0, f64::max)
}

pub mod hertz;
pub mod static_hertz;
