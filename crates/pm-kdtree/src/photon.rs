//! Photons: the decoded form used while tracing, and the 20-byte compact form stored in trees.

use glam::Vec3;

/// How a photon got where it is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PhotonKind {
    /// First diffuse hit straight from the light.
    Direct = 0,
    /// After at least one diffuse bounce.
    Indirect = 1,
    /// After only specular bounces since the light.
    Caustic = 2,
}

/// A set of photon kinds accepted by a query.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct KindMask(pub u8);

impl KindMask {
    /// Every photon.
    pub const ALL: KindMask = KindMask(0b111);
    /// Every photon but direct ones (for shadow-ray rendering).
    pub const NOT_DIRECT: KindMask = KindMask(0b110);
    /// Only `kind`.
    pub const fn only(kind: PhotonKind) -> KindMask {
        KindMask(1 << kind as u8)
    }
    /// True when `kind` is accepted.
    pub const fn accepts(self, kind: PhotonKind) -> bool {
        self.0 & (1 << kind as u8) != 0
    }
}

/// A photon in full precision.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {
    /// Where it landed (metres).
    pub position: Vec3,
    /// Power per RGB channel (watts).
    pub power: Vec3,
    /// Unit direction of travel (towards the surface).
    pub direction: Vec3,
    /// How it got here.
    pub kind: PhotonKind,
}

/// A photon in 20 bytes: position as 3×f32 and 8 bytes of encoded power, direction and kind.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct CompactPhoton {
    position: [f32; 3],
    packed: [u32; 2],
}

impl CompactPhoton {
    /// Encodes a photon.
    pub fn encode(photon: &Photon) -> Self {
        let _ = photon;
        todo!("pm-kdtree issue")
    }
    /// Decodes it.
    pub fn decode(&self) -> Photon {
        todo!("pm-kdtree issue")
    }
    /// Position.
    pub fn position(&self) -> Vec3 {
        Vec3::from(self.position)
    }
    /// Decoded power (watts per channel).
    pub fn power(&self) -> Vec3 {
        todo!("pm-kdtree issue")
    }
    /// Decoded unit direction of travel.
    pub fn direction(&self) -> Vec3 {
        todo!("pm-kdtree issue")
    }
    /// Kind.
    pub fn kind(&self) -> PhotonKind {
        let _ = self.packed;
        todo!("pm-kdtree issue")
    }
}
