//! The shading models: where lighting is evaluated. One closed set for every surface (water,
//! terrain, the OBJ comparison mode), drawn by the one shaded-draw path (`render/shaded_draw.rs`).

crate::closed_set! {
    /// Where lighting is evaluated, and (for water) with which specular lobe.
    ///
    /// Every model computes ambient + diffuse (Lambert) + specular where the surface has one; they
    /// differ in how often lighting runs and in the shape of the highlight. Flat and Gouraud use
    /// the Blinn-Phong lobe at their evaluation points. In a scene file:
    /// `water.material.shading`, `terrain.material.shading`; on the command line `--shading`.
    #[derive(Default)]
    pub enum Shading: "a shading model" {
        /// Once per triangle from its face normal (paper 001's look).
        Flat = "flat",
        /// Once per vertex from the vertex normal, colours interpolated across the triangle (paper 000).
        #[default]
        Gouraud = "gouraud",
        /// Per pixel from the interpolated normal and world position, with Phong's reflection lobe
        /// `(r.v)^s` (Phong 1975).
        Phong = "phong",
        /// Per pixel like Phong, with Blinn's half-vector lobe `(n.h)^s` (Blinn 1977; paper 003 §2).
        BlinnPhong = "blinn-phong",
    }
}
