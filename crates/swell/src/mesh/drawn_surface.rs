//! The water surface a frame draws, in one place: the finite patch, or the camera-following rings
//! of an unbounded sea (issue 24/33: one owner for the drawn water).
//!
//! [`crate::world::World`] owns one and moves it once per update (advanced, displaced, placed,
//! foamed and checked once); the renderer draws exactly it, overlays included. Bakes and exports,
//! which want the finite patch whatever is drawn, ask for it explicitly
//! ([`crate::world::World::sample_patch`]), so nothing displaces a mesh that is not drawn.

use glam::{Vec2, Vec3};

use super::{Clipmap, SurfaceMesh};
use crate::water::WaveModel;

/// The water surface that is drawn.
#[derive(Clone, Debug)]
pub enum DrawnSurface {
    /// A finite patch: the scene's `size` x `cells` grid (`[water] extent = "patch"`).
    Patch(SurfaceMesh),
    /// An unbounded sea's rings around the eye (`extent = "unbounded"`), to the far field's edge.
    Rings(Clipmap),
}

impl DrawnSurface {
    /// Displaced positions (m): the model's frame after [`DrawnSurface::displace`], the world's
    /// once the owner has placed them.
    pub fn positions(&self) -> &[Vec3] {
        match self {
            Self::Patch(m) => &m.positions,
            Self::Rings(c) => &c.positions,
        }
    }

    /// Unit normals, one per position.
    pub fn normals(&self) -> &[Vec3] {
        match self {
            Self::Patch(m) => &m.normals,
            Self::Rings(c) => &c.normals,
        }
    }

    /// Positions and normals to write, e.g. to place them in the world.
    pub fn positions_and_normals_mut(&mut self) -> (&mut [Vec3], &mut [Vec3]) {
        match self {
            Self::Patch(m) => (&mut m.positions, &mut m.normals),
            Self::Rings(c) => (&mut c.positions, &mut c.normals),
        }
    }

    /// Foam coverage in [0, 1] per vertex, if the model has foam.
    pub fn foam(&self) -> Option<&[f32]> {
        match self {
            Self::Patch(m) => m.has_foam.then_some(&m.foam[..]),
            Self::Rings(c) => c.has_foam.then_some(&c.foam[..]),
        }
    }

    /// Triangle list, counter-clockwise seen from +Y.
    pub fn indices(&self) -> &[u32] {
        match self {
            Self::Patch(m) => &m.indices,
            Self::Rings(c) => &c.indices,
        }
    }

    /// The rings, if this is an unbounded sea.
    pub fn rings(&self) -> Option<&Clipmap> {
        match self {
            Self::Rings(c) => Some(c),
            Self::Patch(_) => None,
        }
    }

    /// Moves the rings to follow the local (x, z) point `eye` (m, the camera in the model's frame);
    /// a patch stays where it is.
    pub fn follow(&mut self, eye: Vec2) {
        if let Self::Rings(c) = self {
            c.follow(eye);
        }
    }

    /// Displaces every vertex with `model` at time `t` (s), positions and normals and foam in the
    /// model's frame; allocates nothing. Call [`WaveModel::advance`] first.
    pub fn displace(&mut self, model: &dyn WaveModel, t: f64) {
        match self {
            Self::Patch(m) => m.displace(model, t),
            Self::Rings(c) => c.displace(model, t),
        }
    }

    /// The spacing (m, in the model's frame) of the grid cells around each vertex, for overlays
    /// that size what they draw by the local cell (the normals): the patch's smaller cell side
    /// everywhere, a ring's own spacing on the rings.
    pub fn cell_sizes(&self) -> Vec<f32> {
        match self {
            Self::Patch(m) => {
                let s = m.grid.spacing();
                vec![s.x.min(s.y); m.positions.len()]
            }
            Self::Rings(c) => {
                let mut out = Vec::with_capacity(c.positions.len());
                for (k, g) in c.grids().iter().enumerate() {
                    out.resize(out.len() + g.vertex_count(), c.level_spacing(k as u32));
                }
                out
            }
        }
    }
}
