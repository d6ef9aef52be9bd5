//! Asset handle lifetimes.

use pom::{App, Assets, Stage};

#[test]
fn an_asset_lives_while_any_handle_clone_does() {
    let mut assets = Assets::<u32>::default();
    let first = assets.add(1);
    let second = first.clone();
    let id = first.id();
    drop(first);
    assert_eq!(assets.free_unused(), 0);
    assert_eq!(assets.get(id), Some(&1));
    drop(second);
    assert_eq!(assets.free_unused(), 1);
    assert_eq!(assets.get(id), None);
    assert!(assets.is_empty());
}

#[test]
fn a_stale_id_does_not_see_the_asset_that_reused_its_slot() {
    let mut assets = Assets::<&str>::default();
    let old = assets.add("old");
    let old_id = old.id();
    drop(old);
    assets.free_unused();
    let new = assets.add("new");
    assert_eq!(new.id().index(), old_id.index(), "the slot is reused");
    assert_eq!(assets.get(old_id), None);
    assert_eq!(assets.get(&new), Some(&"new"));
    assert_ne!(old_id, new.id());
}

#[test]
fn mutable_access_bumps_the_version() {
    let mut assets = Assets::<u32>::default();
    let handle = assets.add(1);
    let added = assets.version(&handle).unwrap();
    let _ = assets.get(&handle);
    assert_eq!(
        assets.version(&handle),
        Some(added),
        "reading changes nothing"
    );
    *assets.get_mut(&handle).unwrap() = 2;
    let edited = assets.version(&handle).unwrap();
    assert!(edited > added);
    for (_, value) in assets.iter_mut() {
        *value += 1;
    }
    assert!(assets.version(&handle).unwrap() > edited);
}

#[test]
fn handles_held_by_entities_keep_assets_alive_across_updates() {
    let mut app = App::new();
    app.insert_resource(Assets::<String>::default());
    app.add_system(Stage::PostUpdate, pom::free_unused_assets::<String>);
    let handle = app
        .resources
        .get_mut::<Assets<String>>()
        .unwrap()
        .add("mesh".into());
    let id = handle.id();
    let entity = app.world.spawn((handle,));
    app.update().unwrap();
    assert!(app.resources.get::<Assets<String>>().unwrap().contains(id));
    app.world.despawn(entity).unwrap();
    app.update().unwrap();
    assert!(!app.resources.get::<Assets<String>>().unwrap().contains(id));
}
