//! Arbitrary bytes as an OBJ file: parsed and validated, or refused with an error; never a
//! panic. A parsed mesh must write back to OBJ and parse again to the same mesh.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tilepattern::mesh::obj;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(mesh) = obj::parse(text) {
        let again = obj::parse(&obj::to_string(&mesh)).expect("a written mesh parses");
        assert_eq!(again.faces(), mesh.faces());
    }
});
