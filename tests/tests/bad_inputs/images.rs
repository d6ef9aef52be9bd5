//! Image files: truncated, corrupt, empty, odd sizes and depths, beyond the device limit.

use super::*;

fn image_error(file: &str, kind: TextureKind) -> ImageError {
    let error = Image::load(corpus(file), kind).unwrap_err();
    let name = Path::new(file).file_name().unwrap().to_str().unwrap();
    assert!(error.to_string().contains(name), "{error}");
    error
}

fn assert_load_error(file: &str, reason: &str) {
    match image_error(file, TextureKind::Height) {
        ImageError::Load { path, reason: said } => {
            assert_eq!(path, corpus(file));
            assert!(said.contains(reason), "{said}");
        }
        other => panic!("{file}: expected ImageError::Load, got {other:?}"),
    }
}

#[test]
fn truncated_png() {
    assert_load_error("images/truncated.png", "unexpected end of file");
}

#[test]
fn corrupt_png_data() {
    assert_load_error("images/corrupt_idat.png", "Corrupt deflate stream");
}

#[test]
fn truncated_jpeg() {
    assert_load_error("images/truncated.jpg", "Not enough bytes");
}

#[test]
fn corrupt_jpeg_huffman_table() {
    assert_load_error("images/corrupt_huffman.jpg", "Huffman table");
}

#[test]
fn zero_byte_png() {
    assert_load_error("images/empty.png", "unexpected end of file");
}

#[test]
fn zero_byte_jpeg() {
    assert_load_error("images/empty.jpg", "Not enough bytes");
}

#[test]
fn text_file_named_png() {
    assert_load_error("images/text_named.png", "Invalid PNG signature");
}

#[test]
fn png_with_zero_width() {
    assert_load_error("images/zero_width.png", "Invalid image dimensions");
}

#[test]
fn missing_image_file() {
    assert_load_error("images/no_such_file.png", "No such file");
}

#[test]
fn float_radiance_hdr_file() {
    // The loader decodes PNG and JPEG only; a float HDR file is named and refused.
    assert_load_error("images/float_radiance.hdr", "format Hdr is not supported");
}

#[test]
fn png_declaring_an_enormous_size_is_refused_before_allocating() {
    let error = image_error("images/declares_enormous_size.png", TextureKind::Color);
    assert!(
        matches!(
            error,
            ImageError::TooLarge {
                width: 1_000_000,
                height: 1_000_000,
                max_side: pom::MAX_IMAGE_SIDE,
                ..
            }
        ),
        "{error:?}"
    );
    assert!(error.to_string().contains("32768 per side"), "{error}");
}

#[test]
fn one_by_one_height_map() {
    let height = Image::load(corpus("images/one_by_one_height.png"), TextureKind::Height).unwrap();
    assert_eq!(height.size(), (1, 1));
    assert_eq!(height.mip_chain().len(), 1);
    render_height_map(height);
}

#[test]
fn non_square_non_power_of_two_height_map() {
    let path = corpus("images/non_square_npot_height.png");
    let height = Image::load(path, TextureKind::Height).unwrap();
    assert_eq!(height.size(), (37, 23));
    let sizes: Vec<_> = height.mip_chain().iter().map(Pixels::dimensions).collect();
    assert_eq!(sizes.last(), Some(&(1, 1)));
    render_height_map(height);
}

#[test]
fn sixteen_bit_height_map() {
    let path = corpus("images/sixteen_bit_height.png");
    let height = Image::load(path, TextureKind::Height).unwrap();
    assert!(matches!(height.pixels(), Pixels::Gray16(_)), "stays 16-bit");
    render_height_map(height);
}

#[test]
fn sixteen_bit_rgba_normal_map_with_alpha_height() {
    let path = corpus("images/sixteen_bit_rgba_normal.png");
    let normal = Image::load(&path, TextureKind::Normal).unwrap();
    assert!(
        matches!(normal.pixels(), Pixels::Rgba8(_)),
        "normals become RGBA8"
    );
    let alpha = Image::load_height(&path, Channel::Alpha).unwrap();
    assert!(
        matches!(alpha.pixels(), Pixels::Gray16(_)),
        "heights keep 16 bits"
    );
    let mut app = material_app(|images| ParallaxOcclusionMaterial {
        normal_map: Some(images.add(normal)),
        height_map: Some(HeightSource::Texture(images.add(alpha))),
        ..ParallaxOcclusionMaterial::default()
    });
    renders_cleanly(&mut app);
}

#[test]
fn float_image_in_memory_with_nan_and_out_of_range_values() {
    // Float images reach the library through `Image::from_decoded` (the file loader has no
    // float format): values are clamped to 0..=1 (NaN becomes 0) at 16 bits.
    let values = [f32::NAN, f32::INFINITY, -5.0, 1e30, 0.25, f32::NEG_INFINITY];
    let float = Rgba32FImage::from_fn(6, 3, |x, _| {
        let v = values[x as usize];
        Rgba([v, v, v, v])
    });
    let decoded = DynamicImage::ImageRgba32F(float);
    let height =
        Image::from_decoded(decoded.clone(), TextureKind::Height, Channel::Red, "float").unwrap();
    let Pixels::Gray16(pixels) = height.pixels() else {
        panic!("a float height becomes 16-bit, got {:?}", height.pixels());
    };
    let row: Vec<u16> = (0..6).map(|x| pixels.get_pixel(x, 0).0[0]).collect();
    // NaN, +∞, −5, 10³⁰, 0.25, −∞.
    assert_eq!(row, [0, 65535, 0, 65535, 16384, 0], "heights");
    let colour = Image::from_decoded(decoded, TextureKind::Color, Channel::Red, "float").unwrap();
    let Pixels::Rgba8(texels) = colour.pixels() else {
        panic!("a float colour becomes RGBA8, got {:?}", colour.pixels());
    };
    let row: Vec<u8> = (0..6).map(|x| texels.get_pixel(x, 0).0[0]).collect();
    assert_eq!(row, [0, 255, 0, 255, 64, 0], "colours");
    assert!(
        texels.pixels().all(|p| p.0 == [p.0[0]; 4]),
        "every channel clamps alike"
    );
    let mut app = material_app(|images| ParallaxOcclusionMaterial {
        base_color_texture: Some(images.add(colour)),
        height_map: Some(HeightSource::Texture(images.add(height))),
        ..ParallaxOcclusionMaterial::default()
    });
    renders_cleanly(&mut app);
}

#[test]
fn palette_png_height_map() {
    let path = corpus("images/palette_height.png");
    let height = Image::load(path, TextureKind::Height).unwrap();
    assert!(matches!(height.pixels(), Pixels::Gray8(_)));
    render_height_map(height);
}

#[test]
fn normal_map_without_alpha_asked_for_an_alpha_height() {
    let error =
        Image::load_height(corpus("images/normal_without_alpha.png"), Channel::Alpha).unwrap_err();
    assert!(matches!(error, ImageError::NoAlpha { .. }), "{error:?}");
    assert!(
        error
            .to_string()
            .contains("normal_without_alpha.png has no alpha channel"),
        "{error}"
    );
}

#[test]
fn grey_with_alpha_gives_an_alpha_height() {
    let height =
        Image::load_height(corpus("images/grey_alpha_height.png"), Channel::Alpha).unwrap();
    let Pixels::Gray8(pixels) = height.pixels() else {
        panic!("8-bit");
    };
    assert_eq!(pixels.get_pixel(3, 0).0, [96], "alpha, not the grey");
    render_height_map(height);
}

#[test]
fn height_map_beyond_the_devices_texture_limit() {
    // Generated at run time: its size depends on the device (lavapipe allows 16384).
    install_logger();
    let probe = pom_app(32, TargetFormat::Float32).unwrap();
    let limit = probe
        .resources
        .get::<pom::GpuContext>()
        .unwrap()
        .device
        .limits()
        .max_texture_dimension_2d;
    drop(probe);
    let width = limit + 1;
    let dir = std::env::temp_dir().join(format!("pom-bad-inputs-wide-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("too_wide.png");
    GrayImage::from_fn(width, 3, |x, _| Luma([(x % 251) as u8]))
        .save(&path)
        .unwrap();
    let height = Image::load(&path, TextureKind::Height).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(height.size(), (width, 3));
    render_height_map(height);
    let expected = format!("is {width}×3, over the device's limit of {limit} texels per side");
    let warned = warnings_containing(&expected);
    assert_eq!(warned.len(), 1, "{warned:?}");
    assert!(
        warned[0].contains(&format!("uploaded at {}×1", width / 2)),
        "{warned:?}"
    );
}

#[test]
fn images_made_in_code_with_enormous_sizes_are_errors_not_panics() {
    match Image::gpu_written(u32::MAX, u32::MAX, TextureKind::Color, [0; 4]) {
        Err(ImageError::TooLarge { width, .. }) => assert_eq!(width, u32::MAX),
        other => panic!("expected ImageError::TooLarge, got {other:?}"),
    }
    match Image::gpu_written(100_000, 100_000, TextureKind::Color, [0; 4]) {
        Err(error) => assert!(error.to_string().contains("100000"), "{error}"),
        Ok(_) => panic!("a 100,000² image was made"),
    }
    match Image::from_rgba8(u32::MAX, u32::MAX, vec![0; 16], TextureKind::Color) {
        Err(ImageError::WrongLength { found, .. }) => assert_eq!(found, 16),
        other => panic!("expected ImageError::WrongLength, got {other:?}"),
    }
}

#[test]
fn a_height_field_asked_with_a_side_of_zero_has_one_texel() {
    let field = pom::HeightField::from_fn(0, 0, |_, _| 0.5);
    assert_eq!(field.size(), (1, 1));
    assert_eq!(field.sample(0.3, 0.7), 0.5);
    assert_eq!(field.normal_map(0.05).size(), (1, 1));
    assert_eq!(pom::patterns::bricks(0, 4.0, 8.0).to_image().size(), (1, 1));
}
