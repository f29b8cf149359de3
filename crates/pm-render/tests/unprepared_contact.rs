//! A renderer refuses a contact partition over a scene not split along its contacts, which
//! would otherwise render with the crease-angle maps without a word.

use pm_render::{Disc, RenderError, RenderSettings, Renderer};
use pm_trace::{Contact, PartitionError, Partitioner, scenes};

fn tiny_settings() -> RenderSettings {
    RenderSettings {
        width: 8,
        height: 6,
        photons: 2_000,
        samples_per_pixel: 1,
        ..RenderSettings::default()
    }
}

#[test]
fn contact_without_prepare_scene_is_refused_not_rendered_as_crease_angle() {
    let scene = scenes::build("touching-rooms").unwrap();
    let renderer = Renderer::new(Disc, tiny_settings());
    let refused = renderer.render(&scene, &Contact::default(), &());
    assert!(
        matches!(
            refused,
            Err(RenderError::Partition(PartitionError::NotSplitAtContacts))
        ),
        "got {:?}",
        refused.map(|r| r.stats)
    );
    let prepared = Contact::default().prepare_scene(scene).unwrap();
    let rendered = renderer.render(&prepared, &Contact::default(), &()).unwrap();
    assert!(rendered.stats.map_count > 0);
}
