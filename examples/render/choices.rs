//! The fixed sets of values of the render example's options, as clap value enums: `--help`
//! lists them and a typo gets clap's suggestion.

use clap::ValueEnum;
use photon_maps::render::{EstimatorKind, Mode};
use photon_maps::trace::gltf::LightUnits;
use photon_maps::trace::{Contact, CreaseAngle, PartitionError, Partitioner, SingleMap};
use std::fmt;

/// `--maps`: which photon-map partition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum MapsChoice {
    /// One global photon map (Jensen's basic method).
    Single,
    /// One map per group of faces joined across edges with a small crease angle (the report's
    /// baseline, fastest to build; not for modelled interiors: a wall's map runs on behind the
    /// cabinet standing against it, and the wall reads dark, 6 % over the obvhs kitchen).
    Crease,
    /// The default: crease-angle maps that never join across faces that meet — walls standing
    /// on or running through floors, overlapping or duplicated faces, gaps under 0.2 % of the
    /// scene (the scene is cut where faces meet first).
    Contact,
}

impl MapsChoice {
    /// The partitioner; `contact_gap` (`--contact-gap`) is the contact partition's relative
    /// gap, refused outside (0, 0.1].
    pub fn partitioner(self, contact_gap: Option<f32>) -> Result<Box<dyn Partitioner>, String> {
        Ok(match self {
            MapsChoice::Single => Box::new(SingleMap),
            MapsChoice::Crease => Box::new(CreaseAngle::default()),
            MapsChoice::Contact => {
                let defaults = Contact::default();
                let relative_gap = contact_gap.unwrap_or(defaults.relative_gap);
                if !(relative_gap > 0.0 && relative_gap <= 0.1) {
                    return Err(format!(
                        "--contact-gap {relative_gap}: expected a fraction of the scene's diagonal in (0, 0.1]"
                    ));
                }
                Box::new(Contact {
                    relative_gap,
                    ..defaults
                })
            }
        })
    }
}

/// The message for a partition that failed; where the contact split gave up (more meetings
/// than its bounds allow, as in a dense field of objects closer than the gap), what to try.
pub fn partition_message(error: PartitionError) -> String {
    match error {
        PartitionError::Split(_) => {
            format!("{error} (a smaller --contact-gap, such as 0.0001, or --maps crease avoids it)")
        }
        _ => error.to_string(),
    }
}

/// `--estimator`: which radiance estimator.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EstimatorChoice {
    /// Jensen's disc `π r²`.
    Disc,
    /// Hey & Purgathofer's geometry-based area in a cube.
    Cube,
    /// The geometry-based area in a ball.
    Ball,
}

impl From<EstimatorChoice> for EstimatorKind {
    fn from(choice: EstimatorChoice) -> Self {
        match choice {
            EstimatorChoice::Disc => EstimatorKind::Disc,
            EstimatorChoice::Cube => EstimatorKind::GeometryCube,
            EstimatorChoice::Ball => EstimatorKind::GeometryBall,
        }
    }
}

/// `--mode`: how the image is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ModeChoice {
    /// The photon maps read at the first diffuse hit (formerly `visualize`, still accepted).
    #[value(alias = "visualize")]
    PhotonMap,
    /// Direct light by shadow rays, the rest from the photon maps.
    ShadowRays,
    /// An unbiased path tracer (the reference; reads no photon maps).
    PathTrace,
    /// Progressive photon mapping: passes of fresh photon maps, averaged.
    Progressive,
    /// Stochastic progressive photon mapping (one global map, shrinking radii).
    Sppm,
    /// Final gathering: direct light by shadow rays, caustics from the caustic photons, the
    /// rest by gather rays into precomputed irradiance.
    FinalGather,
}

impl ModeChoice {
    /// The renderer's mode; the progressive modes render their passes like `photon-map`.
    pub fn render_mode(self) -> Mode {
        match self {
            ModeChoice::PhotonMap | ModeChoice::Progressive | ModeChoice::Sppm => Mode::PhotonMap,
            ModeChoice::ShadowRays => Mode::ShadowRays,
            ModeChoice::PathTrace => Mode::PathTrace,
            ModeChoice::FinalGather => Mode::FinalGather,
        }
    }

    /// True for the modes of examples/render/progressive.rs.
    pub fn is_progressive(self) -> bool {
        matches!(self, ModeChoice::Progressive | ModeChoice::Sppm)
    }
}

/// Writes a choice as its command-line name (`shadow-rays`), as in shard identities.
fn write_name<T: ValueEnum>(value: &T, f: &mut fmt::Formatter<'_>) -> fmt::Result {
    match value.to_possible_value() {
        Some(v) => f.write_str(v.get_name()),
        None => Ok(()),
    }
}

impl fmt::Display for MapsChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_name(self, f)
    }
}

impl fmt::Display for ModeChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_name(self, f)
    }
}

/// `--direct`: how a progressive pass lights the first diffuse hit directly.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DirectChoice {
    /// Photons for all light (the `photon-map` mode per pass).
    Photons,
    /// Shadow rays for direct light, photons for the rest (the `shadow-rays` mode per pass).
    ShadowRays,
}

impl DirectChoice {
    /// The render mode of each progressive pass.
    pub fn mode(self) -> Mode {
        match self {
            DirectChoice::Photons => Mode::PhotonMap,
            DirectChoice::ShadowRays => Mode::ShadowRays,
        }
    }
}

/// `--light-units`: how a glTF file's emissive strength, candela and lux become watts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LightUnitsChoice {
    /// Emission 1:1 as radiance, lamps divided by 683 lm/W (the loader's default).
    Mixed,
    /// Everything photometric, divided by 683 lm/W: physical watts, emitters and lamps at the
    /// file's ratio.
    Photometric,
    /// Everything 1:1, as glTF viewers shade: emitters and lamps at the file's ratio.
    Viewer,
}

impl From<LightUnitsChoice> for LightUnits {
    fn from(choice: LightUnitsChoice) -> Self {
        match choice {
            LightUnitsChoice::Mixed => LightUnits::Mixed,
            LightUnitsChoice::Photometric => LightUnits::Photometric,
            LightUnitsChoice::Viewer => LightUnits::Viewer,
        }
    }
}

impl fmt::Display for LightUnitsChoice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_name(self, f)
    }
}

/// `--size`: an image size written `WIDTHxHEIGHT` (e.g. `500x500`), both sides at least 1.
pub fn parse_image_size(text: &str) -> Result<(u32, u32), String> {
    let bad =
        || format!("image size '{text}': expected WIDTHxHEIGHT with both sides at least 1, e.g. 500x500");
    let (w, h) = text.split_once(['x', 'X']).ok_or_else(bad)?;
    let w: u32 = w.trim().parse().map_err(|_| bad())?;
    let h: u32 = h.trim().parse().map_err(|_| bad())?;
    if w == 0 || h == 0 {
        return Err(bad());
    }
    Ok((w, h))
}
