use pom::prelude::*;

pom::material_parameters! {
    /// A matte surface of one colour, lit by every light and shadowed by the scene.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Matte {
        parameters {
            /// The surface's colour, linear.
            color: Color = Color::WHITE, ParamSpec::color();
        }
    }
}
impl ShadedMaterial for Matte {
    const SHADING: WgslFile = WgslFile::new("matte.wgsl", include_str!("matte.wgsl"));
}
