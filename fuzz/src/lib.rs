//! What every fuzz target checks: reading `data` as a file called `name` gives a mesh
//! whose objects are valid face ranges and that the kernel can measure, or an error
//! that names the file. Anything else (a panic, an abort, a timeout, running out
//! of memory) is a crash for the fuzzer.

use std::path::Path;

use meshvol::Surface;

pub fn check(name: &str, data: &[u8]) {
    match meshvol_io::read_bytes(Path::new(name), data.to_vec()) {
        Ok(loaded) => {
            let faces = loaded.surface.face_count();
            let mut next = 0;
            for object in &loaded.objects {
                assert_eq!(object.faces.start, next, "objects are contiguous");
                assert!(object.faces.end <= faces);
                next = object.faces.end;
            }
            assert!(loaded.objects.is_empty() || (loaded.objects.len() >= 2 && next == faces));
            // Finite coordinates can still overflow in products (1e300³): only panics count.
            let _ = meshvol::mass_properties(&loaded.surface);
        }
        Err(e) => assert!(e.to_string().starts_with(name), "{e}"),
    }
}

/// A 3MF package (stored, uncompressed) whose model part is `model`.
pub fn three_mf(model: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let options =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let result = (|| -> zip::result::ZipResult<Vec<u8>> {
        zip.start_file("3D/3dmodel.model", options)?;
        zip.write_all(model)?;
        Ok(zip.finish()?.into_inner())
    })();
    result.expect("writing a zip in memory")
}
