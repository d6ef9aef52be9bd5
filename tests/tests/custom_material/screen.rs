use pom::prelude::*;

pom::material_parameters! {
    /// A picture that gives off light of its own: a screen, a lit sign.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Screen {
        textures {
            /// The picture, sRGB (white when absent).
            picture: WhiteSrgb,
        }
        parameters {
            /// Multiplies the picture, linear.
            tint: Color = Color::WHITE, ParamSpec::color();
            /// Multiplies the light it gives off: above 1 for a screen in daylight.
            brightness: f32 = 1.0, ParamSpec::float(0.0, 100.0);
        }
    }
}
impl ShadedMaterial for Screen {
    const SHADING: WgslFile = WgslFile::new("screen.wgsl", include_str!("screen.wgsl"));
}
