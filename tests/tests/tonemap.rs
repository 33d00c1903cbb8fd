//! The GPU tone mapping equals the engine's CPU display encoding (`PngEncoding`) for every curve,
//! in both byte orders.

use lucid_engine::capture::{PngEncoding, ToneCurve};
use lucid_engine::graph::RenderGraph;
use lucid_passes::post::tonemap::{self, ChannelOrder};
use lucid_passes::renderer::{Renderer, Settings};
use lucid_tests::render::scene;
use lucid_tests::{assert_no_validation_messages, context, run};

#[test]
fn gpu_tone_mapping_matches_the_cpu_encoding() {
    let ctx = context(false);
    let mut renderer =
        Renderer::new(&ctx, scene("cornell-box"), 32, 32, Settings::default()).unwrap();
    for tone in [ToneCurve::Clamp, ToneCurve::Aces, ToneCurve::AgX] {
        let encoding = PngEncoding {
            exposure: 0.5,
            tone,
        };
        let mut g = RenderGraph::new();
        let (images, _) = renderer.add_frame(&mut g);
        let rgba =
            tonemap::add_tonemap_ordered(&mut g, images.hdr, 32, 32, encoding, ChannelOrder::Rgba);
        let bgra =
            tonemap::add_tonemap_ordered(&mut g, images.hdr, 32, 32, encoding, ChannelOrder::Bgra);
        let ids = [g.readback(images.hdr), g.readback(rgba), g.readback(bgra)];
        let out = run(renderer.executor_mut(), g);
        let hdr = out.image(ids[0]).unwrap();
        let rgba = out.image(ids[1]).unwrap();
        let bgra = out.image(ids[2]).unwrap();
        for ((h, a), b) in hdr.pixels.iter().zip(&rgba.pixels).zip(&bgra.pixels) {
            let want = encoding.encode_pixel(*h);
            for c in 0..3 {
                assert!(
                    (a[c] - want[c]).abs() <= 1.5 / 255.0,
                    "{tone:?}: {a:?} vs {want:?} from {h:?}"
                );
                assert_eq!(b[2 - c], a[c], "{tone:?}: BGRA order");
            }
        }
    }
    drop(renderer);
    assert_no_validation_messages(&ctx);
}
