//! Safe glTF 2.0 loading (`.gltf`, `.glb`) into a [`crate`] scene (filled in by the glTF issue).
