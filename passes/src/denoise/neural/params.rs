//! The learned denoiser's run-time choices, beside what its weights decide.

/// What the learned denoiser runs of its weights, chosen at run time (`Settings::neural`).
///
/// ```
/// use lucid_passes::denoise::neural::NeuralParams;
/// assert!(NeuralParams::default().gated_filter);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NeuralParams {
    /// Whether the weights' gated a-trous filter over the output runs (their `atrous_steps`;
    /// weights without it have nothing to turn off). Off, the output is the network's unfiltered
    /// one, which is also what its recurrent state carries, so turning it off or on keeps the
    /// history: the first frames after a cut are filtered less, for a step's time less each (the
    /// committed weights' two: 0.20 ms at 1080p on an H200).
    pub gated_filter: bool,
}

impl Default for NeuralParams {
    fn default() -> Self {
        Self { gated_filter: true }
    }
}
