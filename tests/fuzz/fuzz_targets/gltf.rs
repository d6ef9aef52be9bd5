//! The glTF loader: a .glb or a self-contained .gltf.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = pom_tests::fuzz_entry::gltf(data);
});
