//! Carrying out a script's steps: frames, material changes, camera and light moves, spins and
//! captures here; the expectations in `expect`.

use glam::{Quat, Vec2, Vec3};
use hecs::Entity;
use image::RgbaImage;

use super::{Capture, Runner, look, vec3};
use crate::picking::camera_ray;
use crate::render::Renderer;
use crate::script::format::{MaterialPatch, Step};
use crate::script::lights::light_towards;
use crate::script::stats::SurfaceMask;
use crate::script::{CapturePath, Outcome};
use crate::{
    Assets, DebugView, GpuContext, Mesh, ParallaxOcclusionMaterial, Transform, pick_entity,
};

/// How a step is named in the report.
fn description(step: &Step) -> String {
    match step {
        Step::Advance { frames } => format!("Advance {frames}"),
        Step::Set { entity, .. } => format!("Set {entity:?}"),
        Step::Camera { .. } => "Camera".into(),
        Step::OrbitCamera { degrees } => format!("OrbitCamera {degrees}°"),
        Step::MoveLight { light, .. } => format!("MoveLight {light}"),
        Step::Spin {
            entity,
            degrees_per_frame,
        } => format!("Spin {entity:?} {degrees_per_frame}°/frame"),
        Step::Capture { name, .. } => format!("Capture {name:?}"),
        Step::ExpectMatch { capture, .. } => format!("ExpectMatch {capture:?}"),
        Step::ExpectStat { capture, .. } => format!("ExpectStat {capture:?}"),
        Step::ExpectMonotonic { .. } => "ExpectMonotonic".into(),
    }
}

impl Runner<'_> {
    /// Carries out one step; returns its description and what became of it.
    pub(super) fn execute(&mut self, step: &Step) -> Result<(String, Outcome), String> {
        let outcome = match step {
            Step::Advance { frames } => {
                self.advance(*frames)?;
                Outcome::Done
            }
            Step::Set { entity, material } => {
                self.set_materials(entity, material)?;
                Outcome::Done
            }
            Step::Camera { position, target } => {
                self.place_camera(vec3(*position), vec3(*target));
                Outcome::Done
            }
            Step::OrbitCamera { degrees } => {
                self.orbit_camera(*degrees);
                Outcome::Done
            }
            Step::MoveLight {
                light,
                direction,
                position,
            } => {
                self.move_light(*light, direction.map(vec3), position.map(vec3));
                Outcome::Done
            }
            Step::Spin {
                entity,
                degrees_per_frame,
            } => {
                self.spins.insert(entity.clone(), *degrees_per_frame);
                Outcome::Done
            }
            Step::Capture { name, debug_view } => {
                self.keep_capture(name, *debug_view)?;
                Outcome::Done
            }
            Step::ExpectMatch {
                capture,
                reference,
                tolerance,
            } => self.expect_match(capture, reference, tolerance)?,
            Step::ExpectStat {
                capture,
                stat,
                rect,
                min,
                max,
            } => self.expect_stat(capture, stat, *rect, *min, *max)?,
            Step::ExpectMonotonic {
                captures,
                stat,
                rect,
                increasing,
            } => self.expect_monotonic(captures, stat, *rect, *increasing)?,
        };
        Ok((description(step), outcome))
    }

    /// Runs `frames` updates.
    fn advance(&mut self, frames: u32) -> Result<(), String> {
        for _ in 0..frames {
            self.frame()?;
        }
        Ok(())
    }

    /// One update, with spins applied first; fails on any GPU error the frame raised.
    fn frame(&mut self) -> Result<(), String> {
        for (name, degrees) in &self.spins {
            for entity in self.entities.get(name).into_iter().flatten() {
                if let Ok(mut transform) = self.app.world.get::<&mut Transform>(*entity) {
                    transform.rotation =
                        Quat::from_rotation_y(degrees.to_radians()) * transform.rotation;
                }
            }
        }
        self.app.update().map_err(|error| error.to_string())?;
        let errors = self
            .app
            .resources
            .get::<GpuContext>()
            .map(GpuContext::take_uncaptured_errors)
            .unwrap_or_default();
        match errors.first() {
            Some(error) => Err(format!("GPU error: {error}")),
            None => Ok(()),
        }
    }

    /// Applies `patch` to every parallax material of entity `name` (its own, or a glTF's).
    fn set_materials(&mut self, name: &str, patch: &MaterialPatch) -> Result<(), String> {
        let targets = self.materials_of(name);
        if targets.is_empty() {
            return Err(format!("entity {name:?} has no parallax material"));
        }
        for target in targets {
            if let Ok(mut component) = self.app.world.get::<&mut ParallaxOcclusionMaterial>(target)
            {
                // The loader could check a glTF file's materials only parameter by parameter.
                let mut changed = component.clone();
                patch.apply(&mut changed);
                changed
                    .validate()
                    .map_err(|problem| format!("entity {name:?}: {problem}"))?;
                *component = changed;
            }
        }
        Ok(())
    }

    /// The entities of script entity `name` that have a parallax material.
    fn materials_of(&mut self, name: &str) -> Vec<Entity> {
        self.entities
            .get(name)
            .into_iter()
            .flatten()
            .copied()
            .filter(|entity| {
                self.app
                    .world
                    .satisfies::<&ParallaxOcclusionMaterial>(*entity)
            })
            .collect()
    }

    /// Moves the camera to `position`, looking at `target` (which later orbits turn about).
    fn place_camera(&mut self, position: Vec3, target: Vec3) {
        self.target = target;
        if let Ok(mut transform) = self.app.world.get::<&mut Transform>(self.camera) {
            *transform = look(position, self.target);
        }
        self.camera_cut();
    }

    /// The camera jumped: TAA's history says nothing of the next frame.
    fn camera_cut(&mut self) {
        if let Some(history) = self.app.resources.get_mut::<crate::TemporalHistory>() {
            history.reset();
        }
    }

    /// Frames a capture renders: under TAA the jitter's whole cycle, so a still scene's
    /// history has settled; else one.
    fn capture_frames(&self) -> u32 {
        let taa = self
            .app
            .world
            .get::<&crate::AntiAliasing>(self.camera)
            .is_ok_and(|aa| *aa == crate::AntiAliasing::Taa);
        if !taa {
            return 1;
        }
        self.app
            .world
            .get::<&crate::TemporalAntiAliasing>(self.camera)
            .map_or(1, |settings| settings.settling_frames())
    }

    /// Turns the camera by `degrees` about the vertical axis through its target.
    fn orbit_camera(&mut self, degrees: f32) {
        let target = self.target;
        if let Ok(mut transform) = self.app.world.get::<&mut Transform>(self.camera) {
            let offset =
                Quat::from_rotation_y(degrees.to_radians()) * (transform.translation - target);
            *transform = look(target + offset, target);
        }
        self.camera_cut();
    }

    /// Turns script light `light` towards `direction` and/or moves it to `position`.
    fn move_light(&mut self, light: usize, direction: Option<Vec3>, position: Option<Vec3>) {
        let entity = self.lights[light];
        if let Ok(mut transform) = self.app.world.get::<&mut Transform>(entity) {
            if let Some(direction) = direction {
                // Turned in place: a spot keeps its position.
                let translation = transform.translation;
                *transform = light_towards(direction);
                transform.translation = translation;
            }
            if let Some(position) = position {
                transform.translation = position;
            }
        }
    }

    /// Renders a frame (with `view` on every parallax material, if given) and keeps it as
    /// capture `name`.
    fn keep_capture(&mut self, name: &str, view: Option<DebugView>) -> Result<(), String> {
        let image = self.capture(view)?;
        let path = self.last_frame_path()?;
        let surface = match view {
            Some(_) => Some(self.parallax_surface(image.dimensions())?),
            None => None,
        };
        self.captures.insert(
            name.to_owned(),
            Capture {
                image,
                surface,
                path,
            },
        );
        Ok(())
    }

    /// The pixels of a `size` frame, as the camera now sees it, whose nearest polygon has a
    /// parallax material: what a debug view's statistic counts.
    fn parallax_surface(&self, (width, height): (u32, u32)) -> Result<SurfaceMask, String> {
        let world = &self.app.world;
        let meshes = self
            .app
            .resources
            .get::<Assets<Mesh>>()
            .ok_or("no mesh store")?;
        let viewport = Vec2::new(width as f32, height as f32);
        Ok(SurfaceMask::new(width, height, |x, y| {
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            camera_ray(world, viewport, centre)
                .and_then(|ray| pick_entity(world, meshes, ray))
                .is_some_and(|hit| world.satisfies::<&ParallaxOcclusionMaterial>(hit.entity))
        }))
    }

    /// Renders one frame and reads it back; a debug view is set for this frame only.
    fn capture(&mut self, view: Option<DebugView>) -> Result<RgbaImage, String> {
        let mut saved = Vec::new();
        if let Some(view) = view {
            for (entity, material) in self
                .app
                .world
                .query_mut::<(Entity, &mut ParallaxOcclusionMaterial)>()
            {
                saved.push((entity, material.debug_view));
                material.debug_view = view;
            }
        }
        let frames = self.capture_frames();
        if frames > 1 {
            // A fresh history: the capture is the plain mean of one whole jitter cycle, not a
            // blend with what the earlier steps showed (another debug view, say).
            self.camera_cut();
        }
        let result = (0..frames)
            .try_for_each(|_| self.frame())
            .and_then(|()| crate::capture(&self.app).map_err(|error| error.to_string()));
        for (entity, view) in saved {
            if let Ok(mut material) = self.app.world.get::<&mut ParallaxOcclusionMaterial>(entity) {
                material.debug_view = view;
            }
        }
        result
    }

    /// The path the renderer ran the last frame on (a deferred request can fall back to
    /// forward, which the images alone would not show).
    fn last_frame_path(&self) -> Result<CapturePath, String> {
        let renderer = self
            .app
            .resources
            .get::<Renderer>()
            .ok_or("the app has no renderer")?;
        Ok(
            match (renderer.runs_deferred(), renderer.deferred_unavailable()) {
                (true, _) => CapturePath::Deferred,
                (false, Some(reason)) => CapturePath::FellBackToForward(reason),
                (false, None) => CapturePath::Forward,
            },
        )
    }
}
