//! A post effect of your own: the street corner rendered headless and turned grey after
//! tonemapping (each pixel's red, green and blue its luminance), written to the PNG named by
//! the first argument.
//!
//! `cargo run --release -p parallax-occlusion --example post_effect -- grey.png`

use pom::prelude::*;

/// The effect's WGSL: the value of each output pixel, from the image before it.
const GREYSCALE: &str = "
fn effect(pixel: vec2<u32>) -> vec4<f32> {
    let colour = textureLoad(input, pixel, 0);
    let luminance = dot(to_linear(colour.rgb), vec3<f32>(0.2126, 0.7152, 0.0722));
    return vec4<f32>(from_linear(vec3<f32>(luminance)), colour.a);
}
";

/// The effect: a pass made on the first frame, run on the display image every frame.
#[derive(Default)]
struct Greyscale {
    pass: Option<FullScreenPass>,
}

impl PostEffect for Greyscale {
    fn stage(&self) -> PostStage {
        PostStage::Display
    }

    fn runs(&self, _: FrameView<'_>) -> bool {
        true
    }

    fn record(
        &mut self,
        frame: FrameView<'_>,
        io: PostIo<'_>,
        encoder: &mut pom::wgpu::CommandEncoder,
        time: Option<&PassTimestamps>,
    ) -> Result<Option<PostImage>, RenderError> {
        self.pass
            .get_or_insert_with(|| {
                FullScreenPass::new(frame, PostStage::Display, "greyscale", GREYSCALE)
            })
            .record(frame, io, encoder, time)?;
        Ok(None)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .ok_or("usage: post_effect OUT.png")?;
    let mut app = App::new();
    app.add_plugin(DefaultPlugins::headless(384, 216));
    app.resources
        .get_or_default::<FrameNodes>()
        .add_post_effect("greyscale", Greyscale::default);
    load_gltf(
        &mut app,
        concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/street_corner.glb"),
    )?;
    app.update()?;
    capture(&app)?.save(&out)?;
    println!("wrote {out}");
    Ok(())
}
