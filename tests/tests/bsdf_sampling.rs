//! Every BSDF's sampling agrees with its evaluation (`shaders/common/bsdf.glsl`, through
//! `shaders/bsdf_sampling/bsdf_sampling.comp`): for outgoing directions on both sides and random
//! numbers, each sample's pdf, its reverse pdf (what bidirectional MIS weighs: the pdf of sampling
//! wo from wi) and its weight are what evaluating the BSDF for the sample's two directions gives.
//! Delta lobes carry no pdfs.

use ash::vk;
use lucid_engine::graph::RenderGraph;
use lucid_engine::memory::Buffer;
use lucid_passes::debug::bsdf_sampling::{self, BsdfCase, BsdfOutcome};
use lucid_tests::{assert_no_validation_messages, executor, run};
use std::sync::Arc;

const DIFFUSE: u32 = 0;
const CONDUCTOR: u32 = 1;
const DIELECTRIC: u32 = 2;
const METAL_ROUGH: u32 = 3;

/// Directions and random numbers each material is sampled with.
const SAMPLES: usize = 256;

/// A material: kind, GGX alpha, index of refraction, metallic share, delta lobe.
#[derive(Clone, Copy, Debug)]
struct Material {
    kind: u32,
    alpha: f32,
    ior: f32,
    metallic: f32,
    delta: bool,
}

fn materials() -> Vec<Material> {
    let m = |kind, alpha, ior, metallic, delta| Material {
        kind,
        alpha,
        ior,
        metallic,
        delta,
    };
    let mut all = vec![
        m(DIFFUSE, 1.0, 1.0, 0.0, false),
        m(CONDUCTOR, 0.0, 1.0, 0.0, true),
        m(DIELECTRIC, 0.0, 1.5, 0.0, true),
    ];
    for alpha in [0.05, 0.2, 0.6, 1.0] {
        all.push(m(CONDUCTOR, alpha, 1.0, 0.0, false));
        all.push(m(DIELECTRIC, alpha, 1.5, 0.0, false));
        for metallic in [0.0, 0.5, 1.0] {
            all.push(m(METAL_ROUGH, alpha, 1.5, metallic, false));
        }
    }
    all
}

/// A xorshift generator's next number in [0, 1).
fn next(state: &mut u32) -> f32 {
    *state ^= *state << 13;
    *state ^= *state >> 17;
    *state ^= *state << 5;
    (*state >> 8) as f32 / (1u32 << 24) as f32
}

fn cases(materials: &[Material]) -> Vec<BsdfCase> {
    let mut state = 0x2545_f491;
    let mut cases = Vec::new();
    for m in materials {
        for _ in 0..SAMPLES {
            // Uniform on the sphere, away from grazing.
            let z = loop {
                let z = 2.0 * next(&mut state) - 1.0;
                if z.abs() > 0.1 {
                    break z;
                }
            };
            let phi = std::f32::consts::TAU * next(&mut state);
            let r = (1.0 - z * z).sqrt();
            let u = [next(&mut state), next(&mut state), next(&mut state)];
            cases.push(BsdfCase {
                color_alpha: [0.8, 0.6, 0.3, m.alpha],
                wo_ior: [r * phi.cos(), r * phi.sin(), z, m.ior],
                u_metallic: [u[0], u[1], u[2], m.metallic],
                kind_smooth: [m.kind, u32::from(m.delta), 0, 0],
            });
        }
    }
    cases
}

/// Whether `a` is `b` to a relative `tolerance` (of the larger).
fn close(a: f32, b: f32, tolerance: f32) -> bool {
    (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(1e-6)
}

#[test]
fn samples_carry_the_pdfs_and_weights_their_evaluation_gives() {
    let (ctx, mut executor) = executor(false);
    let materials = materials();
    let cases = cases(&materials);
    let buffer = Buffer::with_data(
        &ctx,
        "bsdf cases",
        "test",
        vk::BufferUsageFlags::STORAGE_BUFFER,
        bytemuck::cast_slice(&cases),
    )
    .expect("upload the cases");
    let mut g = RenderGraph::new();
    let input = g.import_buffer("bsdf cases", Arc::new(buffer));
    let outcomes = bsdf_sampling::add_bsdf_sampling(&mut g, input, cases.len() as u32);
    let readback = g.readback(outcomes);
    let outputs = run(&mut executor, g);
    let outcomes: Vec<BsdfOutcome> =
        bytemuck::pod_collect_to_vec(outputs.bytes(readback).expect("read back"));
    drop(executor);
    assert_no_validation_messages(&ctx);

    for (m, outcomes) in materials.iter().zip(outcomes.chunks(SAMPLES)) {
        let sampled: Vec<&BsdfOutcome> =
            outcomes.iter().filter(|o| o.wi_sampled[3] == 1.0).collect();
        assert!(
            sampled.len() > SAMPLES / 2,
            "{m:?}: {} of {SAMPLES} samples succeeded",
            sampled.len()
        );
        for o in sampled {
            let [rev_pdf, delta, pdf, eval_rev_pdf] = o.rev_delta;
            assert_eq!(delta == 1.0, m.delta, "{m:?}: {o:?}");
            if m.delta {
                assert_eq!((o.weight_pdf[3], rev_pdf), (0.0, 0.0), "{m:?}: {o:?}");
                continue;
            }
            let sample_pdf = o.weight_pdf[3];
            assert!(
                close(sample_pdf, pdf, 2e-3),
                "{m:?}: pdf {sample_pdf} sampled, {pdf} evaluated ({o:?})"
            );
            assert!(
                close(rev_pdf, eval_rev_pdf, 2e-3),
                "{m:?}: reverse pdf {rev_pdf} sampled, {eval_rev_pdf} evaluated ({o:?})"
            );
            for channel in 0..3 {
                let weight = o.weight_pdf[channel];
                let expected = o.value[channel] / pdf;
                assert!(
                    close(weight, expected, 2e-3),
                    "{m:?}: weight {weight} sampled, value / pdf {expected} ({o:?})"
                );
            }
        }
    }
}
