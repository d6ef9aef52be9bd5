//! RON material presets.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = pom_tests::fuzz_entry::preset(data);
});
