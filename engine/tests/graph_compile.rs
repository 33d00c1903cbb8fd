//! The render graph's compile step as plain data, without a GPU: culling, order, barriers,
//! aliasing, history and setup errors.

use ash::vk;
use lucid_engine::graph::{
    Access, BarrierSrc, GraphError, ImageHandle, Plan, RenderGraph, ResourceId, TemporalStore,
};
use lucid_engine::memory::ImageDesc;
use std::collections::HashMap;

fn desc() -> ImageDesc {
    ImageDesc::rgba32f(16, 16)
}

fn noop(p: lucid_engine::graph::PassBuilder<'_>) {
    p.execute(|_| Ok(()));
}

/// An independent hazard checker: replays a plan and reports every access that no barrier covers
/// (read/write after write, write after read, wrong layout).
fn hazards(plan: &Plan) -> Vec<String> {
    #[derive(Default)]
    struct State {
        layout: Option<vk::ImageLayout>,
        pending_write: Option<(vk::PipelineStageFlags2, vk::AccessFlags2)>,
        visible: Vec<(vk::PipelineStageFlags2, vk::AccessFlags2)>,
        reads: vk::PipelineStageFlags2,
        touched: bool,
    }
    let mut states: HashMap<ResourceId, State> = HashMap::new();
    let mut found = Vec::new();
    for pass in &plan.passes {
        for b in &pass.barriers {
            let s = states.entry(b.resource).or_default();
            match b.src {
                BarrierSrc::FrameStart => {
                    if s.touched {
                        found.push(format!("{}: frame-start barrier after use", pass.name));
                    }
                    s.pending_write = None;
                    s.reads = vk::PipelineStageFlags2::empty();
                }
                BarrierSrc::Earlier { stage, access } => {
                    let transition = b.old_layout.is_some_and(|old| old != b.new_layout);
                    if transition && !stage.contains(s.reads) {
                        found.push(format!(
                            "{}: layout transition races earlier reads",
                            pass.name
                        ));
                    }
                    if let Some((ws, wa)) = s.pending_write {
                        if stage.contains(ws) && access.contains(wa) {
                            s.visible.push((b.dst_stage, b.dst_access));
                        }
                    }
                    if stage.contains(s.reads) {
                        s.reads = vk::PipelineStageFlags2::empty();
                    }
                }
            }
            if b.old_layout
                .is_some_and(|old| old != vk::ImageLayout::UNDEFINED && Some(old) != s.layout)
            {
                found.push(format!("{}: barrier from the wrong layout", pass.name));
            }
            s.layout = Some(b.new_layout);
        }
        for &(id, _, access) in &pass.accesses {
            let info = access.info();
            let s = states.entry(id).or_default();
            let is_image = matches!(
                plan.resources[id.0 as usize].desc,
                lucid_engine::graph::ResourceDesc::Image(_)
            );
            if is_image && s.layout != Some(info.layout) {
                found.push(format!(
                    "{}: {:?} in layout {:?}",
                    pass.name, access, s.layout
                ));
            }
            if !s.touched && pass.barriers.iter().all(|b| b.resource != id) {
                found.push(format!("{}: first use without a barrier", pass.name));
            }
            s.touched = true;
            if s.pending_write.is_some()
                && !s
                    .visible
                    .iter()
                    .any(|(st, ac)| st.contains(info.stage) && ac.contains(info.access))
            {
                found.push(format!(
                    "{}: {:?} after an unsynchronised write",
                    pass.name, access
                ));
            }
            if info.writes && !s.reads.is_empty() {
                found.push(format!("{}: write after an unsynchronised read", pass.name));
            }
            if info.writes {
                s.pending_write = Some((info.stage, info.access));
                s.visible.clear();
                s.reads = vk::PipelineStageFlags2::empty();
            } else {
                s.reads |= info.stage;
            }
        }
    }
    found
}

/// gradient -> blur (reads twice, RAR) -> tonemap -> output (imported), plus an unused pass.
fn sample_graph() -> RenderGraph {
    let mut g = RenderGraph::new();
    let output = g.import_image_desc("output", desc());
    let mut p = g.add_pass("gradient");
    let a = p.create_image("a", desc());
    let a = p.write(a, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("unused");
    let x = p.create_image("x", desc());
    p.read(a, Access::ComputeRead);
    p.write(x, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("blur");
    p.read(a, Access::ComputeRead);
    let b = p.create_image("b", desc());
    let b = p.write(b, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("tonemap");
    p.read(a, Access::ComputeRead);
    p.read(b, Access::ComputeSampled);
    p.write(output, Access::ComputeWrite);
    noop(p);
    g
}

#[test]
fn culls_passes_whose_outputs_nobody_reads() {
    let plan = sample_graph().compile().unwrap().plan;
    assert_eq!(plan.order(), ["gradient", "blur", "tonemap"]);
    assert_eq!(plan.culled, ["unused"]);
}

#[test]
fn side_effect_passes_are_never_culled() {
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("writes_nothing_read");
    let x = p.create_image("x", desc());
    p.write(x, Access::ComputeWrite);
    p.side_effect();
    noop(p);
    let mut p = g.add_pass("really_unused");
    let y = p.create_image("y", desc());
    p.write(y, Access::ComputeWrite);
    noop(p);
    let plan = g.compile().unwrap().plan;
    assert_eq!(plan.order(), ["writes_nothing_read"]);
    assert_eq!(plan.culled, ["really_unused"]);
}

#[test]
fn read_after_write_gets_a_barrier_and_read_after_read_none() {
    let plan = sample_graph().compile().unwrap().plan;
    let a = plan.resource_id("a").unwrap();
    let blur = plan.pass("blur").unwrap();
    let raw = blur
        .barriers
        .iter()
        .find(|b| b.resource == a)
        .expect("RAW barrier on a");
    assert_eq!(
        raw.src,
        BarrierSrc::Earlier {
            stage: vk::PipelineStageFlags2::COMPUTE_SHADER,
            access: vk::AccessFlags2::SHADER_STORAGE_WRITE
        }
    );
    assert!(raw
        .dst_access
        .contains(vk::AccessFlags2::SHADER_STORAGE_READ));
    let tonemap = plan.pass("tonemap").unwrap();
    assert!(
        tonemap.barriers.iter().all(|b| b.resource != a),
        "a second read of a in the same layout needs no barrier: {:?}",
        tonemap.barriers
    );
    // b is sampled after a storage write: a barrier with a layout transition.
    let b = plan.resource_id("b").unwrap();
    let sampled = tonemap.barriers.iter().find(|x| x.resource == b).unwrap();
    assert_eq!(sampled.old_layout, Some(vk::ImageLayout::GENERAL));
    assert_eq!(
        sampled.new_layout,
        vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL
    );
    assert!(hazards(&plan).is_empty(), "{:?}", hazards(&plan));
}

#[test]
fn write_after_read_gets_an_execution_barrier() {
    let mut g = RenderGraph::new();
    let out = g.import_image_desc("out", desc());
    let mut p = g.add_pass("w1");
    let a = p.create_image("a", desc());
    let a = p.write(a, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("r");
    p.read(a, Access::ComputeRead);
    let out = p.write(out, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("w2");
    let a2 = p.write(a, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("r2");
    p.read(a2, Access::ComputeRead);
    p.write(out, Access::ComputeReadWrite);
    noop(p);
    let plan = g.compile().unwrap().plan;
    let a = plan.resource_id("a").unwrap();
    let war = plan
        .pass("w2")
        .unwrap()
        .barriers
        .iter()
        .find(|b| b.resource == a)
        .unwrap();
    assert!(
        matches!(war.src, BarrierSrc::Earlier { stage, .. } if stage.contains(vk::PipelineStageFlags2::COMPUTE_SHADER))
    );
    assert!(hazards(&plan).is_empty(), "{:?}", hazards(&plan));
}

#[test]
fn hazard_checker_catches_a_dropped_barrier() {
    let mut plan = sample_graph().compile().unwrap().plan;
    assert!(hazards(&plan).is_empty());
    let blur = plan.passes.iter_mut().find(|p| p.name == "blur").unwrap();
    let a = plan.resources.iter().position(|r| r.name == "a").unwrap();
    blur.barriers.retain(|b| b.resource.0 as usize != a);
    assert!(
        !hazards(&plan).is_empty(),
        "dropping the RAW barrier must be detected"
    );
}

#[test]
fn imported_resources_start_from_frame_state() {
    let plan = sample_graph().compile().unwrap().plan;
    let out = plan.resource_id("output").unwrap();
    let b = plan
        .pass("tonemap")
        .unwrap()
        .barriers
        .iter()
        .find(|b| b.resource == out)
        .unwrap();
    assert_eq!(b.src, BarrierSrc::FrameStart);
    assert_eq!(
        b.old_layout, None,
        "an import keeps its contents: no discard"
    );
    let (_, end) = plan.final_states.iter().find(|(id, _)| *id == out).unwrap();
    assert_eq!(end.layout, vk::ImageLayout::GENERAL);
    assert_eq!(end.access, vk::AccessFlags2::SHADER_STORAGE_WRITE);
}

/// A deterministic pseudo-random chain-and-fan graph.
fn random_graph(seed: u64, passes: usize) -> RenderGraph {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut next = move |n: usize| {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 33) as usize) % n.max(1)
    };
    let mut g = RenderGraph::new();
    let out = g.import_image_desc("out", desc());
    let mut live: Vec<ImageHandle> = Vec::new();
    for i in 0..passes {
        let mut p = g.add_pass(&format!("p{i}"));
        let reads = if live.is_empty() { 0 } else { 1 + next(2) };
        let mut read_ids = Vec::new();
        for _ in 0..reads {
            let h = live[next(live.len())];
            if !read_ids.contains(&h) {
                p.read(
                    h,
                    if next(2) == 0 {
                        Access::ComputeRead
                    } else {
                        Access::ComputeSampled
                    },
                );
                read_ids.push(h);
            }
        }
        let size = 8 << next(3);
        let created = p.create_image(&format!("t{i}"), ImageDesc::rgba32f(size, size));
        live.push(p.write(created, Access::ComputeWrite));
        noop(p);
    }
    let mut p = g.add_pass("final");
    let last = *live.last().unwrap();
    p.read(last, Access::ComputeRead);
    p.write(out, Access::ComputeWrite);
    noop(p);
    g
}

#[test]
fn aliasing_never_overlaps_live_ranges() {
    let mut aliased_somewhere = false;
    for seed in 0..40 {
        let plan = random_graph(seed, 12).compile().unwrap().plan;
        for slot in &plan.slots {
            let lives: Vec<(usize, usize)> = slot
                .members
                .iter()
                .map(|m| plan.resources[m.0 as usize].lifetime.unwrap())
                .collect();
            aliased_somewhere |= lives.len() > 1;
            for i in 0..lives.len() {
                for j in i + 1..lives.len() {
                    let (a, b) = (lives[i], lives[j]);
                    assert!(a.1 < b.0 || b.1 < a.0, "seed {seed}: {a:?} overlaps {b:?}");
                }
            }
        }
        assert!(
            hazards(&plan).is_empty(),
            "seed {seed}: {:?}",
            hazards(&plan)
        );
        let (aliased, unaliased) = plan.transient_bytes();
        assert!(aliased <= unaliased);
    }
    assert!(
        aliased_somewhere,
        "random graphs should alias some transients"
    );
}

#[test]
fn a_chain_of_transients_shares_two_slots() {
    let mut g = RenderGraph::new();
    let out = g.import_image_desc("out", desc());
    let mut p = g.add_pass("p0");
    let t = p.create_image("t0", desc());
    let mut prev = p.write(t, Access::ComputeWrite);
    noop(p);
    for i in 1..6 {
        let mut p = g.add_pass(&format!("p{i}"));
        p.read(prev, Access::ComputeRead);
        let t = p.create_image(&format!("t{i}"), desc());
        prev = p.write(t, Access::ComputeWrite);
        noop(p);
    }
    let mut p = g.add_pass("final");
    p.read(prev, Access::ComputeRead);
    p.write(out, Access::ComputeWrite);
    noop(p);
    let plan = g.compile().unwrap().plan;
    assert_eq!(plan.slots.len(), 2, "{}", plan.dump());
    // The second user of a slot waits for the first user's accesses and discards contents.
    let t2 = plan.resource_id("t2").unwrap();
    let b = plan
        .pass("p2")
        .unwrap()
        .barriers
        .iter()
        .find(|b| b.resource == t2)
        .unwrap();
    assert!(matches!(b.src, BarrierSrc::Earlier { .. }));
    assert_eq!(b.old_layout, Some(vk::ImageLayout::UNDEFINED));
    assert!(hazards(&plan).is_empty());
}

#[test]
fn usage_flags_come_from_accesses() {
    let plan = sample_graph().compile().unwrap().plan;
    let b = &plan.resources[plan.resource_id("b").unwrap().0 as usize];
    assert_eq!(
        b.image_usage,
        vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::SAMPLED
    );
}

#[test]
fn setup_errors_are_reported_by_compile() {
    let mut g = RenderGraph::new();
    let mut p = g.add_pass("reads_nothing_written");
    let x = p.create_image("x", desc());
    p.read(x, Access::ComputeRead);
    noop(p);
    assert!(matches!(g.compile(), Err(GraphError::ReadUnwritten { .. })));

    let mut g = RenderGraph::new();
    let mut p = g.add_pass("w");
    let x = p.create_image("x", desc());
    let x1 = p.write(x, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("stale");
    p.write(x, Access::ComputeWrite);
    noop(p);
    let _ = x1;
    assert!(matches!(g.compile(), Err(GraphError::StaleWrite { .. })));

    let mut g = RenderGraph::new();
    let mut p = g.add_pass("w");
    let x = p.create_image("x", desc());
    let x1 = p.write(x, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("w2");
    p.write(x1, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("late_reader");
    p.read(x1, Access::ComputeRead);
    noop(p);
    assert!(matches!(
        g.compile(),
        Err(GraphError::ReadOverwritten { .. })
    ));

    let mut g = RenderGraph::new();
    let h = g.temporal_image("history", desc());
    let mut p = g.add_pass("writes_prev");
    p.write(h.prev, Access::ComputeWrite);
    noop(p);
    assert!(matches!(
        g.compile(),
        Err(GraphError::WritePrevHistory { .. })
    ));

    let mut g = RenderGraph::new();
    g.temporal_image("history", desc());
    g.temporal_image("history", desc());
    assert!(matches!(
        g.compile(),
        Err(GraphError::DuplicateTemporalKey(_))
    ));

    let mut g = RenderGraph::new();
    let _ = g.add_pass("no_work");
    assert!(matches!(g.compile(), Err(GraphError::NoWork(_))));
}

#[test]
fn temporal_writes_are_roots_and_prev_reads_need_no_writer() {
    let mut g = RenderGraph::new();
    let h = g.temporal_image("accum", desc());
    let mut p = g.add_pass("accumulate");
    p.read(h.prev, Access::ComputeRead);
    p.write(h.cur, Access::ComputeWrite);
    noop(p);
    let plan = g.compile().unwrap().plan;
    assert_eq!(plan.order(), ["accumulate"]);
    assert!(plan.slots.is_empty(), "history never aliases");
}

#[test]
fn temporal_store_carries_history_across_frames() {
    let mut store: TemporalStore<u32, (u32, u32)> = TemporalStore::default();
    let mut created = 0;
    let mut make = |_: (u32, u32), _: usize| -> Result<u32, ()> {
        created += 1;
        Ok(created)
    };
    let f1 = store.begin("svgf.history", (64, 64), &mut make).unwrap();
    let (cur1, valid1, clear1) = (*f1.cur, f1.valid, f1.needs_clear);
    assert!(!valid1 && clear1);
    store.end_frame();
    let f2 = store.begin("svgf.history", (64, 64), &mut make).unwrap();
    assert_eq!(*f2.prev, cur1, "last frame's cur is this frame's prev");
    assert!(f2.valid && !f2.needs_clear);
    let cur2 = *f2.cur;
    store.end_frame();
    // A frame that does not use the key leaves it alone.
    store.end_frame();
    let f3 = store.begin("svgf.history", (64, 64), &mut make).unwrap();
    assert_eq!(*f3.prev, cur2);
    store.end_frame();
    store.reset("svgf.history");
    let f4 = store.begin("svgf.history", (64, 64), &mut make).unwrap();
    assert!(!f4.valid && f4.needs_clear);
    store.end_frame();
    let f5 = store.begin("svgf.history", (32, 32), &mut make).unwrap();
    assert!(!f5.valid, "a resize starts a new history");
    assert_eq!(created, 4, "two pairs: the original and the resized one");
}

#[test]
fn dumps_name_every_pass_and_resource() {
    let plan = sample_graph().compile().unwrap().plan;
    let text = plan.dump();
    for name in ["gradient", "blur", "tonemap", "culled: unused", "output"] {
        assert!(text.contains(name), "{text}");
    }
    let dot = plan.to_dot();
    assert!(
        dot.starts_with("digraph") && dot.contains("\"tonemap\""),
        "{dot}"
    );
}

#[test]
fn a_layout_transition_waits_for_reads_in_other_stages() {
    // Written by compute, copied out (transfer read), then sampled: the transition to
    // SHADER_READ_ONLY must wait for the copy too, not only for the write.
    let mut g = RenderGraph::new();
    let out = g.import_image_desc("out", desc());
    let mut p = g.add_pass("write");
    let a = p.create_image("a", desc());
    let a = p.write(a, Access::ComputeWrite);
    noop(p);
    let mut p = g.add_pass("copy_out");
    p.read(a, Access::TransferRead);
    p.side_effect();
    noop(p);
    let mut p = g.add_pass("sample");
    p.read(a, Access::ComputeSampled);
    p.write(out, Access::ComputeWrite);
    noop(p);
    let plan = g.compile().unwrap().plan;
    let id = plan.resource_id("a").unwrap();
    let b = plan
        .pass("sample")
        .unwrap()
        .barriers
        .iter()
        .find(|b| b.resource == id)
        .unwrap();
    assert!(
        matches!(b.src, BarrierSrc::Earlier { stage, .. } if stage.contains(vk::PipelineStageFlags2::COPY)),
        "{b:?}"
    );
    assert!(hazards(&plan).is_empty(), "{:?}", hazards(&plan));
}

#[test]
fn a_layout_change_after_reads_in_several_passes_waits_for_all_of_them() {
    // Cleared (transfer), sampled by a compute pass and by a fragment pass (one layout), then
    // copied out or cleared again (another layout): the transition must wait for both reads, not
    // only for the clear that last wrote the image.
    for (next, access) in [
        ("copy_out", Access::TransferRead),
        ("clear_again", Access::TransferWrite),
    ] {
        let mut g = RenderGraph::new();
        let mut p = g.add_pass("clear");
        let a = p.create_image("a", desc());
        let a = p.write(a, Access::TransferWrite);
        noop(p);
        for (name, read) in [
            ("sample_compute", Access::ComputeSampled),
            ("sample_fragment", Access::FragmentSampled),
        ] {
            let mut p = g.add_pass(name);
            p.read(a, read);
            p.side_effect();
            noop(p);
        }
        let mut p = g.add_pass(next);
        if access.info().writes {
            p.write(a, access);
        } else {
            p.read(a, access);
        }
        p.side_effect();
        noop(p);
        let plan = g.compile().unwrap().plan;
        let id = plan.resource_id("a").unwrap();
        let b = plan
            .pass(next)
            .unwrap()
            .barriers
            .iter()
            .find(|b| b.resource == id)
            .unwrap();
        assert_eq!(
            b.old_layout,
            Some(vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL),
            "{next}: {b:?}"
        );
        assert_eq!(b.new_layout, access.info().layout, "{next}: {b:?}");
        let reads =
            vk::PipelineStageFlags2::COMPUTE_SHADER | vk::PipelineStageFlags2::FRAGMENT_SHADER;
        assert!(
            matches!(b.src, BarrierSrc::Earlier { stage, .. } if stage.contains(reads)),
            "{next}: {b:?}"
        );
        assert!(hazards(&plan).is_empty(), "{next}: {:?}", hazards(&plan));
    }
}

#[test]
fn an_indirect_dispatch_waits_for_the_pass_that_wrote_its_counts() {
    // A queue kernel appends and counts workgroups (storage writes), the next kernel dispatches
    // that many (indirect-command read) and the one after overwrites the counts (a write after the
    // indirect read): RAW and WAR barriers at the indirect-command stage, derived from the access.
    static SHADER: lucid_engine::shader::ShaderSource = lucid_engine::shader::ShaderSource {
        name: "test/queue",
        path: "shaders/test/queue.comp",
        spirv: &[],
    };
    let mut g = RenderGraph::new();
    let out = g.import_image_desc("out", desc());
    let mut shade = g.compute_pass("shade", &SHADER);
    let args = shade.create_buffer("b_args", "args", 16);
    shade.dispatch([64, 1, 1]);
    let mut extend = g.compute_pass("extend", &SHADER);
    let out = extend.write("u_out", out);
    extend.dispatch_indirect(args, 0);
    let mut reset = g.compute_pass("reset", &SHADER);
    reset.read_write("b_args", args);
    reset.read_write("u_out", out);
    reset.dispatch([1, 1, 1]);
    let plan = g.compile().unwrap().plan;
    assert_eq!(plan.order(), ["shade", "extend", "reset"]);
    let id = plan.resource_id("args").unwrap();
    let barrier = |pass: &str| {
        *plan
            .pass(pass)
            .unwrap()
            .barriers
            .iter()
            .find(|b| b.resource == id)
            .unwrap_or_else(|| panic!("{pass}: no barrier on args"))
    };
    let raw = barrier("extend");
    assert_eq!(
        raw.src,
        BarrierSrc::Earlier {
            stage: vk::PipelineStageFlags2::COMPUTE_SHADER,
            access: vk::AccessFlags2::SHADER_STORAGE_WRITE
        }
    );
    assert_eq!(raw.dst_stage, vk::PipelineStageFlags2::DRAW_INDIRECT);
    assert_eq!(raw.dst_access, vk::AccessFlags2::INDIRECT_COMMAND_READ);
    let accesses = &plan.pass("extend").unwrap().accesses;
    assert!(accesses.contains(&(id, 1, Access::IndirectCommandRead)));
    let war = barrier("reset");
    assert!(
        matches!(war.src, BarrierSrc::Earlier { stage, .. } if stage.contains(vk::PipelineStageFlags2::DRAW_INDIRECT)),
        "{war:?}"
    );
    let args = &plan.resources[id.0 as usize];
    assert_eq!(
        args.buffer_usage,
        vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::INDIRECT_BUFFER
    );
    assert!(hazards(&plan).is_empty(), "{:?}", hazards(&plan));
}
