//! The kinds of scattering a BSDF has (delta, glossy, diffuse; reflection, transmission), as a
//! small set of flags the renderer decides paths by.

use std::ops::BitOr;

/// A set of BSDF lobes. Combine with `|`; a [`super::BsdfSample`] names one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Lobes(u8);

impl Lobes {
    /// No lobe: a black, absorbing surface.
    pub const NONE: Lobes = Lobes(0);
    /// Perfect specular reflection (a mirror).
    pub const DELTA_REFLECTION: Lobes = Lobes(1);
    /// Perfect specular transmission (smooth glass).
    pub const DELTA_TRANSMISSION: Lobes = Lobes(1 << 1);
    /// Glossy reflection (a rough metal, a varnish).
    pub const GLOSSY_REFLECTION: Lobes = Lobes(1 << 2);
    /// Glossy transmission (frosted glass).
    pub const GLOSSY_TRANSMISSION: Lobes = Lobes(1 << 3);
    /// Diffuse reflection.
    pub const DIFFUSE_REFLECTION: Lobes = Lobes(1 << 4);
    /// Diffuse transmission.
    pub const DIFFUSE_TRANSMISSION: Lobes = Lobes(1 << 5);

    const DELTA: u8 = Self::DELTA_REFLECTION.0 | Self::DELTA_TRANSMISSION.0;
    const GLOSSY: u8 = Self::GLOSSY_REFLECTION.0 | Self::GLOSSY_TRANSMISSION.0;
    const DIFFUSE: u8 = Self::DIFFUSE_REFLECTION.0 | Self::DIFFUSE_TRANSMISSION.0;

    /// True when every lobe of `other` is in `self`.
    #[inline]
    pub const fn contains(self, other: Lobes) -> bool {
        self.0 & other.0 == other.0
    }

    /// True when some lobe is delta.
    #[inline]
    pub const fn has_delta(self) -> bool {
        self.0 & Self::DELTA != 0
    }

    /// True when some lobe is glossy.
    #[inline]
    pub const fn has_glossy(self) -> bool {
        self.0 & Self::GLOSSY != 0
    }

    /// True when some lobe is diffuse.
    #[inline]
    pub const fn has_diffuse(self) -> bool {
        self.0 & Self::DIFFUSE != 0
    }

    /// True when some lobe has a density (glossy or diffuse): photons are stored on such a
    /// surface, and a camera path's delta chain ends there.
    #[inline]
    pub const fn has_non_delta(self) -> bool {
        self.0 & !Self::DELTA != 0
    }
}

impl BitOr for Lobes {
    type Output = Lobes;

    #[inline]
    fn bitor(self, other: Lobes) -> Lobes {
        Lobes(self.0 | other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glass_lobes_are_delta_only_and_a_plastic_has_both() {
        let glass = Lobes::DELTA_REFLECTION | Lobes::DELTA_TRANSMISSION;
        assert!(glass.has_delta() && !glass.has_non_delta() && !glass.has_diffuse());
        let plastic = Lobes::DIFFUSE_REFLECTION | Lobes::DELTA_REFLECTION;
        assert!(plastic.has_delta() && plastic.has_non_delta() && plastic.has_diffuse());
        assert!(plastic.contains(Lobes::DELTA_REFLECTION) && !plastic.contains(glass));
        assert!(Lobes::GLOSSY_TRANSMISSION.has_glossy() && Lobes::GLOSSY_TRANSMISSION.has_non_delta());
        assert!(!Lobes::NONE.has_non_delta() && !Lobes::NONE.has_delta());
    }
}
