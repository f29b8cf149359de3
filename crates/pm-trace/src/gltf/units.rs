//! Light units: how glTF's emissive strength and punctual intensities become the renderer's
//! radiance (W/(m²·sr)), radiant intensity (W/sr) and irradiance (W/m²).

/// Lumens per watt of 555 nm light: the factor from photometric to radiometric units.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// How the numbers of a glTF file's lights are read ([`super::GltfOptions::light_units`]).
///
/// glTF gives an emissive surface `emissiveFactor × KHR_materials_emissive_strength` (a
/// luminance in cd/m², "nits", in the files of authors who think in physical units), a point
/// or spot light an intensity in candela and a directional light an illuminance in lux. In
/// one consistent system an emitter of luminance `L` and area `A` (one-sided) emits `π L A`
/// lumens and a point light of `I` candela `4π I`: the modes below other than
/// [`LightUnits::Mixed`] keep that ratio in watts. [`super::GltfOptions::emission_scale`] and
/// [`super::GltfOptions::light_scale`] multiply on top.
///
/// | mode | emissive `L` → W/(m²·sr) | `I` cd → W/sr, `E` lux → W/m² | emitter : lamp |
/// |---|---|---|---|
/// | `Mixed` (default) | `L` | `I / 683`, `E / 683` | 683 × the authored ratio |
/// | `Photometric` | `L / 683` | `I / 683`, `E / 683` | as authored |
/// | `Viewer` | `L` | `I`, `E` | as authored |
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LightUnits {
    /// Emissive values taken 1:1 as radiance, punctual lights converted from photometric
    /// units at 683 lm/W: the loader's behaviour before this option existed, kept as the
    /// default so earlier renders do not change. Emitters come out 683 times too bright
    /// relative to lamps in a file authored in one system of units.
    #[default]
    Mixed,
    /// Everything photometric, converted at [`LUMENS_PER_WATT`] (683 lm/W, the efficacy of
    /// 555 nm light): emissive luminance in cd/m², intensities in cd, illuminance in lux.
    /// Physical watts for a file authored in physical units; emitters and lamps keep the
    /// authored ratio.
    Photometric,
    /// Everything taken 1:1 (1 cd/m² → 1 W/(m²·sr), 1 cd → 1 W/sr, 1 lux → 1 W/m²): the
    /// ratio of [`LightUnits::Photometric`] at 683 times its brightness, the numbers a glTF
    /// viewer shades with (its emissive and its lights in the same units, no conversion).
    Viewer,
}

impl LightUnits {
    /// Radiance in W/(m²·sr) per unit of `emissiveFactor × emissiveStrength`.
    pub fn emission_factor(self) -> f32 {
        match self {
            LightUnits::Mixed | LightUnits::Viewer => 1.0,
            LightUnits::Photometric => 1.0 / LUMENS_PER_WATT,
        }
    }

    /// Watts per lumen for punctual lights: W/sr per candela and W/m² per lux.
    pub fn punctual_factor(self) -> f32 {
        match self {
            LightUnits::Mixed | LightUnits::Photometric => 1.0 / LUMENS_PER_WATT,
            LightUnits::Viewer => 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mode_but_mixed_keeps_the_emitter_to_lamp_ratio() {
        for units in [LightUnits::Photometric, LightUnits::Viewer] {
            assert_eq!(units.emission_factor(), units.punctual_factor(), "{units:?}");
        }
        let mixed = LightUnits::Mixed;
        assert_eq!(mixed.emission_factor() / mixed.punctual_factor(), LUMENS_PER_WATT);
    }
}
