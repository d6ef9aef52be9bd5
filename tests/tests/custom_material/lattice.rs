use pom::prelude::*;

pom::material_parameters! {
    /// A plate with a grid of round holes: a material that cuts holes.
    #[derive(Clone, Debug, PartialEq)]
    pub struct Lattice {
        parameters {
            /// The plate's colour, linear.
            color: Color = Color::WHITE, ParamSpec::color();
            /// Holes along each side of the texture.
            cells: f32 = 4.0, ParamSpec::float(1.0, 64.0);
            /// Each hole's radius, as a fraction of a cell: 0 is no hole.
            hole_radius: f32 = 0.3, ParamSpec::float(0.0, 0.5);
        }
    }
}
impl ShadedMaterial for Lattice {
    const SHADING: WgslFile = WgslFile::new("lattice.wgsl", include_str!("lattice.wgsl"));
    const CUTS_OUT: bool = true;
}
