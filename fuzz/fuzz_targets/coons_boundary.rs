#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    vericad::fuzz_entry::coons_boundary(data);
});
