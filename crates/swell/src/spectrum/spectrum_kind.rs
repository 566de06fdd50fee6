//! The wind-sea spectra a scene can name.

crate::closed_set! {
    /// Which wind-sea spectrum an FFT ocean samples (`spectrum` in `[water]` and in
    /// `[water.blender]`); [`super::WindSea`] is the spectrum itself, set up from it and the wind.
    #[derive(Default)]
    pub enum SpectrumKind: "a spectrum" {
        /// Tessendorf's Phillips spectrum (Blender's "Turbulent Ocean").
        Phillips = "phillips",
        /// Pierson-Moskowitz, fully developed (Blender's "Established Ocean").
        PiersonMoskowitz = "pierson-moskowitz",
        /// JONSWAP, fetch-limited (Blender's "Established Ocean (Sharp Peaks)").
        #[default]
        Jonswap = "jonswap",
        /// TMA (Texel, Marsen and Arsloe): JONSWAP in finite depth, needs `depth` (Blender's
        /// "Shallow Water"; Blender's name `texel-marsen-arsloe` is read too).
        Tma = "tma" | "texel-marsen-arsloe",
        /// A measured or modelled directional spectrum given as tables `E(f, θ)`
        /// (`spectrum_file`, `[[water.spectrum_table]]`, `[water.ndbc]`), summed.
        Table = "table",
    }
}
