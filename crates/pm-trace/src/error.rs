//! Errors of scene building, photon tracing and photon-map building.

use thiserror::Error;

/// Why a scene could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum SceneError {
    /// A mesh could not be built.
    #[error("mesh {mesh}: {source}")]
    Mesh {
        /// Index of the mesh in the order it was added.
        mesh: usize,
        /// What was wrong.
        source: pm_geom::MeshError,
    },
    /// A mesh with per-face surfaces got a different number of surfaces than faces.
    #[error("mesh {mesh}: {surfaces} surfaces given for {faces} faces")]
    SurfaceCount {
        /// Index of the mesh.
        mesh: usize,
        /// Number of surfaces given.
        surfaces: usize,
        /// Number of faces given.
        faces: usize,
    },
    /// A mesh's vertex attributes do not match its vertices.
    #[error("mesh {mesh}: {reason}")]
    InvalidAttributes {
        /// Index of the mesh.
        mesh: usize,
        /// What is wrong.
        reason: String,
    },
    /// An analytic shape with invalid parameters.
    #[error("shape {shape}: {reason}")]
    InvalidShape {
        /// Index of the shape in the order it was added.
        shape: usize,
        /// What is wrong.
        reason: String,
    },
    /// A surface with a non-finite or negative colour, or a non-positive index of refraction.
    #[error("{what}: invalid surface: {reason}")]
    InvalidSurface {
        /// Which object carries the surface.
        what: String,
        /// What is wrong.
        reason: String,
    },
    /// A light with a non-finite position or direction, a bad cone, an empty area, negative
    /// or non-finite power, or a total power past f32's range.
    #[error("light {light}: {reason}")]
    InvalidLight {
        /// Index of the light in the order it was added.
        light: usize,
        /// What is wrong.
        reason: String,
    },
    /// A camera with a non-finite position, no view direction or a bad field of view.
    #[error("camera: {reason}")]
    InvalidCamera {
        /// What is wrong.
        reason: String,
    },
    /// Splitting the faces where they meet (the contact partition) passed one of its bounds.
    #[error("splitting faces where they meet: {0}")]
    Arrangement(#[from] pm_geom::ArrangementError),
    /// The scene has no surfaces at all.
    #[error("the scene has no geometry")]
    NoGeometry,
    /// Geometry reaching ±[`pm_kdtree::MAX_COORDINATE`] (10¹⁸ m) or beyond: photons there
    /// cannot be stored and f32 no longer resolves a room's size.
    #[error(
        "the scene's geometry spans {min:?} to {max:?}; coordinates must stay within ±{limit:e} m (pm_kdtree::MAX_COORDINATE)",
        limit = pm_kdtree::MAX_COORDINATE
    )]
    GeometryOutOfRange {
        /// The bounds' lower corner.
        min: [f32; 3],
        /// The bounds' upper corner.
        max: [f32; 3],
    },
    /// `scenes::build` got a name it does not know.
    #[error("unknown scene {name:?}; the built-in scenes are: {valid}")]
    UnknownScene {
        /// The name asked for.
        name: String,
        /// The valid names, comma separated.
        valid: String,
    },
    /// The meshes hold more triangles than a scene may (checked before building).
    #[error("the meshes hold {triangles} triangles; a scene holds at most {limit} (MAX_SCENE_TRIANGLES)")]
    TooManyTriangles {
        /// Triangles in the meshes given (faces fan-triangulated).
        triangles: usize,
        /// The limit.
        limit: usize,
    },
    /// A scene generator got a parameter outside its range.
    #[error("{what}: {reason}")]
    InvalidParameter {
        /// Which parameter.
        what: String,
        /// What is wrong with it.
        reason: String,
    },
}

/// Why photons could not be traced.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum TraceError {
    /// Zero photons were asked for.
    #[error("zero photons requested; ask for at least one")]
    ZeroPhotons,
    /// More photon paths than [`crate::MAX_PHOTON_PATHS`].
    #[error("{photons} photon paths: more than the limit of {max}", max = crate::MAX_PHOTON_PATHS)]
    TooManyPhotons {
        /// Paths asked for.
        photons: u32,
    },
    /// The paths stored more photons than [`crate::MAX_STORED_PHOTONS`] (long diffuse paths in
    /// a bright closed scene); trace fewer paths.
    #[error("more than the limit of {limit} stored photons; trace fewer photon paths")]
    TooManyPhotonsStored {
        /// The limit.
        limit: u64,
    },
    /// The scene has no light.
    #[error("the scene has no light to emit photons from")]
    NoLights,
    /// The lights emit no power, or a light's power is negative or not finite.
    #[error(
        "light {light}: power {power:?} W; every light needs finite, non-negative power and the total must be positive"
    )]
    InvalidPower {
        /// Index of the (first) offending light, or the light count when the total is zero.
        light: usize,
        /// Its power.
        power: [f32; 3],
    },
    /// A photon handed to [`crate::TracedPhotons::new`] that no map can hold.
    #[error("map {map}, photon {index}: {reason}")]
    InvalidPhoton {
        /// The map (index in the list of maps).
        map: usize,
        /// The photon's index in that map's list.
        index: usize,
        /// What is wrong with it.
        reason: PhotonFault,
    },
    /// Camera-driven emission would emit more than [`crate::MAX_PHOTON_PATHS`] paths to
    /// trace the paths asked for.
    #[error(
        "{photons} photon paths traced on at a keep rate of {keep_rate:.4} means emitting more than the limit of {max}; trace fewer, or raise the guide's floor",
        max = crate::MAX_PHOTON_PATHS
    )]
    TooManyGuidedPhotons {
        /// Paths to be traced on.
        photons: u32,
        /// The guide's keep rate.
        keep_rate: f64,
    },
    /// Camera-driven emission options out of range.
    #[error("camera-driven emission: {0}")]
    InvalidGuide(String),
    /// The map assignment does not belong to this scene.
    #[error("map assignment covers {assigned} parts but the scene has {parts}")]
    AssignmentMismatch {
        /// Parts in the assignment.
        assigned: usize,
        /// Parts in the scene.
        parts: usize,
    },
}

/// What is wrong with a photon handed to [`crate::TracedPhotons::new`].
#[derive(Debug, Error, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum PhotonFault {
    /// Its position has a NaN or infinite coordinate.
    #[error("its position is not finite")]
    Position,
    /// Its direction has a NaN or infinite coordinate, or is zero.
    #[error("its direction is not finite and non-zero")]
    Direction,
    /// Its power has a NaN, infinite or negative channel.
    #[error("its power is not finite and non-negative")]
    Power,
}

/// Why photon maps could not be built.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MapError {
    /// The photons or the assignment do not match the scene.
    #[error(transparent)]
    Mismatch(#[from] TraceError),
    /// `PhotonMaps::validate` found a broken invariant.
    #[error("map {map}: {what}")]
    Invalid {
        /// The map.
        map: u32,
        /// What is wrong.
        what: String,
    },
    /// A photon tree could not be built.
    #[error("map {map}: {source}")]
    Tree {
        /// The map.
        map: u32,
        /// What was wrong.
        source: pm_kdtree::BuildError,
    },
}

/// Why a material could not be made from its parameters.
#[derive(Debug, Error, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum MaterialError {
    /// A parameter (or one channel of a colour) is NaN, infinite or outside its range.
    #[error("{parameter} is {value}: it must be {range}")]
    OutOfRange {
        /// The parameter's name (glTF's, e.g. `metallicFactor`).
        parameter: &'static str,
        /// The offending value (the first offending channel of a colour).
        value: f32,
        /// The allowed range, in words.
        range: &'static str,
    },
}
