//! Keyboard and mouse state for the camera and the app's keys: held WASD/QE, right-button mouse
//! look, wheel steps, digits for bookmarks, F to frame the scene and F12 for captures.

use super::camera::FlyInput;
use glam::{Vec2, Vec3};
use std::collections::HashSet;
use winit::event::MouseButton;
use winit::keyboard::KeyCode;

/// A key that does something once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Action {
    /// Recall bookmark 1-9.
    Recall(u8),
    /// Store the camera in bookmark 1-9 (Shift+digit).
    Store(u8),
    /// Capture the HDR output (F12).
    Capture,
    /// Frame the whole scene from a three-quarter view (F).
    FrameScene,
}

/// Input gathered between frames.
#[derive(Debug, Default)]
pub struct Input {
    held: HashSet<KeyCode>,
    shift: bool,
    looking: bool,
    cursor: Option<Vec2>,
    look: Vec2,
    wheel: f32,
}

impl Input {
    /// A key went down or up; returns the action of a fresh press, if it has one.
    pub fn key(&mut self, code: KeyCode, pressed: bool, repeat: bool) -> Option<Action> {
        if !pressed {
            self.held.remove(&code);
            return None;
        }
        self.held.insert(code);
        if repeat {
            return None;
        }
        match code {
            KeyCode::F12 => return Some(Action::Capture),
            KeyCode::KeyF => return Some(Action::FrameScene),
            _ => {}
        }
        digit(code).map(|d| {
            if self.shift {
                Action::Store(d)
            } else {
                Action::Recall(d)
            }
        })
    }

    /// The Shift modifier changed.
    pub fn set_shift(&mut self, shift: bool) {
        self.shift = shift;
    }

    /// A mouse button went down or up (the right one looks around while held).
    pub fn mouse_button(&mut self, button: MouseButton, pressed: bool) {
        if button == MouseButton::Right {
            self.looking = pressed;
        }
    }

    /// The cursor moved to `position` (pixels).
    pub fn cursor(&mut self, position: Vec2) {
        if let (true, Some(previous)) = (self.looking, self.cursor) {
            self.look += position - previous;
        }
        self.cursor = Some(position);
    }

    /// The wheel turned by `steps` (positive: away from the user).
    pub fn wheel(&mut self, steps: f32) {
        self.wheel += steps;
    }

    /// Forgets held keys and buttons (the window lost focus).
    pub fn release_all(&mut self) {
        self.held.clear();
        self.looking = false;
        self.shift = false;
    }

    /// The camera input since the last call.
    pub fn take(&mut self) -> FlyInput {
        let axis = |plus: KeyCode, minus: KeyCode| {
            f32::from(u8::from(self.held.contains(&plus)))
                - f32::from(u8::from(self.held.contains(&minus)))
        };
        let movement = Vec3::new(
            axis(KeyCode::KeyD, KeyCode::KeyA),
            axis(KeyCode::KeyE, KeyCode::KeyQ),
            axis(KeyCode::KeyW, KeyCode::KeyS),
        );
        FlyInput {
            movement,
            look: std::mem::take(&mut self.look),
            wheel: std::mem::take(&mut self.wheel),
        }
    }
}

fn digit(code: KeyCode) -> Option<u8> {
    const DIGITS: [KeyCode; 9] = [
        KeyCode::Digit1,
        KeyCode::Digit2,
        KeyCode::Digit3,
        KeyCode::Digit4,
        KeyCode::Digit5,
        KeyCode::Digit6,
        KeyCode::Digit7,
        KeyCode::Digit8,
        KeyCode::Digit9,
    ];
    DIGITS.iter().position(|&d| d == code).map(|i| i as u8 + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_keys_move_and_digits_act() {
        let mut input = Input::default();
        assert_eq!(input.key(KeyCode::KeyW, true, false), None);
        input.key(KeyCode::KeyA, true, false);
        input.key(KeyCode::KeyE, true, false);
        assert_eq!(input.take().movement, Vec3::new(-1.0, 1.0, 1.0));
        input.key(KeyCode::KeyW, false, false);
        assert_eq!(input.take().movement, Vec3::new(-1.0, 1.0, 0.0));
        assert_eq!(
            input.key(KeyCode::Digit3, true, false),
            Some(Action::Recall(3))
        );
        input.set_shift(true);
        assert_eq!(
            input.key(KeyCode::Digit9, true, false),
            Some(Action::Store(9))
        );
        assert_eq!(input.key(KeyCode::Digit9, true, true), None);
        assert_eq!(input.key(KeyCode::F12, true, false), Some(Action::Capture));
        assert_eq!(
            input.key(KeyCode::KeyF, true, false),
            Some(Action::FrameScene)
        );
        input.release_all();
        assert_eq!(input.take().movement, Vec3::ZERO);
    }

    #[test]
    fn mouse_looks_only_with_the_right_button() {
        let mut input = Input::default();
        input.cursor(Vec2::new(10.0, 10.0));
        input.cursor(Vec2::new(20.0, 10.0));
        assert_eq!(input.take().look, Vec2::ZERO);
        input.mouse_button(MouseButton::Right, true);
        input.cursor(Vec2::new(25.0, 7.0));
        input.wheel(2.0);
        let taken = input.take();
        assert_eq!(taken.look, Vec2::new(5.0, -3.0));
        assert_eq!(taken.wheel, 2.0);
        assert_eq!(input.take().look, Vec2::ZERO);
    }
}
