//! The water's forces on a hull, from the water as drawn: hydrostatic pressure over the
//! submerged part of every hull triangle, and drag from the water's motion past it.
//!
//! The method is Kerner's ("Water interaction model for boats in video games", Gamasutra 2015,
//! after Ekström's part 2 for the drag terms): the water surface is sampled above each hull
//! vertex, each triangle is clipped where the depth below that surface changes sign, and each
//! submerged piece feels the pressure ρ g d of its depth d, d linear over the piece. Unlike
//! Kerner, who applies a piece's force at its centroid, the force acts at the piece's centre of
//! pressure, `∫ d x dA / ∫ d dA`, exact for a linear d, so that on still water the torque as well
//! as the force is Archimedes' (the buoyancy ρ g V acting at the centre of buoyancy).
//!
//! The pressure is hydrostatic below the local surface: the dynamic pressure of the waves'
//! orbital motion, which decays with depth as `e^{kz}`, is left out, as in Kerner; for a body
//! small against the wavelength the two differ by the order of `k` times its draft.

use glam::DVec3;

use super::rigid_body::Load;
use super::{BodyEnvironment, FloatingBody};

/// Depth (m) given to a hull vertex with no water above it (beyond a pool, on a river bank):
/// far above any water, so a triangle clipped between it and a wet vertex keeps little of the
/// edge, and finite, so that the clipping's interpolation stays finite.
const DRY_DEPTH_M: f64 = -1.0e3;

/// A hull vertex as a step sees it: world position, depth below the water surface above it
/// (positive under water) and the water's velocity there.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Corner {
    pub(super) position: DVec3,
    depth: f64,
    water_velocity: DVec3,
}

impl Corner {
    /// The point on the segment to `dry` where the depth is 0 (`self` wet, `dry` not).
    fn towards(&self, dry: &Corner) -> Corner {
        let s = self.depth / (self.depth - dry.depth);
        Corner {
            position: self.position + (dry.position - self.position) * s,
            depth: 0.0,
            water_velocity: self.water_velocity + (dry.water_velocity - self.water_velocity) * s,
        }
    }
}

/// Calls `piece` with every submerged part of the triangle (a, b, c), wound as it is: none, the
/// whole, one triangle (one corner under water) or two (two corners under).
fn submerged_pieces(a: Corner, b: Corner, c: Corner, mut piece: impl FnMut(&[Corner; 3])) {
    let wet = [a.depth > 0.0, b.depth > 0.0, c.depth > 0.0];
    let tri = [a, b, c];
    match wet.iter().filter(|w| **w).count() {
        0 => {}
        3 => piece(&tri),
        1 => {
            // Turn the triangle (keeping its winding) so that the wet corner comes first.
            let k = wet.iter().position(|w| *w).unwrap_or(0);
            let (p, q, r) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            piece(&[p, p.towards(&q), p.towards(&r)]);
        }
        _ => {
            // The dry corner last: p and q wet, r dry; the wet quadrilateral p, q, q-r, r-p.
            let k = wet.iter().position(|w| !*w).unwrap_or(0);
            let (p, q, r) = (tri[(k + 1) % 3], tri[(k + 2) % 3], tri[k]);
            let (qr, rp) = (q.towards(&r), p.towards(&r));
            piece(&[p, q, qr]);
            piece(&[p, qr, rp]);
        }
    }
}

/// The water's load on `body` at its current state with the environment at time `t`, and the
/// submerged volume (m³) the vertical pressure force implies (exact on still water). `rho` is
/// the water's density (kg/m³), `dt` the step (s) the load will act over: the drag is scaled
/// down where it would reverse the body's motion relative to the water within one step (a light
/// body's explicit quadratic drag otherwise oscillates and blows up).
pub(super) fn water_load<E: BodyEnvironment + ?Sized>(
    body: &mut FloatingBody,
    env: &E,
    t: f64,
    rho: f64,
    dt: f64,
) -> (Load, f64) {
    let s = body.state;
    let mut corners = std::mem::take(&mut body.corners);
    corners.clear();
    body.grounds.clear();
    body.rests.resize(body.hull.positions.len(), glam::Vec2::NAN);
    for (p, rest) in body.hull.positions.iter().zip(&mut body.rests) {
        let world = s.position + s.orientation * p.as_dvec3();
        let (x, z) = (world.x as f32, world.z as f32);
        // Kept for the ground's contacts, which the same step evaluates next.
        let ground = env.ground_height(x, z);
        body.grounds.push(ground);
        let corner = match env.water_height_near(x, z, t, rest) {
            // Ground above the water there means no water: a wave does not run through a dune.
            Some(h) if ground.is_none_or(|g| g < h) => Corner {
                position: world,
                depth: f64::from(h) - world.y,
                water_velocity: env.water_velocity(x, z, t).as_dvec3(),
            },
            _ => Corner { position: world, depth: DRY_DEPTH_M, water_velocity: DVec3::ZERO },
        };
        corners.push(corner);
    }
    let g = f64::from(crate::GRAVITY);
    let (com, v, w) = (s.position, s.velocity, s.angular_velocity);
    let mut pressure = Load::default();
    let mut drag = Load::default();
    // Area-weighted relative velocity of the wetted hull, and the wetted area.
    let mut relative = DVec3::ZERO;
    let mut wetted = 0.0;
    let (cd, cl) = (body.material.drag, body.material.linear_drag);
    for tri in &body.hull.triangles {
        let [a, b, c] = tri.map(|i| corners[i as usize]);
        submerged_pieces(a, b, c, |q| {
            let area_vector = 0.5 * (q[1].position - q[0].position).cross(q[2].position - q[0].position);
            let area = area_vector.length();
            if area <= 0.0 {
                return;
            }
            let sum_depth = q[0].depth + q[1].depth + q[2].depth;
            let sum_position = q[0].position + q[1].position + q[2].position;
            let centroid = sum_position / 3.0;
            // ∫ ρ g d dA over the piece, pushing against the outward normal.
            let force = -rho * g * sum_depth / 3.0 * area_vector;
            let centre = if sum_depth > 0.0 {
                let weighted = q[0].position * q[0].depth + q[1].position * q[1].depth + q[2].position * q[2].depth;
                (weighted + sum_position * sum_depth) / (4.0 * sum_depth)
            } else {
                centroid
            };
            pressure.force += force;
            pressure.torque += (centre - com).cross(force);
            // Drag at the centroid, from the water's velocity there.
            let water = (q[0].water_velocity + q[1].water_velocity + q[2].water_velocity) / 3.0;
            let r = centroid - com;
            let rel = v + w.cross(r) - water;
            let normal = area_vector / area;
            let into = rel.dot(normal);
            let mut f = -cl * area * rel;
            if into > 0.0 {
                f -= 0.5 * rho * cd * area * into * into * normal;
            }
            drag.force += f;
            drag.torque += r.cross(f);
            relative += rel * area;
            wetted += area;
        });
    }
    body.corners = corners;
    // Limit the drag to what stops the relative motion in one step, never reversing it.
    if wetted > 0.0 {
        let rel = relative / wetted;
        let m = body.material.mass;
        let f = drag.force.length() * dt;
        if f > 0.0 {
            let most = m * rel.length();
            if f > most {
                drag.force *= most / f;
            }
        }
        let tq = drag.torque.length() * dt;
        if tq > 0.0 {
            let inertia = body.world_inertia(s.orientation);
            let most = (inertia * w).length() + m * rel.length() * body.reach;
            if tq > most {
                drag.torque *= most / tq;
            }
        }
    }
    (pressure + drag, pressure.force.y / (rho * g))
}

/// The signed volume (m³) of `positions` (a closed, outward-wound triangle soup given as
/// triangles) under the plane y = 0, by the pieces this module clips: used by tests to check the
/// clipping against closed forms.
#[cfg(test)]
pub(super) fn volume_below_zero(triangles: &[[glam::Vec3; 3]]) -> f64 {
    let mut v = 0.0;
    for t in triangles {
        let c = t.map(|p| Corner { position: p.as_dvec3(), depth: -f64::from(p.y), water_velocity: DVec3::ZERO });
        submerged_pieces(c[0], c[1], c[2], |q| {
            let area_vector = 0.5 * (q[1].position - q[0].position).cross(q[2].position - q[0].position);
            // Divergence theorem with F = (0, y, 0): V = ∮ y n_y dA; the cap at y = 0 adds nothing.
            v += (q[0].position.y + q[1].position.y + q[2].position.y) / 3.0 * area_vector.y;
        });
    }
    v
}

/// `∫ y dV` (m⁴) over the part of the triangle soup below y = 0, the first moment the still
/// water's potential energy `-ρ g ∫ y dV` needs: `∮ ½ y² n_y dA` over the clipped pieces (the
/// cap at y = 0 adds nothing), with `∫ y² dA = A/6 (Σ yᵢ² + Σ yᵢ yⱼ)` for y linear on a piece.
#[cfg(test)]
pub(super) fn first_moment_below_zero(triangles: &[[DVec3; 3]]) -> f64 {
    let mut m = 0.0;
    for t in triangles {
        let c = t.map(|p| Corner { position: p, depth: -p.y, water_velocity: DVec3::ZERO });
        submerged_pieces(c[0], c[1], c[2], |q| {
            let area_vector = 0.5 * (q[1].position - q[0].position).cross(q[2].position - q[0].position);
            let [a, b, c] = [q[0].position.y, q[1].position.y, q[2].position.y];
            m += 0.5 * area_vector.y * (a * a + b * b + c * c + a * b + b * c + c * a) / 6.0;
        });
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::Hull;
    use glam::Vec3;

    #[test]
    fn clipping_a_box_at_any_depth_keeps_the_volume_below_the_plane() {
        let hull = Hull::cuboid(Vec3::new(1.0, 2.0, 0.5), [1, 1, 1]);
        for y in [-2.0f32, -0.7, 0.0, 0.3, 0.99, 3.0] {
            let tris: Vec<[Vec3; 3]> =
                hull.triangles.iter().map(|t| t.map(|i| hull.positions[i as usize] + Vec3::new(0.0, y, 0.0))).collect();
            let expected = f64::from((1.0 - y).clamp(0.0, 2.0) * 0.5);
            let v = volume_below_zero(&tris);
            assert!((v - expected).abs() < 1e-6, "y {y}: {v} vs {expected}");
        }
    }

    #[test]
    fn a_tilted_box_keeps_the_volume_below_the_plane() {
        // A unit cube turned 45° about Z, its centre at y = 0: half its volume below.
        let hull = Hull::cuboid(Vec3::ONE, [1, 1, 1]);
        let q = glam::Quat::from_rotation_z(std::f32::consts::FRAC_PI_4);
        let tris: Vec<[Vec3; 3]> = hull.triangles.iter().map(|t| t.map(|i| q * hull.positions[i as usize])).collect();
        assert!((volume_below_zero(&tris) - 0.5).abs() < 1e-6);
    }
}
