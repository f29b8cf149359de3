//! Materials and surfaces: how light scatters at a surface, whether it emits, whether the
//! camera sees it.

use glam::Vec3;

use crate::sides::Sides;

/// How a surface scatters light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Material {
    /// Ideal diffuse reflector; `albedo` per channel in `[0, 1]`.
    Lambertian {
        /// Reflectance per RGB channel.
        albedo: Vec3,
    },
    /// Perfect specular reflector.
    Mirror {
        /// Reflectance per RGB channel.
        reflectance: Vec3,
    },
    /// Smooth dielectric (Fresnel reflection and refraction), colourless.
    Glass {
        /// Index of refraction (inside / outside), e.g. 1.5.
        ior: f32,
    },
}

impl Material {
    /// True for diffuse materials (photons are stored there).
    pub fn is_diffuse(&self) -> bool {
        matches!(self, Material::Lambertian { .. })
    }
}

/// A material plus emission and camera visibility.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Surface {
    /// Scattering.
    pub material: Material,
    /// Emitted radiance, W/(m²·sr) per channel, from the front (the side the normal points to)
    /// and, for [`Sides::Double`], from the back too (area lights).
    pub emission: Vec3,
    /// False for cut-away walls: invisible to camera rays, still blocking light and storing photons.
    pub camera_visible: bool,
    /// Which sides emit and which camera rays see ([`Sides::Front`] for the constructors
    /// here: front-emitting, seen from both sides).
    pub sides: Sides,
}

impl Surface {
    /// A visible, non-emitting diffuse surface.
    pub fn diffuse(albedo: Vec3) -> Self {
        Surface {
            material: Material::Lambertian { albedo },
            emission: Vec3::ZERO,
            camera_visible: true,
            sides: Sides::Front,
        }
    }

    /// A visible mirror.
    pub fn mirror(reflectance: Vec3) -> Self {
        Surface {
            material: Material::Mirror { reflectance },
            emission: Vec3::ZERO,
            camera_visible: true,
            sides: Sides::Front,
        }
    }

    /// A visible glass surface.
    pub fn glass(ior: f32) -> Self {
        Surface {
            material: Material::Glass { ior },
            emission: Vec3::ZERO,
            camera_visible: true,
            sides: Sides::Front,
        }
    }

    /// The same surface with `sides` (see [`Sides`]).
    pub fn with_sides(self, sides: Sides) -> Self {
        Surface { sides, ..self }
    }

    /// The same surface, hidden from camera rays.
    pub fn hidden_from_camera(self) -> Self {
        Surface {
            camera_visible: false,
            ..self
        }
    }
}
