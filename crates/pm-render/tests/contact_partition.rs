//! Contact maps come only with the scene split for them: partitioning returns the split scene
//! and its maps together, a renderer takes that value, and no scene can be paired with an
//! assignment made for another.

use pm_render::{Disc, RenderSettings, Renderer};
use pm_trace::{Contact, CreaseAngle, MapAssignment, PartitionError, Partitioned, Partitioner, scenes};

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
fn contact_maps_come_with_the_split_scene() {
    let scene = scenes::build("touching-rooms").unwrap();
    let parts_before = scene.part_count();
    let contact = Contact::default().partition(scene.clone()).unwrap();
    let record = contact
        .record()
        .expect("the contact partition says what it found");
    assert!(record.counts().meetings() > 0, "{:?}", record.counts());
    // The floor under the dividing wall is cut: the scene the maps are for has more parts.
    assert!(contact.scene().part_count() > parts_before);
    assert_eq!(contact.assignment().part_count(), contact.scene().part_count());

    let crease = CreaseAngle::default().partition(scene).unwrap();
    assert!(crease.record().is_none());
    assert_eq!(crease.scene().part_count(), parts_before);
    assert!(contact.assignment().map_count() > crease.assignment().map_count());

    let rendered = Renderer::new(Disc, tiny_settings())
        .render(&contact, &())
        .unwrap();
    assert_eq!(rendered.stats.map_count, contact.assignment().map_count());
}

#[test]
fn an_assignment_for_another_scene_is_refused() {
    let contact = Contact::default()
        .partition(scenes::build("touching-rooms").unwrap())
        .unwrap();
    let unsplit = scenes::build("touching-rooms").unwrap();
    // The split scene's maps do not fit the scene as built.
    let refused = Partitioned::new(unsplit.clone(), contact.assignment().clone());
    assert_eq!(
        refused.err(),
        Some(PartitionError::AssignmentMismatch {
            scene_parts: unsplit.part_count(),
            assigned_parts: contact.scene().part_count(),
        })
    );
    let one_map = Partitioned::new(unsplit.clone(), MapAssignment::single(unsplit.part_count())).unwrap();
    assert!(one_map.record().is_none());
}
