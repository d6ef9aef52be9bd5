//! Input as resources a game's systems read: keys and mouse buttons held, pressed or released
//! this frame, the mouse's motion and scroll summed over the frame, the cursor, and the window's
//! own events. The runner queues winit's events as they arrive; [`update_input`] applies them
//! in [`crate::Stage::PreUpdate`], so every system of a frame sees the same input.

use std::collections::HashSet;
use std::hash::Hash;

use glam::Vec2;
use winit::event::{ElementState, MouseScrollDelta, WindowEvent};
use winit::keyboard::PhysicalKey;

use crate::Resources;

/// A key on the keyboard, by its place (winit's physical key codes: `KeyCode::KeyW` is the key
/// where W is on a US layout, whatever the layout).
pub use winit::keyboard::KeyCode;

/// A mouse button.
pub use winit::event::MouseButton;

/// Which buttons of one kind are held, and which went down or up this frame. A resource for
/// [`KeyCode`] and for [`MouseButton`].
///
/// # Example
/// ```
/// use pom::window::{ButtonInput, KeyCode};
/// let mut keys = ButtonInput::default();
/// keys.press(KeyCode::Space);
/// assert!(keys.pressed(KeyCode::Space) && keys.just_pressed(KeyCode::Space));
/// keys.clear_just();
/// assert!(keys.pressed(KeyCode::Space) && !keys.just_pressed(KeyCode::Space));
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ButtonInput<T: Copy + Eq + Hash> {
    pressed: HashSet<T>,
    just_pressed: HashSet<T>,
    just_released: HashSet<T>,
}

impl<T: Copy + Eq + Hash> Default for ButtonInput<T> {
    fn default() -> Self {
        Self {
            pressed: HashSet::new(),
            just_pressed: HashSet::new(),
            just_released: HashSet::new(),
        }
    }
}

impl<T: Copy + Eq + Hash> ButtonInput<T> {
    /// Records `button` going down (a key's auto-repeat is not a new press).
    pub fn press(&mut self, button: T) {
        if self.pressed.insert(button) {
            self.just_pressed.insert(button);
        }
    }

    /// Records `button` going up.
    pub fn release(&mut self, button: T) {
        if self.pressed.remove(&button) {
            self.just_released.insert(button);
        }
    }

    /// Releases every held button (the window lost focus: their releases go elsewhere).
    pub fn release_all(&mut self) {
        self.just_released.extend(self.pressed.drain());
    }

    /// Whether `button` is held.
    pub fn pressed(&self, button: T) -> bool {
        self.pressed.contains(&button)
    }

    /// Whether `button` went down this frame.
    pub fn just_pressed(&self, button: T) -> bool {
        self.just_pressed.contains(&button)
    }

    /// Whether `button` went up this frame.
    pub fn just_released(&self, button: T) -> bool {
        self.just_released.contains(&button)
    }

    /// Whether any of `buttons` is held.
    pub fn any_pressed(&self, buttons: impl IntoIterator<Item = T>) -> bool {
        buttons.into_iter().any(|button| self.pressed(button))
    }

    /// The held buttons, in no order.
    pub fn get_pressed(&self) -> impl Iterator<Item = T> + '_ {
        self.pressed.iter().copied()
    }

    /// Forgets this frame's presses and releases (the buttons stay held): the start of a frame.
    pub fn clear_just(&mut self) {
        self.just_pressed.clear();
        self.just_released.clear();
    }
}

/// How far the mouse moved this frame, in its own units (raw motion, not the cursor: it goes on
/// at the screen's edge). A resource.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MouseMotion {
    /// Right and down are positive.
    pub delta: Vec2,
}

/// How far the wheel or touchpad scrolled this frame. A resource.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MouseScroll {
    /// Wheel steps (lines); up and right are positive.
    pub lines: Vec2,
    /// Touchpad pixels; up and right are positive.
    pub pixels: Vec2,
}

/// Where the cursor is over the window, in physical pixels from its top-left corner; `None`
/// while it is outside. A resource.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CursorPosition(pub Option<Vec2>);

/// What happened to the window this frame. A resource.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct WindowEvents {
    /// Its new inner size in physical pixels, if it changed.
    pub resized: Option<(u32, u32)>,
    /// Whether it gained (`true`) or lost focus, if either happened.
    pub focused: Option<bool>,
    /// Whether the user asked to close it (the runner then exits after this frame).
    pub close_requested: bool,
}

/// One input event as the runner queued it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum InputEvent {
    Key { key: KeyCode, down: bool },
    Mouse { button: MouseButton, down: bool },
    Motion(Vec2),
    Scroll { lines: Vec2, pixels: Vec2 },
    Cursor(Option<Vec2>),
    Resized(u32, u32),
    Focused(bool),
    CloseRequested,
}

impl InputEvent {
    /// The input a winit window event carries: keys, mouse buttons, the cursor and the wheel
    /// (window events such as resizes are the runner's to queue).
    pub(crate) fn from_window_event(event: &WindowEvent) -> Option<Self> {
        match event {
            WindowEvent::KeyboardInput { event, .. } => match event.physical_key {
                PhysicalKey::Code(key) => Some(Self::Key {
                    key,
                    down: event.state == ElementState::Pressed,
                }),
                PhysicalKey::Unidentified(_) => None,
            },
            WindowEvent::MouseInput { state, button, .. } => Some(Self::Mouse {
                button: *button,
                down: *state == ElementState::Pressed,
            }),
            WindowEvent::CursorMoved { position, .. } => Some(Self::Cursor(Some(Vec2::new(
                position.x as f32,
                position.y as f32,
            )))),
            WindowEvent::CursorLeft { .. } => Some(Self::Cursor(None)),
            WindowEvent::MouseWheel { delta, .. } => {
                let (lines, pixels) = match delta {
                    MouseScrollDelta::LineDelta(x, y) => (Vec2::new(*x, *y), Vec2::ZERO),
                    MouseScrollDelta::PixelDelta(p) => {
                        (Vec2::ZERO, Vec2::new(p.x as f32, p.y as f32))
                    }
                };
                Some(Self::Scroll { lines, pixels })
            }
            _ => None,
        }
    }
}

/// Events queued since the last frame's [`update_input`]. A resource.
#[derive(Debug, Default)]
pub(crate) struct PendingInput(pub(crate) Vec<InputEvent>);

/// The input resources every windowed app has.
pub(crate) fn insert_input_resources(resources: &mut Resources) {
    resources.get_or_default::<ButtonInput<KeyCode>>();
    resources.get_or_default::<ButtonInput<MouseButton>>();
    resources.get_or_default::<MouseMotion>();
    resources.get_or_default::<MouseScroll>();
    resources.get_or_default::<CursorPosition>();
    resources.get_or_default::<WindowEvents>();
    resources.get_or_default::<PendingInput>();
}

/// Starts a frame's input: forgets the last frame's presses, motion and window events, then
/// applies the events queued since. A [`crate::Stage::PreUpdate`] system of
/// [`super::WindowPlugin`].
pub fn update_input(_: &mut hecs::World, resources: &mut Resources) {
    let events = std::mem::take(&mut resources.get_or_default::<PendingInput>().0);
    resources
        .get_or_default::<ButtonInput<KeyCode>>()
        .clear_just();
    resources
        .get_or_default::<ButtonInput<MouseButton>>()
        .clear_just();
    *resources.get_or_default::<MouseMotion>() = MouseMotion::default();
    *resources.get_or_default::<MouseScroll>() = MouseScroll::default();
    *resources.get_or_default::<WindowEvents>() = WindowEvents::default();
    for event in events {
        match event {
            InputEvent::Key { key, down } => {
                let keys = resources.get_or_default::<ButtonInput<KeyCode>>();
                if down {
                    keys.press(key)
                } else {
                    keys.release(key)
                }
            }
            InputEvent::Mouse { button, down } => {
                let buttons = resources.get_or_default::<ButtonInput<MouseButton>>();
                if down {
                    buttons.press(button)
                } else {
                    buttons.release(button)
                }
            }
            InputEvent::Motion(delta) => resources.get_or_default::<MouseMotion>().delta += delta,
            InputEvent::Scroll { lines, pixels } => {
                let scroll = resources.get_or_default::<MouseScroll>();
                scroll.lines += lines;
                scroll.pixels += pixels;
            }
            InputEvent::Cursor(position) => {
                resources.get_or_default::<CursorPosition>().0 = position;
            }
            InputEvent::Resized(width, height) => {
                resources.get_or_default::<WindowEvents>().resized = Some((width, height));
            }
            InputEvent::Focused(focused) => {
                resources.get_or_default::<WindowEvents>().focused = Some(focused);
                if !focused {
                    resources
                        .get_or_default::<ButtonInput<KeyCode>>()
                        .release_all();
                    resources
                        .get_or_default::<ButtonInput<MouseButton>>()
                        .release_all();
                }
            }
            InputEvent::CloseRequested => {
                resources.get_or_default::<WindowEvents>().close_requested = true;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(resources: &mut Resources, events: &[InputEvent]) {
        resources
            .get_or_default::<PendingInput>()
            .0
            .extend_from_slice(events);
        update_input(&mut hecs::World::new(), resources);
    }

    #[test]
    fn a_press_is_just_pressed_for_one_frame_and_held_until_released() {
        let mut resources = Resources::default();
        let down = InputEvent::Key {
            key: KeyCode::KeyW,
            down: true,
        };
        let up = InputEvent::Key {
            key: KeyCode::KeyW,
            down: false,
        };
        frame(&mut resources, &[down]);
        let keys = resources.get::<ButtonInput<KeyCode>>().unwrap();
        assert!(keys.pressed(KeyCode::KeyW) && keys.just_pressed(KeyCode::KeyW));
        // Auto-repeat while held is not a new press.
        frame(&mut resources, &[down]);
        let keys = resources.get::<ButtonInput<KeyCode>>().unwrap();
        assert!(keys.pressed(KeyCode::KeyW) && !keys.just_pressed(KeyCode::KeyW));
        frame(&mut resources, &[up]);
        let keys = resources.get::<ButtonInput<KeyCode>>().unwrap();
        assert!(!keys.pressed(KeyCode::KeyW) && keys.just_released(KeyCode::KeyW));
        // A tap within one frame: pressed and released, not held.
        frame(&mut resources, &[down, up]);
        let keys = resources.get::<ButtonInput<KeyCode>>().unwrap();
        assert!(keys.just_pressed(KeyCode::KeyW) && keys.just_released(KeyCode::KeyW));
        assert!(!keys.pressed(KeyCode::KeyW));
    }

    #[test]
    fn motion_and_scroll_sum_over_a_frame_and_reset_the_next() {
        let mut resources = Resources::default();
        frame(
            &mut resources,
            &[
                InputEvent::Motion(Vec2::new(1.0, 2.0)),
                InputEvent::Motion(Vec2::new(3.0, -1.0)),
                InputEvent::Scroll {
                    lines: Vec2::Y,
                    pixels: Vec2::ZERO,
                },
                InputEvent::Cursor(Some(Vec2::new(10.0, 20.0))),
                InputEvent::Resized(640, 480),
            ],
        );
        assert_eq!(
            resources.get::<MouseMotion>().unwrap().delta,
            Vec2::new(4.0, 1.0)
        );
        assert_eq!(resources.get::<MouseScroll>().unwrap().lines, Vec2::Y);
        assert_eq!(
            resources.get::<WindowEvents>().unwrap().resized,
            Some((640, 480))
        );
        frame(&mut resources, &[]);
        assert_eq!(resources.get::<MouseMotion>().unwrap().delta, Vec2::ZERO);
        assert_eq!(resources.get::<WindowEvents>().unwrap().resized, None);
        assert_eq!(
            resources.get::<CursorPosition>().unwrap().0,
            Some(Vec2::new(10.0, 20.0)),
            "the cursor stays where it was"
        );
    }

    #[test]
    fn losing_focus_releases_every_held_button() {
        let mut resources = Resources::default();
        frame(
            &mut resources,
            &[
                InputEvent::Key {
                    key: KeyCode::KeyA,
                    down: true,
                },
                InputEvent::Mouse {
                    button: MouseButton::Left,
                    down: true,
                },
            ],
        );
        frame(&mut resources, &[InputEvent::Focused(false)]);
        let keys = resources.get::<ButtonInput<KeyCode>>().unwrap();
        assert!(!keys.pressed(KeyCode::KeyA) && keys.just_released(KeyCode::KeyA));
        let buttons = resources.get::<ButtonInput<MouseButton>>().unwrap();
        assert!(!buttons.pressed(MouseButton::Left));
    }
}
