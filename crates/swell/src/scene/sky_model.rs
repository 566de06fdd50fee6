//! The sky models: what `[sky] model` selects.

crate::closed_set! {
    /// How the sky's radiance is computed (`[sky] model`).
    #[derive(Default)]
    pub enum SkyModel: "a sky model" {
        /// Two colours blended by the view ray's elevation (`horizon`, `zenith`, `ground`), with
        /// a sun disc along `sun_direction` or the first directional light: swell's original sky.
        #[default]
        Gradient = "gradient",
        /// The physically based clear sky of Preetham, Shirley and Smits (1999), set by
        /// `sun_elevation_deg`, `sun_azimuth_deg` and `turbidity`, with a limb-darkened sun and
        /// its glow.
        Preetham = "preetham",
    }
}
