#!/bin/sh
# Regenerates the README's images from the code as it is. Run from the repository root, with
# the glTF corpus at ../shared/gltf-corpus for the last one: sh docs/images/regenerate.sh
# `cargo run` finds the example wherever CARGO_TARGET_DIR puts it.
set -eu
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cargo build --release --example render
render() { cargo run --quiet --release --example render -- "$@"; }
render --out "$out/cornell-box.exr"
render --mode final-gather --size 300x300 --photons 200000 --gather-rays 64 --spp 4 \
    --out "$out/cornell-box-final-gather.exr"
render --compare --scene lit-unlit-rooms --out "$out/lit-unlit-rooms-compare.exr"
render --scene touching-rooms --maps crease --exposure -3.5 --out "$out/touching-rooms-crease.exr"
render --scene touching-rooms --maps contact --exposure -3.5 --out "$out/touching-rooms-contact.exr"
render --scene solid-rooms-pierce --maps crease --size 400x200 --exposure -3.5 --out "$out/solid-rooms-crease.exr"
render --scene solid-rooms-pierce --maps contact --size 400x200 --exposure -3.5 --out "$out/solid-rooms-contact.exr"
render --scene examples/scenes/textured-room/textured-room.gltf --size 300x300 --photons 1000000 \
    --out "$out/textured-room.exr"
render --scene ../shared/gltf-corpus/cornell/007Renderer/cornell_box.gltf --size 300x300 \
    --out "$out/gltf-cornell-box.exr"
cp "$out"/*.png docs/images/
