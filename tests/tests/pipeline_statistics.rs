//! Pipeline executable statistics (`VK_KHR_pipeline_executable_properties`): captured for every
//! compute pipeline when requested and supported, absent otherwise, and never an error.

use ash::vk;
use lucid_engine::shader::{ShaderLibrary, Specialization};
use lucid_engine::{Context, ContextDesc};
use lucid_passes::shaders::test_pattern::GRADIENT;
use lucid_tests::{assert_no_validation_messages, context};

/// Whether the context's device offers the extension and its `pipelineExecutableInfo` feature.
fn device_supports_statistics(ctx: &Context) -> bool {
    // SAFETY: the physical device belongs to the context's instance.
    let extensions = unsafe {
        ctx.instance()
            .enumerate_device_extension_properties(ctx.physical_device())
    }
    .expect("device extensions");
    let listed = extensions
        .iter()
        .any(|e| e.extension_name_as_c_str() == Ok(ash::khr::pipeline_executable_properties::NAME));
    let mut feature = vk::PhysicalDevicePipelineExecutablePropertiesFeaturesKHR::default();
    let mut query = vk::PhysicalDeviceFeatures2::default().push_next(&mut feature);
    // SAFETY: as above; the chain points at locals.
    unsafe {
        ctx.instance()
            .get_physical_device_features2(ctx.physical_device(), &mut query)
    };
    listed && feature.pipeline_executable_info == vk::TRUE
}

#[test]
fn statistics_are_not_captured_unless_requested() {
    let ctx = context(false);
    assert!(!ctx.info().pipeline_statistics);
    let library = ShaderLibrary::new(&ctx, None).unwrap();
    let pipeline = library
        .pipeline(&GRADIENT, &Specialization::default())
        .unwrap();
    assert!(pipeline.statistics.is_empty());
    assert_eq!(library.pipeline_statistics(), None);
    drop((pipeline, library));
    assert_no_validation_messages(&ctx);
}

#[test]
fn requested_statistics_are_captured_where_the_device_supports_them() {
    let desc = ContextDesc {
        pipeline_statistics: true,
        ..ContextDesc::for_tests(false)
    };
    let ctx = Context::new(&desc).expect("requesting statistics never fails context creation");
    let supported = device_supports_statistics(&ctx);
    assert_eq!(ctx.info().pipeline_statistics, supported);
    let library = ShaderLibrary::new(&ctx, None).unwrap();
    let pipeline = library
        .pipeline(&GRADIENT, &Specialization::default())
        .unwrap();
    let listed = library.pipeline_statistics();
    if supported {
        assert!(
            !pipeline.statistics.is_empty(),
            "{} reported no statistics",
            ctx.info().name
        );
        assert!(pipeline.statistics.iter().all(|s| !s.name.is_empty()));
        let listed = listed.expect("statistics are listed");
        assert_eq!(listed.len(), 1);
        assert_eq!(listed[0].name, GRADIENT.name);
        assert_eq!(listed[0].statistics, pipeline.statistics);
    } else {
        assert!(pipeline.statistics.is_empty());
        assert_eq!(listed, None);
    }
    drop((pipeline, library));
    assert_no_validation_messages(&ctx);
}
