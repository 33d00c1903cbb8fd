//! Why a measurement or calibration failed.

use lucid_engine::metrics::MetricsError;
use lucid_engine::EngineError;

/// Why measuring configurations failed.
#[derive(Debug, thiserror::Error)]
pub enum TradeoffError {
    /// Rendering failed.
    #[error(transparent)]
    Engine(#[from] EngineError),
    /// An image could not be compared with the reference.
    #[error("measuring {config}: {source}")]
    Metrics {
        /// The configuration (`pt/svgf/1`) or `reference`.
        config: String,
        /// What the metrics said.
        #[source]
        source: MetricsError,
    },
    /// The reference has NaN or infinite pixels: no error against it means anything.
    #[error("the reference has non-finite pixels")]
    NonFiniteReference,
    /// Nothing is left to measure (e.g. only bidirectional path tracing on a device without
    /// 64-bit integer atomics).
    #[error("no configuration to measure: {0}")]
    NoCandidates(String),
}
