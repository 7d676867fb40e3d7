#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let _ = vericad::fuzz_entry::ssi_surfaces(data);
});
