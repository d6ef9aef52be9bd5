//! The image loader: a selector byte (kind, height channel) and a PNG or JPEG file.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = pom_tests::fuzz_entry::image(data);
});
