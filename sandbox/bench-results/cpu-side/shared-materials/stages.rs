// The Extract and Prepare stages of 10,000 parallax entities timed without the Render stage
// between them (no GPU work pollutes the caches), each entity with a copy of the material or a
// handle to one shared (where the build has `Assets<ParallaxOcclusionMaterial>`): copy into
// plugin/examples/ and run `cargo run --release -p parallax-occlusion --example stages` on each
// build; a second argument times only the cases whose name holds it (`stages new walking`).
use pom::glam::{Quat, Vec3};
use pom::*;
fn case(percent: usize, walking: bool, shared: bool) -> Option<(f64, f64)> {
    let mut app = App::new();
    app.add_plugin(RenderPlugin::new(64, 64)).add_plugin(PomPlugin);
    app.finish().unwrap();
    let plane = app.resources.get_mut::<Assets<Mesh>>().unwrap().add(Mesh::plane(0.9));
    let handle = match app.resources.get_mut::<Assets<ParallaxOcclusionMaterial>>() {
        Some(store) => Some(store.add(ParallaxOcclusionMaterial::default())),
        None if shared => return None,
        None => None,
    };
    let side = 100usize;
    let mut movers = Vec::new();
    for index in 0..10000usize {
        let jitter = if walking { (index as f32 * 0.618_034).fract() - 0.5 } else { 0.0 };
        let place = Vec3::new((index % side) as f32 - 50.0, 0.0, (index / side) as f32 + jitter - 50.0);
        let e = app.world.spawn((plane.clone(), Transform::from_translation(place)));
        match (&handle, shared) {
            (Some(handle), true) => app.world.insert_one(e, handle.clone()).unwrap(),
            _ => app.world.insert_one(e, ParallaxOcclusionMaterial::default()).unwrap(),
        }
        if index % 100 < percent { movers.push((e, place)); }
    }
    app.world.spawn((Camera::perspective(60.0), Transform::from_xyz(0.0, 100.0, 100.0).looking_at(Vec3::ZERO, Vec3::Y)));
    app.world.spawn((DirectionalLight::default(), Transform::IDENTITY.looking_at(Vec3::new(-1.0, -2.0, -1.0), Vec3::Y)));
    app.update().unwrap();
    app.update().unwrap();
    let (mut ex, mut pr) = (Vec::new(), Vec::new());
    for frame in 0..300 {
        let f = frame as f32;
        for (e, place) in &movers {
            let mut t = app.world.get::<&mut Transform>(*e).unwrap();
            if walking { t.translation.z = place.z + 0.5 * (f * 0.05 + place.x).sin(); } else { t.rotation = Quat::from_rotation_y(f * 0.01); }
        }
        app.run_stages(&[Stage::PostUpdate]).unwrap();
        let t0 = std::time::Instant::now();
        app.run_stages(&[Stage::Extract]).unwrap();
        let t1 = std::time::Instant::now();
        app.run_stages(&[Stage::Prepare]).unwrap();
        let t2 = std::time::Instant::now();
        ex.push((t1 - t0).as_secs_f64() * 1e3);
        pr.push((t2 - t1).as_secs_f64() * 1e3);
        if frame % 50 == 49 { app.update().unwrap(); }
    }
    ex.sort_by(|a, b| a.partial_cmp(b).unwrap());
    pr.sort_by(|a, b| a.partial_cmp(b).unwrap());
    Some((ex[ex.len() / 2], pr[pr.len() / 2]))
}
fn main() {
    let label = std::env::args().nth(1).unwrap_or_default();
    let only = std::env::args().nth(2).unwrap_or_default();
    for (percent, walking, shared) in [(0, false, false), (10, false, false), (10, true, false), (100, false, false), (0, false, true), (10, false, true), (10, true, true)] {
        let what = format!("{percent}% {}{}", if walking { "walking" } else { "turning" }, if shared { ", shared" } else { "" });
        if !what.contains(&only) { continue; }
        match case(percent, walking, shared) {
            Some((ex, pr)) => println!("{label} {what}: extract {ex:.3} prepare {pr:.3}"),
            None => println!("{label} {what}: no shared materials in this build"),
        }
    }
}
