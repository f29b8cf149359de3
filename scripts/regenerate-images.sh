#!/bin/sh
# Renders the pictures of the README and the user guide from the code as it is, into the folder
# named (default target/images; `sh scripts/regenerate-images.sh docs/images` replaces the
# repository's own). Run from the repository root. The renders are deterministic at any thread
# count, so two runs write byte-identical PNGs (tests/readme_images.rs checks one of them
# against docs/images). The glTF Cornell box needs the glTF corpus at ../shared/gltf-corpus
# (or PM_GLTF_CORPUS) and is skipped without it. The convergence charts in docs/images are the
# convergence example's (`--out-dir docs`), not this script's.
set -eu
dest=${1:-target/images}
corpus=${PM_GLTF_CORPUS:-../shared/gltf-corpus}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cargo build --quiet --release --example render
# `cargo run` finds the example wherever CARGO_TARGET_DIR puts it.
render() { cargo run --quiet --release --example render -- "$@"; }
# The default render: final gather, 16 samples × 4 gather rays per pixel.
render --out "$out/cornell-box.exr"
# The report's view: the photon maps seen directly.
render --mode photon-map --out "$out/cornell-box-photon-map.exr"
render --mode final-gather --size 300x300 --photons 200000 --gather-rays 64 --spp 4 \
    --out "$out/cornell-box-final-gather.exr"
render --compare --scene lit-unlit-rooms --out "$out/lit-unlit-rooms-compare.exr"
render --mode photon-map --scene touching-rooms --maps crease --exposure -3.5 \
    --out "$out/touching-rooms-crease.exr"
render --mode photon-map --scene touching-rooms --maps contact --exposure -3.5 \
    --out "$out/touching-rooms-contact.exr"
render --mode photon-map --scene solid-rooms-pierce --maps crease --size 400x200 --exposure -3.5 \
    --out "$out/solid-rooms-crease.exr"
render --mode photon-map --scene solid-rooms-pierce --maps contact --size 400x200 --exposure -3.5 \
    --out "$out/solid-rooms-contact.exr"
render --mode photon-map --scene examples/scenes/textured-room/textured-room.gltf --size 300x300 \
    --photons 1000000 --out "$out/textured-room.exr"
# glTF metallic-roughness: gold blocks at roughness 0.2 and 0.5 on a glossy dielectric floor.
render --scene glossy-cornell-box --size 300x300 --out "$out/glossy-cornell-box.exr"
gltf="$corpus/cornell/007Renderer/cornell_box.gltf"
if [ -f "$gltf" ]; then
    render --mode photon-map --scene "$gltf" --size 300x300 --out "$out/gltf-cornell-box.exr"
else
    echo "no glTF corpus at $corpus: gltf-cornell-box.png not rendered" >&2
fi
# The photon cache's debug view (docs/cache.md): distance to the answering cache point.
cargo run --quiet --release --example cache_query -- --view radii --size 160x160 --out "$out/cache-radii.png"
mkdir -p "$dest"
cp "$out"/*.png "$dest"/
echo "wrote $(ls "$out"/*.png | wc -l) pictures to $dest"
