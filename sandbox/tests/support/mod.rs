//! Helpers shared by the sandbox's tests.

pub mod xvfb;
