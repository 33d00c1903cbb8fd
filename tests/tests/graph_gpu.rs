//! Render graphs executed on the device (lavapipe in CI) with validation on: exact outputs,
//! aliasing, history across frames, specialization, reflection and binding errors, indirect
//! dispatch.

use lucid_engine::graph::{Access, Executor, ImageHandle, RenderGraph};
use lucid_engine::memory::ImageDesc;
use lucid_engine::shader::DescriptorKind;
use lucid_passes::debug::test_pattern::{self, Params};
use lucid_passes::shaders::test_pattern::{
    ACCUMULATE, COMBINE, COUNT_INVOCATIONS, GRADIENT, INDIRECT_ARGS, SCALE,
};
use lucid_tests::{assert_no_validation_messages, executor, run};

fn assert_close(got: &[[f32; 4]], want: &[[f32; 4]], tolerance: f32) {
    assert_eq!(got.len(), want.len());
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        for c in 0..4 {
            let scale = w[c].abs().max(1.0);
            assert!(
                (g[c] - w[c]).abs() <= tolerance * scale,
                "pixel {i} channel {c}: got {} want {}",
                g[c],
                w[c]
            );
        }
    }
}

fn run_pattern(executor: &mut Executor, w: u32, h: u32, params: &Params) -> Vec<[f32; 4]> {
    let mut g = RenderGraph::new();
    let out = test_pattern::add_test_pattern(&mut g, w, h, params);
    let readback = g.readback(out.combined);
    run(executor, g).image(readback).unwrap().pixels
}

#[test]
fn three_pass_graph_output_equals_expected_values() {
    // Synchronization validation catches any missing or wrong barrier between the passes.
    let (ctx, mut executor) = executor(true);
    let (w, h) = (61, 37); // not multiples of the workgroup size
    let params = Params::default();
    let got = run_pattern(&mut executor, w, h, &params);
    assert_close(&got, &test_pattern::expected(w, h, &params), 1e-5);
    let timings = executor.pass_timings();
    let names: Vec<&str> = timings.iter().map(|t| t.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "test_pattern.gradient",
            "test_pattern.row_sum",
            "test_pattern.combine",
            "readback test_pattern.combined"
        ]
    );
    assert!(timings.iter().all(|t| t.ms >= 0.0 && t.ms.is_finite()));
    // A second frame reuses the transients and barriers from the tracked state.
    let again = run_pattern(&mut executor, w, h, &params);
    assert_eq!(got, again, "frames are reproducible");
    assert_no_validation_messages(&ctx);
}

#[test]
fn specialization_constants_change_the_pipeline() {
    let (ctx, mut executor) = executor(false);
    let params = Params {
        add_offset: false,
        combine_group_width: 16,
        gain: 2.0,
        checker: 3,
        ..Params::default()
    };
    let got = run_pattern(&mut executor, 40, 24, &params);
    assert_close(&got, &test_pattern::expected(40, 24, &params), 1e-5);
    let with_offset = Params {
        add_offset: true,
        ..params
    };
    let got = run_pattern(&mut executor, 40, 24, &with_offset);
    assert_close(&got, &test_pattern::expected(40, 24, &with_offset), 1e-5);
    assert_eq!(
        executor.library().pipeline_count(),
        4,
        "gradient, row_sum and two combines"
    );
    assert_no_validation_messages(&ctx);
}

#[test]
fn aliased_transients_keep_correct_contents() {
    let (ctx, mut executor) = executor(true);
    let (w, h) = (32, 16);
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("gradient");
    let t = p.create_image("t0", ImageDesc::rgba32f(w, h));
    let mut prev = p.write(t, Access::ComputeWrite);
    let first = prev;
    p.execute(move |ctx| {
        ctx.compute(&GRADIENT)
            .image("u_out", first)
            .push(&[1.0f32.to_bits(), 4u32])
            .dispatch_threads([w, h, 1])
    });
    for i in 1..5 {
        let mut p = g.add_pass(&format!("scale{i}"));
        let input = p.read(prev, Access::ComputeRead);
        let t = p.create_image(&format!("t{i}"), ImageDesc::rgba32f(w, h));
        let out = p.write(t, Access::ComputeWrite);
        p.execute(move |ctx| {
            ctx.compute(&SCALE)
                .image("u_in", input)
                .image("u_out", out)
                .push(&2.0f32)
                .dispatch_threads([w, h, 1])
        });
        prev = out;
    }
    let readback = g.readback(prev);
    let compiled = g.compile().unwrap();
    assert_eq!(compiled.plan.slots.len(), 2, "{}", compiled.plan.dump());
    let frame = executor.execute(compiled).unwrap();
    let got = executor
        .wait(frame)
        .unwrap()
        .image(readback)
        .unwrap()
        .pixels;
    let params = Params {
        gain: 1.0,
        checker: 4,
        ..Params::default()
    };
    let want: Vec<[f32; 4]> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| test_pattern::expected_pattern(w, h, x, y, &params).map(|v| v * 16.0))
        .collect();
    assert_close(&got, &want, 1e-6);
    assert_no_validation_messages(&ctx);
}

fn accumulate_frame(executor: &mut Executor, w: u32, h: u32) -> f32 {
    let mut g = RenderGraph::new();
    let history = g.temporal_image("test.accumulate", ImageDesc::rgba32f(w, h));
    let mut p = g.add_pass("accumulate");
    let prev = p.read(history.prev, Access::ComputeRead);
    let cur = p.write(history.cur, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&ACCUMULATE)
            .image("u_prev", prev)
            .image("u_cur", cur)
            .push(&1.0f32)
            .dispatch_threads([w, h, 1])
    });
    let readback = g.readback(cur);
    let image = run(executor, g).image(readback).unwrap();
    let first = image.pixels[0][0];
    assert!(
        image.pixels.iter().all(|p| p[0] == first),
        "uniform history"
    );
    first
}

#[test]
fn history_survives_frames_and_resets() {
    let (ctx, mut executor) = executor(true);
    let counts: Vec<f32> = (0..4)
        .map(|_| accumulate_frame(&mut executor, 16, 8))
        .collect();
    assert_eq!(counts, [1.0, 2.0, 3.0, 4.0]);
    executor.reset_history();
    assert_eq!(
        accumulate_frame(&mut executor, 16, 8),
        1.0,
        "reset clears history"
    );
    assert_eq!(accumulate_frame(&mut executor, 16, 8), 2.0);
    assert_eq!(
        accumulate_frame(&mut executor, 24, 8),
        1.0,
        "resize starts a new history"
    );
    assert_no_validation_messages(&ctx);
}

#[test]
fn frames_in_flight_overlap_and_each_returns_its_outputs() {
    let (ctx, mut executor) = executor(true);
    let params = Params::default();
    let mut frames = Vec::new();
    for gain in [1.0f32, 2.0] {
        let mut g = RenderGraph::new();
        let out = test_pattern::add_test_pattern(&mut g, 16, 16, &Params { gain, ..params });
        let readback = g.readback(out.pattern);
        frames.push((
            executor.execute(g.compile().unwrap()).unwrap(),
            readback,
            gain,
        ));
    }
    for (frame, readback, gain) in frames {
        let image = executor.wait(frame).unwrap().image(readback).unwrap();
        assert_eq!(image.pixels[16 + 8][0], 8.0 / 16.0 * gain);
    }
    assert_no_validation_messages(&ctx);
}

#[test]
fn reflection_finds_bindings_by_name() {
    let (ctx, executor) = executor(false);
    let r = executor.library().reflection(&COMBINE).unwrap();
    let u_in = r.binding("u_in").unwrap();
    assert_eq!(
        (u_in.binding, u_in.kind, u_in.read_only),
        (0, DescriptorKind::StorageImage, true)
    );
    let sums = r.binding("b_sums").unwrap();
    assert_eq!(
        (sums.binding, sums.kind),
        (1, DescriptorKind::StorageBuffer)
    );
    assert_eq!(
        r.binding("RowSums").unwrap().binding,
        1,
        "blocks are found by type name too"
    );
    let u_out = r.binding("u_out").unwrap();
    assert_eq!((u_out.binding, u_out.read_only), (2, false));
    assert_eq!(r.push_constant_size, 4);
    assert_eq!(r.workgroup_size, [1, 8, 1], "local_size_x_id default is 1");
    assert!(r.spec_constant("ADD_OFFSET").is_some());
    assert_eq!(r.spec_constant("local_size_x").unwrap().id, 0);
    assert!(r.binding("u_missing").is_none());
    let g = executor.library().reflection(&GRADIENT).unwrap();
    assert_eq!(g.workgroup_size, [8, 8, 1]);
    assert_eq!(g.push_constant_size, 8);
    assert_no_validation_messages(&ctx);
}

/// Compiles and executes `g`, which must fail; returns the error's message.
fn execution_error(executor: &mut Executor, g: RenderGraph) -> String {
    executor
        .execute(g.compile().unwrap())
        .expect_err("must fail")
        .to_string()
}

fn run_with_binding(executor: &mut Executor, name: &'static str) -> String {
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("bad_binding");
    let t = p.create_image("t", ImageDesc::rgba32f(8, 8));
    let t = p.write(t, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&GRADIENT)
            .image(name, t)
            .push(&[1.0f32.to_bits(), 2u32])
            .dispatch_threads([8, 8, 1])
    });
    g.readback(t);
    execution_error(executor, g)
}

#[test]
fn binding_an_unknown_name_is_a_clear_error() {
    let (ctx, mut executor) = executor(false);
    let message = run_with_binding(&mut executor, "u_typo");
    assert!(
        message.contains("u_typo") && message.contains("u_out"),
        "{message}"
    );
    assert!(
        message.contains("test_pattern/gradient") && message.contains("bad_binding"),
        "{message}"
    );
    // The executor stays usable after a failed frame.
    let ok = run_pattern(&mut executor, 8, 8, &Params::default());
    assert_eq!(ok.len(), 64);
    assert_no_validation_messages(&ctx);
}

#[test]
fn binding_undeclared_or_missing_resources_are_errors() {
    let (ctx, mut executor) = executor(false);
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("w");
    let a = p.create_image("a", ImageDesc::rgba32f(8, 8));
    let a = p.write(a, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&GRADIENT)
            .image("u_out", a)
            .push(&[0u32, 1])
            .dispatch_threads([8, 8, 1])
    });
    let mut p = g.add_pass("scale_without_declaring_input");
    let b = p.create_image("b", ImageDesc::rgba32f(8, 8));
    let b = p.write(b, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&SCALE)
            .image("u_in", a)
            .image("u_out", b)
            .push(&1.0f32)
            .dispatch_threads([8, 8, 1])
    });
    g.readback(b);
    let message = execution_error(&mut executor, g);
    assert!(message.contains("without declaring"), "{message}");

    let mut g = RenderGraph::new();
    let mut p = g.add_pass("forgets_a_binding");
    let a = p.create_image("a", ImageDesc::rgba32f(8, 8));
    let a = p.write(a, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&SCALE)
            .image("u_out", a)
            .push(&1.0f32)
            .dispatch_threads([8, 8, 1])
    });
    g.readback(a);
    let message = execution_error(&mut executor, g);
    assert!(message.contains("\"u_in\" was not bound"), "{message}");
    assert_no_validation_messages(&ctx);
}

/// Executes a gradient and a `ComputePass` of SCALE that `declare` sets up besides its output;
/// returns the frame's error.
fn scale_pass_error(
    executor: &mut Executor,
    declare: impl FnOnce(&mut lucid_engine::graph::ComputePass<'_>, ImageHandle),
) -> String {
    let mut g = RenderGraph::new();
    let mut gradient = g.compute_pass("gradient", &GRADIENT);
    let a = gradient.create_image("u_out", "a", ImageDesc::rgba32f(8, 8));
    gradient.push(&[1.0f32.to_bits(), 4u32]);
    gradient.dispatch([8, 8, 1]);
    let mut scale = g.compute_pass("scale", &SCALE);
    declare(&mut scale, a);
    let out = scale.create_image("u_out", "b", ImageDesc::rgba32f(8, 8));
    scale.dispatch([8, 8, 1]);
    g.readback(out);
    execution_error(executor, g)
}

#[test]
fn a_compute_pass_is_checked_against_the_shader_reflection() {
    let (ctx, mut executor) = executor(false);
    let message = scale_pass_error(&mut executor, |p, a| {
        p.read("u_typo", a).push(&2.0f32);
    });
    assert!(
        message.contains("u_typo") && message.contains("u_in") && message.contains("scale"),
        "{message}"
    );
    let message = scale_pass_error(&mut executor, |p, _| {
        p.push(&2.0f32);
    });
    assert!(message.contains("\"u_in\" was not bound"), "{message}");
    let message = scale_pass_error(&mut executor, |p, a| {
        p.read("u_in", a).push(&[2.0f32, 3.0]);
    });
    assert!(
        message.contains("push constants are 8 bytes but the shader expects 4"),
        "{message}"
    );
    assert_no_validation_messages(&ctx);
}

#[test]
fn synchronization_validation_reports_a_hazard_the_graph_did_not_declare() {
    // Two dispatches inside one pass: the second reads what the first wrote, with no barrier
    // between them (the graph only places barriers between passes). The layer must flag it, which
    // proves the validation net the other tests rely on is live.
    let (ctx, mut executor) = executor(true);
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("read_after_write_inside_one_pass");
    let a = p.create_image("a", ImageDesc::rgba32f(8, 8));
    let a = p.write(a, Access::ComputeWrite);
    let b = p.create_image("b", ImageDesc::rgba32f(8, 8));
    let b = p.write(b, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&GRADIENT)
            .image("u_out", a)
            .push(&[1.0f32.to_bits(), 2u32])
            .dispatch_threads([8, 8, 1])?;
        ctx.compute(&SCALE)
            .image("u_in", a)
            .image("u_out", b)
            .push(&2.0f32)
            .dispatch_threads([8, 8, 1])
    });
    let readback = g.readback(b);
    run(&mut executor, g).image(readback).unwrap();
    let messages = ctx.validation_log().take();
    assert!(
        messages.iter().any(|m| m.id.contains("SYNC-HAZARD-READ")),
        "synchronization validation must flag the unsynchronised read: {messages:?}"
    );
}

#[test]
fn a_cleared_image_reads_back_its_colour_through_a_compute_pass() {
    let (ctx, mut executor) = executor(true);
    let (w, h) = (4, 3);
    let colour = [0.25f32, 0.5, 0.75, 1.0];
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("clear");
    let t = p.create_image("cleared", ImageDesc::rgba32f(w, h));
    let cleared = p.write(t, Access::TransferWrite);
    p.execute(move |ctx| ctx.clear_image(cleared, colour));
    let mut p = g.add_pass("scale");
    let input = p.read(cleared, Access::ComputeRead);
    let t = p.create_image("scaled", ImageDesc::rgba32f(w, h));
    let out = p.write(t, Access::ComputeWrite);
    p.execute(move |ctx| {
        ctx.compute(&SCALE)
            .image("u_in", input)
            .image("u_out", out)
            .push(&2.0f32)
            .dispatch_threads([w, h, 1])
    });
    let readback = g.readback(out);
    let got = run(&mut executor, g).image(readback).unwrap().pixels;
    assert_close(&got, &vec![colour.map(|c| 2.0 * c); (w * h) as usize], 0.0);
    assert_no_validation_messages(&ctx);
}

#[test]
fn layout_changes_after_reads_wait_for_them() {
    // Cleared (transfer), read by two compute passes, then read back (a new layout), or first
    // cleared again: each layout change must wait for the compute reads, not only for the clear
    // that last wrote the image, or synchronization validation reports the hazard.
    let (ctx, mut executor) = executor(true);
    let (w, h) = (4, 3);
    let colour = [0.25f32, 0.5, 0.75, 1.0];
    let second = [1.0f32, 0.0, 0.5, 1.0];
    for clear_again in [false, true] {
        let mut g = RenderGraph::new();
        let mut p = g.add_pass("clear");
        let t = p.create_image("cleared", ImageDesc::rgba32f(w, h));
        let cleared = p.write(t, Access::TransferWrite);
        p.execute(move |ctx| ctx.clear_image(cleared, colour));
        let mut scaled = Vec::new();
        for factor in [2.0f32, 3.0] {
            let mut p = g.add_pass(&format!("scale by {factor}"));
            let input = p.read(cleared, Access::ComputeRead);
            let t = p.create_image(&format!("scaled by {factor}"), ImageDesc::rgba32f(w, h));
            let out = p.write(t, Access::ComputeWrite);
            p.execute(move |ctx| {
                ctx.compute(&SCALE)
                    .image("u_in", input)
                    .image("u_out", out)
                    .push(&factor)
                    .dispatch_threads([w, h, 1])
            });
            scaled.push((factor, g.readback(out)));
        }
        let (last, want) = if clear_again {
            let mut p = g.add_pass("clear again");
            let again = p.write(cleared, Access::TransferWrite);
            p.execute(move |ctx| ctx.clear_image(again, second));
            (again, second)
        } else {
            (cleared, colour)
        };
        let readback = g.readback(last);
        let outputs = run(&mut executor, g);
        let pixels = (w * h) as usize;
        for (factor, id) in scaled {
            let got = outputs.image(id).unwrap().pixels;
            assert_close(&got, &vec![colour.map(|c| factor * c); pixels], 0.0);
        }
        assert_close(
            &outputs.image(readback).unwrap().pixels,
            &vec![want; pixels],
            0.0,
        );
        assert_no_validation_messages(&ctx);
    }
}

/// Adds a pass that writes `groups` x 1 x 1 indirect arguments at word `at` of a new 32-byte
/// buffer, and a pass creating a zeroed counter.
fn indirect_args_and_counter(
    g: &mut RenderGraph,
    groups: u32,
    at: u32,
) -> (
    lucid_engine::graph::BufferHandle,
    lucid_engine::graph::BufferHandle,
) {
    let mut p = g.compute_pass("write_args", &INDIRECT_ARGS);
    let args = p.create_buffer("b_args", "args", 32);
    p.push(&[groups, at]);
    p.dispatch([1, 1, 1]);
    let mut p = g.add_pass("clear_counter");
    let counter = p.create_buffer("counter", 8);
    let counter = p.write(counter, Access::TransferWrite);
    p.execute(move |ctx| ctx.fill_buffer(counter, 0));
    (args, counter)
}

#[test]
fn an_indirect_dispatch_runs_the_workgroups_an_earlier_pass_wrote() {
    // Synchronization validation checks the barrier from the storage write of the arguments to
    // their indirect-command read.
    let (ctx, mut executor) = executor(true);
    for (groups, at) in [(5, 0), (3, 4), (0, 0)] {
        let mut g = RenderGraph::new();
        let (args, counter) = indirect_args_and_counter(&mut g, groups, at);
        let mut p = g.compute_pass("count", &COUNT_INVOCATIONS);
        let counter = p.read_write("b_counter", counter);
        p.dispatch_indirect(args, u64::from(at) * 4);
        let readback = g.readback(counter);
        let outputs = run(&mut executor, g);
        let counts: &[u32] = bytemuck::cast_slice(outputs.bytes(readback).unwrap());
        assert_eq!(
            counts,
            [32 * groups, groups],
            "{groups} groups at word {at}"
        );
    }
    assert_no_validation_messages(&ctx);
}

#[test]
fn indirect_arguments_must_be_declared_as_such_and_fit() {
    let (ctx, mut executor) = executor(false);
    for (access, offset, expect) in [
        (Access::ComputeRead, 0, "need Access::IndirectCommandRead"),
        (Access::IndirectCommandRead, 24, "do not fit"),
        (Access::IndirectCommandRead, 2, "4-byte aligned"),
    ] {
        let mut g = RenderGraph::new();
        let (args, counter) = indirect_args_and_counter(&mut g, 1, 0);
        let mut p = g.add_pass("count");
        p.read(args, access);
        let counter = p.write(counter, Access::ComputeReadWrite);
        p.execute(move |ctx| {
            ctx.compute(&COUNT_INVOCATIONS)
                .buffer("b_counter", counter)
                .dispatch_indirect(args, offset)
        });
        g.readback(counter);
        let message = executor
            .execute(g.compile().unwrap())
            .expect_err("the frame fails")
            .to_string();
        assert!(
            message.contains(expect) && message.contains("count"),
            "{access:?} at {offset}: {message}"
        );
    }
    assert_no_validation_messages(&ctx);
}
