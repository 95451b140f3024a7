//! Writes `samples/flanged-bushing.stl`, the sample part the README measures: a flanged
//! bushing (mm) with a bore, chamfers and an O-ring groove, turned as a solid of
//! revolution so its polyhedral volume has a closed form to check meshvol against.
//!
//! Run: `cargo run -p meshvol --example sample_part -- samples/flanged-bushing.stl`

use meshvol::shapes::{revolve, revolve_volume};
use meshvol::{mass_properties, Surface};

/// (radius, height) in mm, counter-clockwise: along the bottom, up the outside, down the bore.
const PROFILE: [(f64, f64); 15] = [
    (10.0, 0.0),
    (29.0, 0.0),
    (30.0, 1.0),
    (30.0, 5.0),
    (29.0, 6.0),
    (17.0, 6.0),
    (16.0, 7.0),
    (16.0, 15.0),
    (14.5, 15.0),
    (14.5, 18.0),
    (16.0, 18.0),
    (16.0, 29.0),
    (15.0, 30.0),
    (11.0, 30.0),
    (10.0, 29.0),
];
const SEGMENTS: u32 = 128;

fn main() -> std::io::Result<()> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "samples/flanged-bushing.stl".into());
    let part = revolve(&PROFILE, SEGMENTS).triangulated();
    let mut bytes = Vec::with_capacity(84 + 50 * part.face_count());
    let mut header = [b' '; 80];
    let title = b"meshvol sample part: flanged bushing, millimetres";
    header[..title.len()].copy_from_slice(title);
    bytes.extend_from_slice(&header);
    bytes.extend_from_slice(&(part.face_count() as u32).to_le_bytes());
    for face in 0..part.face_count() {
        part.fan(face, |a, b, c| {
            // The normal is left zero: readers recompute it, and volume never uses it.
            let floats = [[0.0; 3], a, b, c].concat();
            for x in floats {
                bytes.extend_from_slice(&(x as f32).to_le_bytes());
            }
            bytes.extend_from_slice(&0u16.to_le_bytes());
        });
    }
    std::fs::write(&out, bytes)?;
    println!(
        "wrote {out}: {} triangles; closed-form volume {} mm^3, computed {} mm^3",
        part.face_count(),
        revolve_volume(&PROFILE, SEGMENTS),
        mass_properties(&part).signed_volume
    );
    Ok(())
}
