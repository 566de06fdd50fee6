//! The sun glitter models: what `[water.material] glitter` selects.

crate::closed_set! {
    /// How water reflects the lights (`[water.material] glitter`).
    #[derive(Default)]
    pub enum GlitterModel: "a glitter model" {
        /// The lights' irradiance through the surface's slope distribution (Cox and Munk 1954):
        /// the slopes the mesh resolves, those it filters (issue 17) and a micro-roughness that
        /// brings the total to Cox and Munk's measured variance for the wind. Physical units:
        /// a facet facing the sun reflects the sun's full radiance times Fresnel.
        #[default]
        CoxMunk = "cox-munk",
        /// The shading model's Phong or Blinn-Phong lobe of exponent `shininess` times `specular`:
        /// the highlight the papers draw, with no micro-roughness.
        Lobe = "lobe",
    }
}
