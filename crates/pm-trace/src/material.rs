//! Materials and surfaces: how light scatters at a surface (a built-in BSDF or the caller's
//! own), whether it emits, whether the camera sees it.

use glam::{Vec2, Vec3};

use crate::bsdf::glass::Glass;
use crate::bsdf::lambertian::Lambertian;
use crate::bsdf::lobes::Lobes;
use crate::bsdf::metallic_roughness::MetallicRoughness;
use crate::bsdf::mirror::Mirror;
use crate::bsdf::shading_point::ShadingPoint;
use crate::bsdf::{Bsdf, BsdfSample};
use crate::rng::Rng;
use crate::sides::Sides;

/// How a surface scatters light: one of the built-in BSDFs, or a [`Bsdf`] of the caller's.
///
/// The built-ins stay enum variants (matched without a virtual call in the renderer's hot
/// loops, compared by value, and named as before by scenes and the glTF loader);
/// [`Material::Custom`] holds any other BSDF. `Material` is itself a [`Bsdf`], dispatching to
/// the variant's.
///
/// A custom BSDF is held as `&'static dyn Bsdf` so that `Material` and [`Surface`] stay `Copy`
/// (scenes pass one surface to many meshes by value, and the renderer copies surfaces in its
/// loops without reference counting). A BSDF known at compile time is a `static`; one made at
/// run time is leaked once (`Box::leak(Box::new(bsdf))`), which costs its size for the rest of
/// the program: make each distinct BSDF once, not once per scene load.
#[derive(Clone, Copy, Debug)]
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
    /// glTF 2.0's metallic-roughness material (GGX over Lambert, Appendix B), made by
    /// [`MetallicRoughness::new`], which checks its ranges.
    MetallicRoughness(MetallicRoughness),
    /// A BSDF of the caller's (see [`crate::bsdf`]).
    Custom(&'static dyn Bsdf),
}

impl Material {
    /// True for materials with a diffuse or glossy lobe (photons are stored there).
    pub fn is_diffuse(&self) -> bool {
        self.lobes().has_non_delta()
    }
}

/// Built-ins compare by value, custom BSDFs by identity (the same object).
impl PartialEq for Material {
    fn eq(&self, other: &Material) -> bool {
        match (self, other) {
            (Material::Lambertian { albedo: a }, Material::Lambertian { albedo: b }) => a == b,
            (Material::Mirror { reflectance: a }, Material::Mirror { reflectance: b }) => a == b,
            (Material::Glass { ior: a }, Material::Glass { ior: b }) => a == b,
            (Material::MetallicRoughness(a), Material::MetallicRoughness(b)) => a == b,
            (Material::Custom(a), Material::Custom(b)) => std::ptr::addr_eq(*a, *b),
            _ => false,
        }
    }
}

/// Calls `$call` on the variant's BSDF: the built-ins statically, a custom one through its
/// reference.
macro_rules! dispatch {
    ($material:expr, $bsdf:ident => $call:expr) => {
        match $material {
            Material::Lambertian { albedo } => {
                let $bsdf = Lambertian { albedo: *albedo };
                $call
            }
            Material::Mirror { reflectance } => {
                let $bsdf = Mirror {
                    reflectance: *reflectance,
                };
                $call
            }
            Material::Glass { ior } => {
                let $bsdf = Glass { ior: *ior };
                $call
            }
            Material::MetallicRoughness(bsdf) => {
                let $bsdf = bsdf;
                $call
            }
            Material::Custom(custom) => {
                let $bsdf = *custom;
                $call
            }
        }
    };
}

impl Material {
    /// [`Bsdf::sample_from`] for every material but the Lambertian, out of line.
    #[inline(never)]
    fn sample_from_out_of_line(&self, at: &ShadingPoint, wo: Vec3, rng: &mut Rng) -> Option<BsdfSample> {
        dispatch!(self, b => b.sample_from(at, wo, rng))
    }
}

impl Bsdf for Material {
    #[inline]
    fn lobes(&self) -> Lobes {
        dispatch!(self, b => b.lobes())
    }

    #[inline]
    fn eval(&self, at: &ShadingPoint, wo: Vec3, wi: Vec3) -> Vec3 {
        dispatch!(self, b => b.eval(at, wo, wi))
    }

    #[inline]
    fn pdf(&self, at: &ShadingPoint, wo: Vec3, wi: Vec3) -> f32 {
        dispatch!(self, b => b.pdf(at, wo, wi))
    }

    #[inline]
    fn sample(&self, at: &ShadingPoint, wo: Vec3, u: Vec2, u_lobe: f32) -> Option<BsdfSample> {
        dispatch!(self, b => b.sample(at, wo, u, u_lobe))
    }

    /// The built-in Lambertian's sampling inline (every diffuse bounce of every path); the
    /// others out of line, so that this stays small enough to inline where paths are traced.
    #[inline]
    fn sample_from(&self, at: &ShadingPoint, wo: Vec3, rng: &mut Rng) -> Option<BsdfSample> {
        match self {
            Material::Lambertian { albedo } => Lambertian { albedo: *albedo }.sample_from(at, wo, rng),
            other => other.sample_from_out_of_line(at, wo, rng),
        }
    }

    #[inline]
    fn albedo(&self, at: &ShadingPoint, wo: Vec3) -> Vec3 {
        dispatch!(self, b => b.albedo(at, wo))
    }

    #[inline]
    fn glossy_roughness(&self) -> Option<f32> {
        dispatch!(self, b => b.glossy_roughness())
    }

    #[inline]
    fn diffuse_albedo(&self, at: &ShadingPoint) -> Vec3 {
        dispatch!(self, b => b.diffuse_albedo(at))
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

    /// A visible, non-emitting glTF metallic-roughness surface.
    pub fn metallic_roughness(material: MetallicRoughness) -> Self {
        Surface {
            material: Material::MetallicRoughness(material),
            emission: Vec3::ZERO,
            camera_visible: true,
            sides: Sides::Front,
        }
    }

    /// A visible, non-emitting surface scattering by `bsdf` (a renderer author's own).
    /// (See [`Material`] for why it is `'static`.)
    pub fn with_bsdf(bsdf: &'static dyn Bsdf) -> Self {
        Surface {
            material: Material::Custom(bsdf),
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
