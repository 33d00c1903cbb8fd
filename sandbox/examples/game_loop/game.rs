//! The game's simulation, independent of rendering: a fixed time step and what the world looks
//! like at each tick (the tall box of the Cornell box slides, the camera sways and dollies).

use glam::{Affine3A, Vec3};
use lucid_engine::scene::Camera;
use lucid_passes::renderer::Renderer;

/// Simulation steps per second (fixed, independent of how fast frames render).
pub const TICKS_PER_SECOND: f64 = 60.0;
/// The most steps one frame catches up on; a longer stall is dropped rather than replayed.
pub const MAX_STEPS_PER_FRAME: u32 = 30;

/// Turns elapsed wall-clock time into whole simulation steps of `1 / TICKS_PER_SECOND` seconds.
#[derive(Clone, Debug, Default)]
pub struct FixedStep {
    accumulator: f64,
}

impl FixedStep {
    /// Adds `elapsed` seconds; returns the steps to simulate now (at most
    /// [`MAX_STEPS_PER_FRAME`]). The remainder waits for the next frame.
    pub fn advance(&mut self, elapsed: f64) -> u32 {
        let dt = 1.0 / TICKS_PER_SECOND;
        self.accumulator += elapsed.max(0.0);
        let steps = (self.accumulator / dt).floor();
        if steps > f64::from(MAX_STEPS_PER_FRAME) {
            self.accumulator %= dt;
            return MAX_STEPS_PER_FRAME;
        }
        self.accumulator -= steps * dt;
        steps as u32
    }
}

/// The world: which instance moves, and where things start.
pub struct Game {
    moving: usize,
    home: Affine3A,
    start_camera: Camera,
    camera_moves: bool,
}

impl Game {
    /// A game on the Cornell box `renderer` draws; the camera stays put unless `camera_moves`.
    pub fn new(renderer: &Renderer, camera_moves: bool) -> Self {
        // The box the game moves: the scene's last instance (the tall box).
        let moving = renderer.scene().instances.len() - 1;
        Self {
            moving,
            home: renderer.scene().instances[moving].transform,
            start_camera: renderer.camera(),
            camera_moves,
        }
    }

    /// The box's offset from home at `tick`: it slides left and right.
    pub fn box_offset(tick: u64) -> Vec3 {
        let t = tick as f32 / TICKS_PER_SECOND as f32;
        Vec3::new(0.25 * (t * 3.0).sin(), 0.0, 0.0)
    }

    /// The camera at `tick`: it sways sideways and dollies in and out along its path.
    pub fn camera(&self, tick: u64) -> Camera {
        let mut camera = self.start_camera;
        if self.camera_moves {
            let t = tick as f32 / TICKS_PER_SECOND as f32;
            camera.position +=
                Vec3::new(0.1 * (t * 0.7).sin(), 0.0, -0.3 * (1.0 - (t * 0.4).cos()));
        }
        camera
    }

    /// Puts the box and the camera where they are at `tick`.
    pub fn apply(&self, renderer: &mut Renderer, tick: u64) -> anyhow::Result<()> {
        let transform = Affine3A::from_translation(Self::box_offset(tick)) * self.home;
        renderer.set_instance_transform(self.moving, transform)?;
        renderer.set_camera(self.camera(tick));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_steps_follow_elapsed_time_and_carry_the_remainder() {
        let mut step = FixedStep::default();
        assert_eq!(step.advance(0.010), 0, "less than a step");
        assert_eq!(step.advance(0.010), 1, "the remainder carries over");
        assert_eq!(step.advance(0.050), 3);
        let mut total = 0;
        for _ in 0..600 {
            total += step.advance(1.0 / 144.0);
        }
        assert!(
            (249..=250).contains(&total),
            "{total} steps in 600 frames at 144 Hz"
        );
        assert_eq!(step.advance(-1.0), 0, "time does not run backwards");
    }

    #[test]
    fn a_long_stall_is_capped_not_replayed() {
        let mut step = FixedStep::default();
        assert_eq!(step.advance(10.0), MAX_STEPS_PER_FRAME);
        assert_eq!(step.advance(0.0), 0, "the rest of the stall was dropped");
    }

    #[test]
    fn the_box_slides_and_returns() {
        assert_eq!(Game::box_offset(0), Vec3::ZERO);
        let quarter = (TICKS_PER_SECOND * std::f64::consts::FRAC_PI_2 / 3.0).round() as u64;
        assert!((Game::box_offset(quarter).x - 0.25).abs() < 1e-3);
        assert!(Game::box_offset(2 * quarter).x.abs() < 2e-2);
    }
}
