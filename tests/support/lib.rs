//! Shared helpers for Lucid's GPU tests (the tests are `tests/tests/*.rs`): a validated context,
//! checks on validation messages, rendering ([`render`]), the SVGF tests' methods and statistics
//! ([`svgf`]) and the statistics comparing Monte Carlo estimates ([`bdpt_stats`]).

use lucid_engine::graph::{Executor, FrameOutputs, RenderGraph};
use lucid_engine::shader::ShaderLibrary;
use lucid_engine::{Context, ContextDesc, Validation};

/// A context with the validation layer required (plus synchronization validation when `sync`).
pub fn context(sync: bool) -> Context {
    let ctx = Context::new(&ContextDesc::for_tests(sync)).expect("create a Vulkan context");
    let expected = if sync {
        Validation::Sync
    } else {
        Validation::On
    };
    assert_eq!(
        ctx.validation(),
        expected,
        "validation must be active in tests"
    );
    ctx
}

/// A validated context and an executor on it.
pub fn executor(sync: bool) -> (Context, Executor) {
    let ctx = context(sync);
    let library = ShaderLibrary::new(&ctx, None).expect("shader library");
    let executor = Executor::new(&ctx, library).expect("executor");
    (ctx, executor)
}

/// Compiles `g`, runs it on `executor` and waits for its outputs.
pub fn run(executor: &mut Executor, g: RenderGraph) -> FrameOutputs {
    let frame = executor
        .execute(g.compile().expect("the graph compiles"))
        .expect("the frame runs");
    executor.wait(frame).expect("the frame finishes")
}

/// Panics with every collected validation message, if any.
pub fn assert_no_validation_messages(ctx: &Context) {
    if let Some(report) = ctx.validation_log().take_report() {
        panic!("{report}");
    }
}

pub mod bdpt_stats;
pub mod gltf;
pub mod render;
pub mod same_paths;
pub mod svgf;
