//! The pictures in docs/images are the code's output byte for byte: one of them, rendered as
//! `scripts/regenerate-images.sh` renders it, must equal the committed PNG (issue 32:
//! `cornell-box.png` had drifted from a fresh render by one step). When this fails after a
//! change that alters images on purpose, run `sh scripts/regenerate-images.sh docs/images`.

#[path = "support/example.rs"]
mod example;
#[path = "support/scratch.rs"]
mod scratch;

use std::path::Path;

#[test]
fn solid_rooms_contact_png_is_the_code_output() {
    let dir = scratch::Scratch::new("solid-rooms-contact");
    let out = dir.path("solid-rooms-contact.exr");
    // The script's line for this picture, with the output in the scratch folder.
    let args = [
        "--mode",
        "photon-map",
        "--scene",
        "solid-rooms-pierce",
        "--maps",
        "contact",
        "--size",
        "400x200",
        "--exposure",
        "-3.5",
        "--out",
        &out,
    ];
    let Some(output) = example::run(&args) else { return };
    example::assert_ok(&args, &output);
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/images/solid-rooms-contact.png");
    let fresh = std::fs::read(dir.0.join("solid-rooms-contact.png")).unwrap();
    let kept = std::fs::read(&committed).unwrap();
    assert!(
        fresh == kept,
        "{} differs from a fresh render ({} against {} bytes): regenerate it with `sh scripts/regenerate-images.sh docs/images`",
        committed.display(),
        kept.len(),
        fresh.len()
    );
}
