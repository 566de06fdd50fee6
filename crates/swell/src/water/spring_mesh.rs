//! A dynamic water surface: a lattice of masses joined to their four neighbours by springs (paper
//! 003 §1.1.3, after Hooke's law; the lattice of "mass-spring" cloth models, Provot 1995).
//!
//! For the spring from node i to neighbour j, rest length L, current length l = |x_j - x_i|:
//!
//! ```text
//! f_ij = c (x_j - x_i) (1 - L / l)                              (paper 003 eq. 4)
//! a_i  = (f_ext,i + sum_j f_ij - gamma v_i) / m                 (eq. 5)
//! v_i <- v_i + a_i dt,    x_i <- x_i + v_i dt                   (semi-implicit Euler, eq. 5)
//! ```
//!
//! Departures from the paper, each for physical correctness:
//! - paper 003 writes `a = (f_ext - gamma v - f) / m`; with its own f (which points from i towards j
//!   when the spring is stretched) that pushes stretched springs further apart and the lattice
//!   explodes. swell adds the spring force.
//! - A lattice whose springs rest at their natural length has no *linear* stiffness against
//!   vertical displacement (a stretch of `l - L ~ dy^2 / 2L`), so ripples would not travel. swell
//!   rests the springs at `rest_length_ratio` x spacing (default 0.5): the lattice is under tension,
//!   like a drum skin, and vertical waves travel at about `spacing sqrt(c (1 - ratio) / m)` nodes per
//!   second. Ratio 1 reproduces the paper's slack lattice.
//!
//! **Time stepping.** The state advances in fixed steps of `time_step` whatever the frame rate: a
//! call to [`WaveModel::advance`] for time t takes every step up to t, and scheduled drops happen at
//! step boundaries, so the state at t is the same however the frames fall. Going back in time
//! restarts from the initial state.
//!
//! **Stability.** Semi-implicit Euler on an oscillator `a = -w^2 x - b v` is stable iff
//! `w^2 dt^2 + 2 b dt < 4`. Each node has at most four springs, each of stiffness at most c along
//! its axis (and `c (1 - L/l) <= c` across it), so by Gershgorin's theorem the stiffest mode has
//! `w^2 <= 8 c / m`; with `b = gamma / m` the step is refused up front unless
//! `8 c dt^2 / m + 2 gamma dt / m < 4` (the paper's m = 4, c = 7, gamma = 0.05, dt = 0.4 gives 2.25).
//! Should the state still diverge (an enormous disturbance), [`WaveModel::advance`] returns
//! [`Error::Unstable`] and the surface keeps its last good state; it never carries NaN.

use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::wave_model::WaveModel;
use super::ModelParams;
use crate::error::{check_count, check_non_negative, check_positive, check_range, check_seed, Error, Result};
use crate::math::GridSpec;

/// Most lattice cells along one side.
pub const MAX_SPRING_CELLS: u32 = 1024;

/// Most steps one [`WaveModel::advance`] call may take (about a minute of work on a 256² lattice),
/// so a huge time cannot hang the program.
pub const MAX_STEPS_PER_ADVANCE: u64 = 1_000_000;

/// A node that moves farther than this many lattice extents from rest means the state diverged.
const DIVERGENCE_EXTENTS: f32 = 100.0;

crate::closed_set! {
    /// How the lattice's border nodes behave (`edges`).
    #[derive(Default)]
    pub enum Edges: "an edge behaviour" {
        /// Border nodes never move (a basin wall reflects waves).
        #[default]
        Fixed = "fixed",
        /// Border nodes move like the others (no external force holds the lattice).
        Free = "free",
    }
}

/// Drops falling at regular intervals at seeded random places.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DropSchedule {
    /// Seconds between drops, > 0; the first falls at simulation time 0.
    pub interval: f32,
    /// Radius of each drop's dent, metres; > 0.
    pub radius: f32,
    /// Depth of each dent at its centre, metres; >= 0.
    pub depth: f32,
    /// Seed of the drop positions. Default 1.
    #[serde(default = "one")]
    pub seed: u64,
}

fn one() -> u64 {
    1
}

/// Parameters of [`SpringMesh`]: `model = "springs"`. Defaults are paper 003's table 1.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SpringMeshParams {
    /// Lattice cells along x and z, each in [2, 1024]; the lattice is centred on the world origin and
    /// spans `lattice x spacing` metres. Default [128, 128].
    pub lattice: [u32; 2],
    /// Distance between neighbouring nodes at rest, metres; > 0. Default 0.25.
    pub spacing: f32,
    /// Mass m of each node, kg; > 0. Default 4.
    pub mass: f32,
    /// Spring constant c, N/m; > 0. Default 7.
    pub stiffness: f32,
    /// Damping gamma, kg/s; >= 0 (0 conserves energy). Default 0.05.
    pub damping: f32,
    /// Fixed time step dt, seconds; in (0, stability bound] (see the module documentation). Default 0.4.
    pub time_step: f32,
    /// Spring rest length as a fraction of `spacing`, in (0, 1]; below 1 the lattice is under
    /// tension and carries vertical waves. Default 0.5.
    pub rest_length_ratio: f32,
    /// Border behaviour. Default `fixed`.
    pub edges: Edges,
    /// If true, nodes move only vertically (paper 003's option). Default true.
    pub vertical_only: bool,
    /// Seconds simulated before scene time 0, >= 0, so a single frame at t = 0 already shows
    /// ripples. Default 0.
    pub warm_up: f32,
    /// Drops at regular intervals, if any. Default none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drops: Option<DropSchedule>,
}

impl Default for SpringMeshParams {
    fn default() -> Self {
        Self {
            lattice: [128, 128],
            spacing: 0.25,
            mass: 4.0,
            stiffness: 7.0,
            damping: 0.05,
            time_step: 0.4,
            rest_length_ratio: 0.5,
            edges: Edges::Fixed,
            vertical_only: true,
            warm_up: 0.0,
            drops: None,
        }
    }
}

impl SpringMeshParams {
    /// Largest stable time step (s) for the given mass, stiffness and damping: the positive root of
    /// `8 c dt^2 / m + 2 gamma dt / m = 4`.
    pub fn max_stable_time_step(&self) -> f32 {
        let (m, c, g) = (f64::from(self.mass), f64::from(self.stiffness), f64::from(self.damping));
        let (a, b) = (8.0 * c / m, 2.0 * g / m);
        ((-b + (b * b + 16.0 * a).sqrt()) / (2.0 * a)) as f32
    }

    /// Checks every value, naming keys under `key` (normally `water`).
    pub fn validate(&self, key: &str) -> Result<()> {
        check_count(&format!("{key}.lattice[0]"), self.lattice[0], 2, MAX_SPRING_CELLS)?;
        check_count(&format!("{key}.lattice[1]"), self.lattice[1], 2, MAX_SPRING_CELLS)?;
        check_positive(&format!("{key}.spacing"), self.spacing)?;
        check_positive(&format!("{key}.mass"), self.mass)?;
        check_positive(&format!("{key}.stiffness"), self.stiffness)?;
        check_non_negative(&format!("{key}.damping"), self.damping)?;
        check_range(&format!("{key}.rest_length_ratio"), self.rest_length_ratio, 1e-3, 1.0)?;
        check_non_negative(&format!("{key}.warm_up"), self.warm_up)?;
        check_positive(&format!("{key}.time_step"), self.time_step)?;
        let max_dt = self.max_stable_time_step();
        if self.time_step >= max_dt {
            return Err(Error::out_of_range(
                format!("{key}.time_step"),
                self.time_step,
                format!(
                    "(0, {max_dt}) (semi-implicit Euler is stable only while 8 c dt^2 / m + 2 gamma dt / m < 4; \
                     here m = {}, c = {}, gamma = {})",
                    self.mass, self.stiffness, self.damping
                ),
            ));
        }
        // The warm-up is simulated in one advance, which is capped at MAX_STEPS_PER_ADVANCE steps.
        let max_warm_up = MAX_STEPS_PER_ADVANCE as f32 * self.time_step;
        check_range(&format!("{key}.warm_up"), self.warm_up, 0.0, max_warm_up)?;
        if let Some(d) = &self.drops {
            check_positive(&format!("{key}.drops.interval"), d.interval)?;
            check_positive(&format!("{key}.drops.radius"), d.radius)?;
            check_non_negative(&format!("{key}.drops.depth"), d.depth)?;
            check_seed(&format!("{key}.drops.seed"), d.seed)?;
        }
        Ok(())
    }
}

/// The spring lattice and its state; see the [module documentation](self).
#[derive(Clone, Debug)]
pub struct SpringMesh {
    params: SpringMeshParams,
    /// The lattice as a grid: node (i, j) rests at `grid.rest_position(i, j)`.
    lattice: GridSpec,
    rest_length: f32,
    positions: Vec<Vec3>,
    velocities: Vec<Vec3>,
    /// External forces, held until [`SpringMesh::release_forces`].
    forces: Vec<Vec3>,
    normals: Vec<Vec3>,
    /// Scratch for the candidate next positions, checked before they replace `positions`.
    next: Vec<Vec3>,
    steps: u64,
    next_drop: u64,
    drop_rng: ChaCha8Rng,
}

impl SpringMesh {
    /// Builds the lattice at rest, refusing invalid (or unstable) parameters.
    pub fn new(params: SpringMeshParams) -> Result<Self> {
        params.validate("water")?;
        let size = Vec2::new(params.lattice[0] as f32, params.lattice[1] as f32) * params.spacing;
        let lattice = GridSpec::centered(size, params.lattice[0], params.lattice[1])?;
        let n = lattice.vertex_count();
        let mut mesh = Self {
            params,
            lattice,
            rest_length: params.rest_length_ratio * params.spacing,
            positions: vec![Vec3::ZERO; n],
            velocities: vec![Vec3::ZERO; n],
            forces: vec![Vec3::ZERO; n],
            normals: vec![Vec3::Y; n],
            next: vec![Vec3::ZERO; n],
            steps: 0,
            next_drop: 0,
            drop_rng: ChaCha8Rng::seed_from_u64(params.drops.map_or(0, |d| d.seed)),
        };
        mesh.reset();
        Ok(mesh)
    }

    /// Returns every node to rest, clears forces and restarts the clock and the drop schedule.
    pub fn reset(&mut self) {
        let nx = self.lattice.verts_x();
        for (idx, p) in self.positions.iter_mut().enumerate() {
            let r = self.lattice.rest_position(idx % nx, idx / nx);
            *p = Vec3::new(r.x, 0.0, r.y);
        }
        self.velocities.fill(Vec3::ZERO);
        self.forces.fill(Vec3::ZERO);
        self.normals.fill(Vec3::Y);
        self.steps = 0;
        self.next_drop = 0;
        self.drop_rng = ChaCha8Rng::seed_from_u64(self.params.drops.map_or(0, |d| d.seed));
    }

    /// The parameters, as given.
    pub fn params(&self) -> &SpringMeshParams {
        &self.params
    }

    /// The lattice's grid (node positions at rest).
    pub fn lattice(&self) -> &GridSpec {
        &self.lattice
    }

    /// Simulated time since the start (s), counting the warm-up: steps taken x time step.
    pub fn simulated_time(&self) -> f64 {
        self.steps as f64 * f64::from(self.params.time_step)
    }

    /// Current node positions (world metres, row-major over [`SpringMesh::lattice`]).
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Current node velocities (m/s).
    pub fn velocities(&self) -> &[Vec3] {
        &self.velocities
    }

    /// Total mechanical energy (J): kinetic `sum m v^2 / 2` plus spring `sum c (l - L)^2 / 2`.
    pub fn energy(&self) -> f64 {
        let m = f64::from(self.params.mass);
        let kinetic: f64 = self.velocities.iter().map(|v| 0.5 * m * f64::from(v.length_squared())).sum();
        let (nx, nz) = (self.lattice.verts_x(), self.lattice.verts_z());
        let c = f64::from(self.params.stiffness);
        let l0 = f64::from(self.rest_length);
        let mut potential = 0.0;
        for j in 0..nz {
            for i in 0..nx {
                let p = self.positions[j * nx + i];
                for (di, dj) in [(1, 0), (0, 1)] {
                    if i + di < nx && j + dj < nz {
                        let l = f64::from((self.positions[(j + dj) * nx + i + di] - p).length());
                        potential += 0.5 * c * (l - l0) * (l - l0);
                    }
                }
            }
        }
        kinetic + potential
    }

    /// Total momentum `sum m v` (kg m/s).
    pub fn momentum(&self) -> Vec3 {
        let sum: glam::DVec3 = self.velocities.iter().map(|v| v.as_dvec3()).sum();
        (sum * f64::from(self.params.mass)).as_vec3()
    }

    /// A drop: pushes the surface down by `depth` metres at (x, z), easing to 0 at `radius` (a
    /// raised-cosine dent). A position disturbance.
    pub fn drop(&mut self, x: f32, z: f32, radius: f32, depth: f32) -> Result<()> {
        check_non_negative("drop.depth", depth)?;
        self.disturb(x, z, radius, |p, _, _, w| p.y -= depth * w)
    }

    /// Moves the nodes near (x, z) by `offset` (m) weighted by the raised-cosine profile of `radius`.
    pub fn displace(&mut self, x: f32, z: f32, radius: f32, offset: Vec3) -> Result<()> {
        crate::error::check_finite_vec("displace.offset", &offset.to_array())?;
        let offset = self.constrain(offset);
        self.disturb(x, z, radius, |p, _, _, w| *p += offset * w)
    }

    /// Sets the velocity of the nodes near (x, z) to `velocity` (m/s) weighted by the profile.
    pub fn set_velocity(&mut self, x: f32, z: f32, radius: f32, velocity: Vec3) -> Result<()> {
        crate::error::check_finite_vec("set_velocity.velocity", &velocity.to_array())?;
        let velocity = self.constrain(velocity);
        self.disturb(x, z, radius, |_, v, _, w| *v = velocity * w)
    }

    /// Adds an external force (N) to the nodes near (x, z), weighted by the profile; it acts on every
    /// step until [`SpringMesh::release_forces`].
    pub fn push(&mut self, x: f32, z: f32, radius: f32, force: Vec3) -> Result<()> {
        crate::error::check_finite_vec("push.force", &force.to_array())?;
        let force = self.constrain(force);
        self.disturb(x, z, radius, |_, _, f, w| *f += force * w)
    }

    /// Removes every external force.
    pub fn release_forces(&mut self) {
        self.forces.fill(Vec3::ZERO);
    }

    fn constrain(&self, v: Vec3) -> Vec3 {
        if self.params.vertical_only {
            Vec3::new(0.0, v.y, 0.0)
        } else {
            v
        }
    }

    /// Applies `f(position, velocity, force, weight)` to every movable node within `radius` of (x, z).
    fn disturb(&mut self, x: f32, z: f32, radius: f32, f: impl Fn(&mut Vec3, &mut Vec3, &mut Vec3, f32)) -> Result<()> {
        crate::error::check_finite_vec("disturbance position", &[x, z])?;
        check_positive("disturbance radius", radius)?;
        let (nx, nz) = (self.lattice.verts_x(), self.lattice.verts_z());
        let sp = self.params.spacing;
        let o = self.lattice.origin;
        let lo = |c: f32, o: f32| ((c - radius - o) / sp).floor().max(0.0) as usize;
        let hi = |c: f32, o: f32, n: usize| (((c + radius - o) / sp).ceil().max(0.0) as usize).min(n - 1);
        let fixed = self.params.edges == Edges::Fixed;
        for j in lo(z, o.y)..=hi(z, o.y, nz) {
            for i in lo(x, o.x)..=hi(x, o.x, nx) {
                if fixed && (i == 0 || j == 0 || i == nx - 1 || j == nz - 1) {
                    continue;
                }
                let d = (self.lattice.rest_position(i, j) - Vec2::new(x, z)).length();
                if d < radius {
                    let w = 0.5 * (1.0 + (std::f32::consts::PI * d / radius).cos());
                    let k = j * nx + i;
                    f(&mut self.positions[k], &mut self.velocities[k], &mut self.forces[k], w);
                }
            }
        }
        self.update_normals();
        Ok(())
    }

    /// Applies the scheduled drops due at or before the current step.
    fn apply_due_drops(&mut self) {
        let Some(d) = self.params.drops else { return };
        let now = self.simulated_time();
        while self.next_drop as f64 * f64::from(d.interval) <= now + 1e-9 {
            let size = self.lattice.size;
            let margin = Vec2::splat(d.radius).min(0.25 * size);
            let u = Vec2::new(self.drop_rng.gen::<f32>(), self.drop_rng.gen::<f32>());
            let at = self.lattice.origin + margin + u * (size - 2.0 * margin);
            // Radius and depth were validated; the position lies on the lattice.
            let _ = self.drop(at.x, at.y, d.radius, d.depth);
            self.next_drop += 1;
        }
    }

    /// One semi-implicit Euler step of `time_step` seconds.
    fn step(&mut self) -> Result<()> {
        let p = self.params;
        let (nx, nz) = (self.lattice.verts_x(), self.lattice.verts_z());
        let (dt, inv_m, c, gamma, l0) = (p.time_step, 1.0 / p.mass, p.stiffness, p.damping, self.rest_length);
        let fixed = p.edges == Edges::Fixed;
        let positions = &self.positions;
        let forces = &self.forces;
        // Velocities first (they read only positions), then positions from the new velocities.
        self.velocities.par_chunks_mut(nx).enumerate().for_each(|(j, vrow)| {
            for (i, v) in vrow.iter_mut().enumerate() {
                if fixed && (i == 0 || j == 0 || i == nx - 1 || j == nz - 1) {
                    continue;
                }
                let k = j * nx + i;
                let xi = positions[k];
                let mut f = forces[k] - gamma * *v;
                // Fixed neighbour order (left, right, down, up) keeps the sum identical on any thread.
                let mut spring = |kj: usize| {
                    let d = positions[kj] - xi;
                    let l = d.length();
                    if l > 0.0 {
                        f += c * d * (1.0 - l0 / l);
                    }
                };
                if i > 0 {
                    spring(k - 1);
                }
                if i + 1 < nx {
                    spring(k + 1);
                }
                if j > 0 {
                    spring(k - nx);
                }
                if j + 1 < nz {
                    spring(k + nx);
                }
                let mut a = f * inv_m;
                if p.vertical_only {
                    a.x = 0.0;
                    a.z = 0.0;
                }
                *v += a * dt;
            }
        });
        let limit = DIVERGENCE_EXTENTS * self.lattice.size.max_element();
        let velocities = &self.velocities;
        let lattice = &self.lattice;
        let diverged = self
            .next
            .par_chunks_mut(nx)
            .enumerate()
            .map(|(j, row)| {
                let mut bad: Option<usize> = None;
                for (i, x) in row.iter_mut().enumerate() {
                    let k = j * nx + i;
                    *x = positions[k] + velocities[k] * dt;
                    let r = lattice.rest_position(i, j);
                    let moved = (*x - Vec3::new(r.x, 0.0, r.y)).length();
                    if (moved.is_nan() || moved > limit) && bad.is_none() {
                        bad = Some(k);
                    }
                }
                bad
            })
            .reduce(|| None, |a, b| a.or(b));
        if let Some(k) = diverged {
            return Err(Error::Unstable(format!(
                "spring mesh diverged at t = {:.3} s: node ({}, {}) moved more than {limit} m from rest; \
                 lower water.time_step, water.stiffness or the disturbance",
                self.simulated_time(),
                k % nx,
                k / nx
            )));
        }
        std::mem::swap(&mut self.positions, &mut self.next);
        self.steps += 1;
        Ok(())
    }

    /// Recomputes node normals from central differences of the displaced lattice.
    fn update_normals(&mut self) {
        let (nx, nz) = (self.lattice.verts_x(), self.lattice.verts_z());
        let positions = &self.positions;
        self.normals.par_chunks_mut(nx).enumerate().for_each(|(j, row)| {
            for (i, n) in row.iter_mut().enumerate() {
                let at = |i: usize, j: usize| positions[j * nx + i];
                let tx = at((i + 1).min(nx - 1), j) - at(i.saturating_sub(1), j);
                let tz = at(i, (j + 1).min(nz - 1)) - at(i, j.saturating_sub(1));
                *n = tz.cross(tx).normalize_or(Vec3::Y);
            }
        });
    }

    /// Displacement and normal at world (x, z), bilinear between nodes; zero outside the lattice.
    fn sample(&self, x: f32, z: f32) -> (Vec3, Vec3) {
        let g = &self.lattice;
        let u = (x - g.origin.x) / self.params.spacing;
        let v = (z - g.origin.y) / self.params.spacing;
        let (nx, nz) = (g.verts_x(), g.verts_z());
        if !(u >= 0.0 && v >= 0.0 && u <= (nx - 1) as f32 && v <= (nz - 1) as f32) {
            return (Vec3::ZERO, Vec3::Y);
        }
        let (i, j) = ((u as usize).min(nx - 2), (v as usize).min(nz - 2));
        let (fu, fv) = (u - i as f32, v - j as f32);
        let disp = |i: usize, j: usize| {
            let r = g.rest_position(i, j);
            self.positions[j * nx + i] - Vec3::new(r.x, 0.0, r.y)
        };
        let nrm = |i: usize, j: usize| self.normals[j * nx + i];
        let lerp2 = |f: &dyn Fn(usize, usize) -> Vec3| {
            let a = f(i, j).lerp(f(i + 1, j), fu);
            let b = f(i, j + 1).lerp(f(i + 1, j + 1), fu);
            a.lerp(b, fv)
        };
        (lerp2(&disp), lerp2(&nrm).normalize_or(Vec3::Y))
    }
}

impl ModelParams for SpringMeshParams {
    /// Finite: the lattice has as many masses as cells, no more.
    fn defined_everywhere(&self) -> bool {
        false
    }

    fn validate(&self) -> Result<()> {
        SpringMeshParams::validate(self, "water")
    }

    fn build(&self) -> Result<Box<dyn WaveModel>> {
        Ok(Box::new(SpringMesh::new(*self)?))
    }

    /// Positions, velocities, forces, normals and the next positions: five `Vec3` per node.
    fn estimate_bytes(&self) -> u64 {
        let nodes = (u64::from(self.lattice[0]) + 1) * (u64::from(self.lattice[1]) + 1);
        nodes * 5 * 12
    }

    fn steps_to(&self, t: f64) -> Option<f64> {
        Some(((t + f64::from(self.warm_up)) / f64::from(self.time_step)).floor().max(0.0))
    }

    fn time_after_steps(&self, steps: f64) -> Option<f64> {
        Some(steps * f64::from(self.time_step) - f64::from(self.warm_up))
    }

    fn takes_disturbances(&self) -> bool {
        true
    }
}

impl WaveModel for SpringMesh {
    /// Nothing: a simulated lattice has no spectrum: its surface is what its vertices say.
    fn slope_components(&self, _out: &mut Vec<(f32, f32)>) {}

    /// Samples the lattice at each grid vertex (bilinear in displacement and normal; exact copies
    /// where grid vertices coincide with nodes). The grid may differ from the lattice; outside the
    /// lattice the surface is at rest.
    fn evaluate(&self, grid: &GridSpec, _t: f64, positions: &mut [Vec3], normals: &mut [Vec3]) {
        let n = grid.vertex_count();
        assert!(positions.len() == n && normals.len() == n, "buffers must hold grid.vertex_count() = {n} vertices");
        let row = grid.verts_x();
        positions.par_chunks_mut(row).zip(normals.par_chunks_mut(row)).enumerate().for_each(|(j, (prow, nrow))| {
            for (i, (p, nr)) in prow.iter_mut().zip(nrow.iter_mut()).enumerate() {
                let r = grid.rest_position(i, j);
                let (d, normal) = self.sample(r.x, r.y);
                *p = Vec3::new(r.x, 0.0, r.y) + d;
                *nr = normal;
            }
        });
    }

    /// Height of the state of the last [`WaveModel::advance`] (`t` is ignored): bilinear between
    /// nodes, with the horizontal motion inverted by fixed-point iteration when nodes move
    /// sideways (error below 1e-4 m while neighbouring nodes do not overtake each other).
    fn height_at(&self, x: f32, z: f32, _t: f64) -> f32 {
        let target = Vec2::new(x, z);
        let mut rest = target;
        if !self.params.vertical_only {
            for _ in 0..32 {
                let (d, _) = self.sample(rest.x, rest.y);
                let next = target - Vec2::new(d.x, d.z);
                if (next - rest).length() < 1e-6 {
                    break;
                }
                rest = next;
            }
        }
        self.sample(rest.x, rest.y).0.y
    }

    /// A [`SpringMesh::drop`] at (x, z): `amount` >= 0 m deep, `radius` > 0 m.
    fn disturb(&mut self, x: f32, z: f32, amount: f32, radius: f32) -> Result<bool> {
        self.drop(x, z, radius, amount)?;
        Ok(true)
    }

    /// Steps to scene time `t` (simulation time `t + warm_up`) at the fixed time step.
    fn advance(&mut self, t: f64) -> Result<()> {
        self.advance_partly(t, u64::MAX).map(|_| ())
    }

    /// Steps towards `t` at most `work / nodes` steps (at least one), so that a caller checks for
    /// a cancel about every `work` node updates whatever the lattice's size.
    fn advance_partly(&mut self, t: f64, work: u64) -> Result<u64> {
        if !t.is_finite() {
            return Err(Error::out_of_range("time", t, "finite seconds"));
        }
        let target = t + f64::from(self.params.warm_up);
        let dt = f64::from(self.params.time_step);
        if target < self.simulated_time() - 1e-9 {
            self.reset();
        }
        let wanted = ((target + 1e-9) / dt).floor().max(0.0);
        if wanted - self.steps as f64 > MAX_STEPS_PER_ADVANCE as f64 {
            return Err(Error::out_of_range(
                "time",
                crate::error::Human(t),
                format!(
                    "at most {MAX_STEPS_PER_ADVANCE} spring-mesh steps ({} s) past the current state",
                    MAX_STEPS_PER_ADVANCE as f64 * dt
                ),
            ));
        }
        let wanted = wanted as u64;
        let nodes = self.positions().len().max(1) as u64;
        let budget = (work / nodes).max(1);
        let before = self.steps;
        loop {
            self.apply_due_drops();
            if self.steps >= wanted || self.steps - before >= budget {
                break;
            }
            self.step()?;
        }
        // Normals follow the positions at the end of each part: a part may be the last one a
        // cancelled caller sees, and its state must be drawable.
        if self.steps != before {
            self.update_normals();
        }
        Ok(wanted.saturating_sub(self.steps))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small(edges: Edges, vertical_only: bool, damping: f32) -> SpringMesh {
        SpringMesh::new(SpringMeshParams {
            lattice: [40, 40],
            spacing: 0.5,
            edges,
            vertical_only,
            damping,
            ..Default::default()
        })
        .unwrap()
    }

    fn height(m: &SpringMesh, i: usize, j: usize) -> f32 {
        m.positions()[j * m.lattice().verts_x() + i].y
    }

    #[test]
    fn disturb_through_the_trait_dents_the_surface_there_and_refuses_bad_input() {
        let mut m = small(Edges::Fixed, true, 0.05);
        let model: &mut dyn WaveModel = &mut m;
        assert!(model.disturb(1.0, -2.0, 0.4, 1.5).unwrap());
        // The node under the centre sinks by the full amount, the rim not at all, the far side never.
        assert!((model.height_at(1.0, -2.0, 0.0) + 0.4).abs() < 1e-5);
        assert!(model.height_at(1.0, -0.5, 0.0).abs() < 1e-6);
        assert_eq!(model.height_at(-5.0, 5.0, 0.0), 0.0);
        // Bad input is refused with the reason and changes nothing.
        let before = m.positions().to_vec();
        let model: &mut dyn WaveModel = &mut m;
        assert!(model.disturb(0.0, 0.0, -1.0, 1.0).unwrap_err().to_string().contains("depth"));
        assert!(model.disturb(0.0, 0.0, 0.1, 0.0).unwrap_err().to_string().contains("radius"));
        assert!(model.disturb(f32::NAN, 0.0, 0.1, 1.0).is_err());
        assert_eq!(m.positions(), &before[..]);
        // Closed-form models have nothing to disturb.
        let mut g = crate::water::Gerstner::new(vec![]).unwrap();
        assert!(!WaveModel::disturb(&mut g, 0.0, 0.0, 0.1, 1.0).unwrap());
    }

    #[test]
    fn a_drop_spreads_symmetrically() {
        let mut m = small(Edges::Fixed, true, 0.05);
        m.drop(0.0, 0.0, 2.0, 0.3).unwrap();
        m.advance(8.0).unwrap();
        let c = 20;
        let mut moved = false;
        for d in 1..15 {
            let h = height(&m, c + d, c);
            for other in [height(&m, c - d, c), height(&m, c, c + d), height(&m, c, c - d)] {
                assert!((h - other).abs() < 1e-5, "ring not symmetric at {d}: {h} vs {other}");
            }
            let diag = height(&m, c + d, c + d) - height(&m, c - d, c - d);
            assert!(diag.abs() < 1e-5);
            moved |= d > 5 && h.abs() > 1e-4;
        }
        assert!(moved, "the disturbance did not travel");
    }

    #[test]
    fn energy_decays_with_damping_and_momentum_is_conserved_without() {
        let mut m = small(Edges::Fixed, true, 0.5);
        m.drop(1.0, -2.0, 2.0, 0.3).unwrap();
        let mut last = m.energy();
        for k in 1..=10 {
            m.advance(k as f64 * 8.0).unwrap();
            let e = m.energy();
            assert!(e < last, "energy rose from {last} to {e}");
            last = e;
        }
        // Free edges, full 3-D motion, no damping: only internal forces act.
        let mut m = small(Edges::Free, false, 0.0);
        m.set_velocity(2.0, 1.0, 3.0, Vec3::new(0.3, -0.5, 0.2)).unwrap();
        let p0 = m.momentum();
        assert!(p0.length() > 1.0);
        m.advance(40.0).unwrap();
        assert!((m.momentum() - p0).length() < 1e-4 * p0.length(), "{} vs {p0}", m.momentum());
    }

    #[test]
    fn stepping_does_not_depend_on_the_frame_rate_or_thread_count() {
        let params = SpringMeshParams {
            lattice: [32, 24],
            drops: Some(DropSchedule { interval: 3.0, radius: 1.5, depth: 0.2, seed: 4 }),
            ..Default::default()
        };
        let mut a = SpringMesh::new(params).unwrap();
        a.advance(20.0).unwrap();
        let mut b = SpringMesh::new(params).unwrap();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        pool.install(|| {
            for k in 0..=600 {
                b.advance(k as f64 / 30.0).unwrap();
            }
        });
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let mut c = SpringMesh::new(params).unwrap();
        one.install(|| c.advance(20.0).unwrap());
        assert_eq!(a.positions(), b.positions());
        assert_eq!(a.positions(), c.positions());
        assert!(a.positions().iter().any(|p| p.y.abs() > 1e-3));
        // Going back restarts: the state at 5 s is the same as a fresh run to 5 s.
        let mut fresh = SpringMesh::new(params).unwrap();
        fresh.advance(5.0).unwrap();
        a.advance(5.0).unwrap();
        assert_eq!(a.positions(), fresh.positions());
    }

    #[test]
    fn unstable_steps_are_refused_and_blow_ups_reported() {
        let e = SpringMesh::new(SpringMeshParams { time_step: 1.2, ..Default::default() }).unwrap_err().to_string();
        assert!(e.starts_with("water.time_step = 1.2 is outside (0, 0.53"), "{e}");
        let mut m = small(Edges::Fixed, true, 0.05);
        m.set_velocity(0.0, 0.0, 2.0, Vec3::new(0.0, 1e37, 0.0)).unwrap();
        let e = m.advance(10.0).unwrap_err();
        assert!(matches!(e, Error::Unstable(_)), "{e}");
        assert!(m.positions().iter().all(|p| p.is_finite()));
    }

    #[test]
    fn at_rest_it_is_the_plane_and_the_grid_matches_height_at() {
        let mut m = small(Edges::Fixed, false, 0.05);
        let grid = GridSpec::centered(Vec2::splat(20.0), 40, 40).unwrap();
        let mut p = vec![Vec3::ZERO; grid.vertex_count()];
        let mut n = p.clone();
        m.advance(3.0).unwrap();
        m.evaluate(&grid, 3.0, &mut p, &mut n);
        assert!(p.iter().all(|v| v.y == 0.0) && n.iter().all(|v| *v == Vec3::Y));
        m.drop(1.0, 1.0, 3.0, 0.4).unwrap();
        m.advance(9.0).unwrap();
        m.evaluate(&grid, 9.0, &mut p, &mut n);
        for v in p.iter().step_by(7) {
            assert!((m.height_at(v.x, v.z, 9.0) - v.y).abs() < 1e-4);
        }
    }
}
