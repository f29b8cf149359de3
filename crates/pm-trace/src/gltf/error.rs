//! The loader's typed errors: every one names the file and the glTF element at fault, so a
//! user can find the bad byte without a debugger.

use std::path::PathBuf;

/// Why a glTF file could not be loaded. The `Display` text names the file and the element
/// (`scene.gltf: mesh 3 primitive 0: index 255 out of range for 24 vertices`).
#[derive(Debug, thiserror::Error)]
pub enum GltfError {
    /// The scene file itself could not be opened or read.
    #[error("{file}: cannot read the file: {source}")]
    Io {
        /// The file that was being read.
        file: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The scene file is larger than [`GltfOptions::max_file_bytes`](super::GltfOptions).
    #[error("{file}: the file is larger than the limit of {limit} bytes")]
    FileTooLarge {
        /// The scene file.
        file: PathBuf,
        /// The limit in force.
        limit: u64,
    },
    /// A `.glb` container whose header or chunk lengths disagree with the file.
    #[error("{file}: malformed GLB container: {reason}")]
    Glb {
        /// The scene file.
        file: PathBuf,
        /// What was wrong with the container.
        reason: String,
    },
    /// The JSON could not be parsed or failed the glTF crate's validation.
    #[error("{file}: invalid glTF: {message}")]
    Parse {
        /// The scene file.
        file: PathBuf,
        /// The parser's or validator's message.
        message: String,
    },
    /// The gltf crate panicked on this file. The loader catches the panic and reports it here
    /// (the process's panic hook may still have printed a message).
    #[error("{file}: the glTF parser panicked on this file: {message}")]
    Panic {
        /// The scene file.
        file: PathBuf,
        /// The panic payload, when it was a string.
        message: String,
    },
    /// A buffer could not be resolved: refused URI, missing or oversized file, bad data URI.
    #[error("{file}: buffer {buffer}: {reason}")]
    Buffer {
        /// The scene file.
        file: PathBuf,
        /// Index of the buffer in `buffers`.
        buffer: usize,
        /// What was wrong.
        reason: BufferError,
    },
    /// An accessor (or the buffer view under it) does not fit its data or has the wrong type.
    #[error("{file}: accessor {accessor}: {reason}")]
    Accessor {
        /// The scene file.
        file: PathBuf,
        /// Index of the accessor in `accessors`.
        accessor: usize,
        /// What was wrong.
        reason: String,
    },
    /// A mesh primitive is unusable: an index out of range, a non-finite position, a missing
    /// accessor or material.
    #[error("{file}: mesh {mesh} primitive {primitive}: {reason}")]
    Primitive {
        /// The scene file.
        file: PathBuf,
        /// Index of the mesh in `meshes`.
        mesh: usize,
        /// Index of the primitive in the mesh.
        primitive: usize,
        /// What was wrong.
        reason: String,
    },
    /// The node graph is unusable: a cycle, a node reached twice, too deep, a missing node,
    /// a non-finite transform, a missing mesh, camera or light.
    #[error("{file}: node {node}: {reason}")]
    Node {
        /// The scene file.
        file: PathBuf,
        /// Index of the node in `nodes`.
        node: usize,
        /// What was wrong.
        reason: String,
    },
    /// A node's `translation`, `rotation`, `scale` or `matrix`, read again from the JSON text
    /// in f64 (the gltf crate holds them in f32), is not an array of the field's length (3, 4,
    /// 3, 16) of numbers finite in f64.
    #[error("{file}: node {node} {field}: {reason}")]
    NodeTransform {
        /// The scene file.
        file: PathBuf,
        /// Index of the node in `nodes`.
        node: usize,
        /// The field, as the JSON names it (`"translation"`, `"rotation"`, `"scale"`, `"matrix"`).
        field: &'static str,
        /// What was wrong.
        reason: String,
    },
    /// The JSON text, read again for the nodes' f64 transforms, holds a different number of
    /// nodes than the gltf crate parsed from it.
    #[error("{file}: the JSON text holds {found} nodes where the glTF parser read {parsed}")]
    NodeCount {
        /// The scene file.
        file: PathBuf,
        /// Nodes in the JSON text's `nodes` array.
        found: usize,
        /// Nodes the gltf crate parsed.
        parsed: usize,
    },
    /// The scene would take more memory than
    /// [`GltfOptions::max_scene_bytes`](super::GltfOptions) (counted before decoding).
    #[error(
        "{file}: node {node} mesh {mesh}: the scene would take more than {budget} bytes (GltfOptions::max_scene_bytes); it needs at least {needed}"
    )]
    SceneTooLarge {
        /// The scene file.
        file: PathBuf,
        /// The node whose placement passed the budget.
        node: usize,
        /// The mesh it places.
        mesh: usize,
        /// The budget in force.
        budget: u64,
        /// The bytes counted up to and with this placement.
        needed: u64,
    },
    /// The scene builder refused the content (see [`SceneError`](crate::SceneError)).
    #[error("{file}: {source}")]
    Build {
        /// The scene file.
        file: PathBuf,
        /// The builder's reason.
        source: crate::error::SceneError,
    },
    /// An image a material uses could not be read or decoded: outside the folder, missing,
    /// truncated, not PNG or JPEG, or larger than [`GltfOptions::max_texture_pixels`](super::GltfOptions).
    #[error("{file}: image {image}: {reason}")]
    Image {
        /// The scene file.
        file: PathBuf,
        /// Index of the image (or of the texture when it names no image).
        image: usize,
        /// What was wrong.
        reason: String,
    },
    /// The file names a scene that does not exist, holds no triangles, or has no light
    /// while [`GltfOptions::default_light`](super::GltfOptions) is off.
    #[error("{file}: {reason}")]
    Scene {
        /// The scene file.
        file: PathBuf,
        /// What was wrong.
        reason: String,
    },
}

impl GltfError {
    /// A short, stable name for the kind of error (`"buffer/escapes-folder"`, `"node"`, ...),
    /// for counting errors by kind in logs and tests.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Io { .. } => "io",
            Self::FileTooLarge { .. } => "file-too-large",
            Self::Glb { .. } => "glb",
            Self::Parse { .. } => "parse",
            Self::Panic { .. } => "panic",
            Self::Buffer { reason, .. } => reason.kind(),
            Self::Accessor { .. } => "accessor",
            Self::Primitive { .. } => "primitive",
            Self::Node { .. } => "node",
            Self::NodeTransform { .. } => "node-transform",
            Self::NodeCount { .. } => "node-count",
            Self::Build { .. } => "build",
            Self::SceneTooLarge { .. } => "scene-too-large",
            Self::Scene { .. } => "scene",
            Self::Image { .. } => "image",
        }
    }
}

/// Why one buffer could not be resolved.
#[derive(Debug, thiserror::Error)]
pub enum BufferError {
    /// The URI has a scheme other than `data:` (`file:`, `http:`, ...). Only relative paths
    /// and data URIs are followed.
    #[error("URI {uri:?} has a scheme; only relative paths and data: URIs are allowed")]
    Scheme {
        /// The URI as written in the file.
        uri: String,
    },
    /// The URI is an absolute path.
    #[error("URI {uri:?} is an absolute path; only paths relative to the scene are allowed")]
    Absolute {
        /// The URI as written in the file.
        uri: String,
    },
    /// The URI has an invalid percent escape (such as `%FF`, which is not UTF-8).
    #[error("URI {uri:?} has an invalid percent escape")]
    BadEscape {
        /// The URI as written in the file.
        uri: String,
    },
    /// After percent-decoding and canonicalisation the path leaves the scene's folder.
    #[error("URI {uri:?} leads outside the scene's folder")]
    EscapesFolder {
        /// The URI as written in the file.
        uri: String,
    },
    /// The path does not name a regular file (a directory, a device such as `/dev/zero`).
    #[error("URI {uri:?} is not a regular file")]
    NotRegularFile {
        /// The URI as written in the file.
        uri: String,
    },
    /// The referenced file is missing or unreadable.
    #[error("URI {uri:?} cannot be read: {source}")]
    Unreadable {
        /// The URI as written in the file.
        uri: String,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The data holds more bytes than the buffer's declared `byteLength`.
    #[error("holds more than its declared byteLength of {declared} bytes")]
    LongerThanDeclared {
        /// The declared `byteLength`.
        declared: u64,
    },
    /// The data holds fewer bytes than the buffer's declared `byteLength`.
    #[error("holds {actual} bytes, fewer than its declared byteLength of {declared}")]
    ShorterThanDeclared {
        /// The declared `byteLength`.
        declared: u64,
        /// The bytes found.
        actual: u64,
    },
    /// The declared `byteLength` exceeds [`GltfOptions::max_file_bytes`](super::GltfOptions).
    #[error("declared byteLength {declared} exceeds the limit of {limit} bytes")]
    TooLarge {
        /// The declared `byteLength`.
        declared: u64,
        /// The limit in force.
        limit: u64,
    },
    /// The buffers' files and data URIs together hold more than
    /// [`GltfOptions::max_file_bytes`](super::GltfOptions) (each distinct file counted once).
    #[error("the buffers hold more than the limit of {limit} bytes in all")]
    TotalTooLarge {
        /// The limit in force.
        limit: u64,
    },
    /// A `data:` URI that is not base64 or does not decode.
    #[error("malformed data: URI: {reason}")]
    BadDataUri {
        /// What was wrong.
        reason: String,
    },
    /// A buffer without a URI in a file that has no GLB binary chunk for it.
    #[error("has no URI and the file has no GLB binary chunk")]
    MissingBinChunk,
}

impl BufferError {
    /// A short, stable name for the kind of buffer error, prefixed with `buffer/`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Scheme { .. } => "buffer/scheme",
            Self::Absolute { .. } => "buffer/absolute",
            Self::BadEscape { .. } => "buffer/bad-escape",
            Self::EscapesFolder { .. } => "buffer/escapes-folder",
            Self::NotRegularFile { .. } => "buffer/not-regular-file",
            Self::Unreadable { .. } => "buffer/unreadable",
            Self::LongerThanDeclared { .. } => "buffer/longer-than-declared",
            Self::ShorterThanDeclared { .. } => "buffer/shorter-than-declared",
            Self::TooLarge { .. } => "buffer/too-large",
            Self::TotalTooLarge { .. } => "buffer/total-too-large",
            Self::BadDataUri { .. } => "buffer/bad-data-uri",
            Self::MissingBinChunk => "buffer/missing-bin-chunk",
        }
    }
}
