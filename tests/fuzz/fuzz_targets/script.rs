//! RON scene scripts, parsed and checked.
#![no_main]

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let _ = pom_tests::fuzz_entry::script(data);
});
