//! Writes a UV sphere (radius 100) of about N triangles as a binary STL, centred at
//! (X, 0, 0) (default 0): the inputs of the scaling benchmark (`bench/scaling/run.sh`).
//!
//! ```text
//! cargo run --release -p meshvol-io --example sphere -- 5000000 /tmp/sphere-5m.stl [X]
//! ```

use meshvol::shapes::uv_sphere;
use std::io::BufWriter;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(count), Some(path)) = (args.get(1), args.get(2)) else {
        return Err("usage: sphere TRIANGLES OUT.stl [X]".into());
    };
    let triangles: f64 = count.parse()?;
    let x: f64 = args.get(3).map_or(Ok(0.0), |x| x.parse())?;
    // 2·segments·(rings − 1) triangles, with rings = segments / 2.
    let segments = (triangles.max(16.0)).sqrt().round() as u32;
    let sphere = uv_sphere(100.0, segments, segments / 2);
    let positions = sphere.positions().iter().map(|p| [p[0] + x, p[1], p[2]]).collect();
    let faces = (0..sphere.face_count()).map(|f| sphere.face(f));
    let sphere = meshvol::Mesh::from_polygons(positions, faces)?;
    let mut out = BufWriter::new(std::fs::File::create(path)?);
    meshvol_io::write::stl_binary(&mut out, &sphere)?;
    Ok(())
}
