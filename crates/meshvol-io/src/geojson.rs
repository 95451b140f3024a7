//! GeoJSON polygons (RFC 7946): reading `Polygon`, `MultiPolygon`, `GeometryCollection`,
//! `Feature` and `FeatureCollection`, and writing a `Feature` with a `MultiPolygon`.
//!
//! A `FeatureCollection` gives one feature per member, named by its `properties.name`
//! or its `id`; anything else gives one feature. Features whose geometry has no area
//! (`Point`, `LineString`, …) or is `null` are kept, empty, with a warning. Positions
//! with more than two numbers use the first two. A ring's closing copy of its first
//! position is dropped; an unclosed ring is closed implicitly, with a warning. The
//! first ring of a polygon is its exterior, the rest are holes, whatever their winding
//! (RFC 7946 asks for counter-clockwise exteriors; older files often differ).
//!
//! Errors name the JSON item: `features[3].geometry.coordinates[0][2]: expected a
//! position (an array of two or more numbers)`; invalid JSON gives the line and column.
//!
//! The document is parsed with serde_json; the small GeoJSON layer is written here (and
//! not taken from the `geojson` crate) for those located errors.

use std::io::{self, Write};

use meshvol::polygon::{Point2, Polygon};
use serde_json::Value;

use crate::error::{Location, ParseError};
use crate::polygon_feature::PolygonFeature;

/// Nesting deeper than this is refused (GeometryCollections inside each other).
const MAX_DEPTH: u32 = 64;

fn error(path: &str, message: impl Into<String>) -> ParseError {
    ParseError::new(Some(Location::Json(path.to_string())), message)
}

/// Reading state: warnings' counts.
#[derive(Default)]
struct Reader {
    unclosed: usize,
    first_unclosed: String,
    no_area: Vec<String>,
}

impl Reader {
    fn position(&self, value: &Value, path: &str) -> Result<Point2, ParseError> {
        let bad = || error(path, "expected a position (an array of two or more numbers)");
        let items = value.as_array().ok_or_else(bad)?;
        if items.len() < 2 {
            return Err(bad());
        }
        let coordinate = |k: usize| items[k].as_f64().filter(|x| x.is_finite()).ok_or_else(bad);
        Ok([coordinate(0)?, coordinate(1)?])
    }

    fn ring(&mut self, value: &Value, path: &str) -> Result<Vec<Point2>, ParseError> {
        let items = value
            .as_array()
            .ok_or_else(|| error(path, "expected a ring (an array of positions)"))?;
        let mut ring = Vec::with_capacity(items.len());
        for (i, item) in items.iter().enumerate() {
            ring.push(self.position(item, &format!("{path}[{i}]"))?);
        }
        if ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        } else if !ring.is_empty() {
            if self.unclosed == 0 {
                self.first_unclosed = path.to_string();
            }
            self.unclosed += 1;
        }
        Ok(ring)
    }

    fn polygon(&mut self, value: &Value, path: &str) -> Result<Option<Polygon>, ParseError> {
        let rings = value
            .as_array()
            .ok_or_else(|| error(path, "expected a polygon (an array of rings)"))?;
        let mut rings =
            rings.iter().enumerate().map(|(i, r)| self.ring(r, &format!("{path}[{i}]")));
        let Some(exterior) = rings.next().transpose()? else { return Ok(None) };
        let holes = rings.collect::<Result<Vec<_>, _>>()?;
        Ok(Some(Polygon::new(exterior, holes)))
    }

    /// A geometry object's polygons, appended to `out`.
    fn geometry(
        &mut self,
        value: &Value,
        path: &str,
        out: &mut Vec<Polygon>,
        depth: u32,
    ) -> Result<(), ParseError> {
        if depth > MAX_DEPTH {
            return Err(error(path, format!("geometries nested more than {MAX_DEPTH} deep")));
        }
        if value.is_null() {
            self.no_area.push(format!("{path} is null"));
            return Ok(());
        }
        let kind = type_of(value, path)?;
        let coordinates = || {
            value
                .get("coordinates")
                .ok_or_else(|| error(path, format!("a {kind} needs 'coordinates'")))
        };
        match kind {
            "Polygon" => {
                out.extend(self.polygon(coordinates()?, &format!("{path}.coordinates"))?);
            }
            "MultiPolygon" => {
                let here = format!("{path}.coordinates");
                let items = coordinates()?
                    .as_array()
                    .ok_or_else(|| error(&here, "expected an array of polygons"))?;
                for (i, item) in items.iter().enumerate() {
                    out.extend(self.polygon(item, &format!("{here}[{i}]"))?);
                }
            }
            "GeometryCollection" => {
                let here = format!("{path}.geometries");
                let items = value.get("geometries").and_then(Value::as_array).ok_or_else(|| {
                    error(path, "a GeometryCollection needs a 'geometries' array")
                })?;
                for (i, item) in items.iter().enumerate() {
                    self.geometry(item, &format!("{here}[{i}]"), out, depth + 1)?;
                }
            }
            "Point" | "MultiPoint" | "LineString" | "MultiLineString" => {
                self.no_area.push(format!("{path} is a {kind}"));
            }
            other => {
                return Err(error(path, format!("'{other}' is not a GeoJSON geometry type")));
            }
        }
        Ok(())
    }

    fn feature(&mut self, value: &Value, path: &str) -> Result<PolygonFeature, ParseError> {
        let geometry = value
            .get("geometry")
            .ok_or_else(|| error(path, "a Feature needs a 'geometry' (null is allowed)"))?;
        let mut polygons = Vec::new();
        self.geometry(geometry, &format!("{path}.geometry"), &mut polygons, 0)?;
        let name = value
            .get("properties")
            .and_then(|p| p.get("name"))
            .or_else(|| value.get("id"))
            .and_then(|n| match n {
                Value::String(s) => Some(s.clone()),
                Value::Number(n) => Some(n.to_string()),
                _ => None,
            });
        Ok(PolygonFeature { name, polygons })
    }
}

fn type_of<'v>(value: &'v Value, path: &str) -> Result<&'v str, ParseError> {
    let at = if path.is_empty() { "the document" } else { path };
    value.get("type").and_then(Value::as_str).ok_or_else(|| {
        error(path, format!("{at} is not a GeoJSON object: it has no \"type\" string"))
    })
}

/// Reads a GeoJSON document's polygons, one feature per member of a FeatureCollection.
pub(crate) fn read(
    bytes: &[u8],
    warnings: &mut Vec<String>,
) -> Result<Vec<PolygonFeature>, ParseError> {
    let bytes = &bytes[crate::text::bom_len(bytes)..];
    let value: Value = serde_json::from_slice(bytes).map_err(|e| {
        // serde_json's message ends with its own " at line L column C": keep the
        // location apart.
        let message = e.to_string();
        let message = message.rsplit_once(" at line ").map_or(message.as_str(), |(m, _)| m);
        ParseError::line(e.line() as u64, format!("column {}: invalid JSON: {message}", e.column()))
    })?;
    let mut reader = Reader::default();
    let features = match type_of(&value, "")? {
        "FeatureCollection" => {
            let items = value
                .get("features")
                .and_then(Value::as_array)
                .ok_or_else(|| error("features", "a FeatureCollection needs a 'features' array"))?;
            items
                .iter()
                .enumerate()
                .map(|(i, f)| reader.feature(f, &format!("features[{i}]")))
                .collect::<Result<Vec<_>, _>>()?
        }
        "Feature" => vec![reader.feature(&value, "feature")?],
        _ => {
            let mut polygons = Vec::new();
            reader.geometry(&value, "geometry", &mut polygons, 0)?;
            vec![PolygonFeature { name: None, polygons }]
        }
    };
    if reader.unclosed > 0 {
        warnings.push(format!(
            "{} ring(s) not closed (first at {}): closed implicitly",
            reader.unclosed, reader.first_unclosed
        ));
    }
    if let Some(first) = reader.no_area.first() {
        warnings.push(format!(
            "{} geometr{} without area (first: {first}): counted as empty",
            reader.no_area.len(),
            if reader.no_area.len() == 1 { "y" } else { "ies" }
        ));
    }
    Ok(features)
}

/// The coordinates of a MultiPolygon: rings closed, as RFC 7946 requires.
fn multipolygon_coordinates(polygons: &[Polygon]) -> Value {
    let ring = |ring: &[Point2]| -> Value {
        ring.iter().chain(ring.first()).map(|p| Value::from(p.to_vec())).collect()
    };
    polygons.iter().map(|p| p.rings().map(ring).collect::<Value>()).collect()
}

/// Writes a GeoJSON `Feature` with a `MultiPolygon` geometry and the given properties,
/// and a newline. Numbers are written in their shortest round-trip form. Rings are
/// written as given: for RFC 7946, exteriors counter-clockwise and holes clockwise.
///
/// ```
/// use meshvol::polygon::Polygon;
/// let square = Polygon::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], vec![]);
/// let mut properties = serde_json::Map::new();
/// properties.insert("area".into(), 1.0.into());
/// let mut out = Vec::new();
/// meshvol_io::geojson::write_feature(&mut out, &[square], properties).unwrap();
/// let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
/// assert_eq!(v["geometry"]["type"], "MultiPolygon");
/// assert_eq!(v["geometry"]["coordinates"][0][0][4], serde_json::json!([0.0, 0.0]));
/// ```
pub fn write_feature(
    out: &mut impl Write,
    polygons: &[Polygon],
    properties: serde_json::Map<String, Value>,
) -> io::Result<()> {
    let feature = serde_json::json!({
        "type": "Feature",
        "properties": properties,
        "geometry": { "type": "MultiPolygon", "coordinates": multipolygon_coordinates(polygons) },
    });
    serde_json::to_writer(&mut *out, &feature)?;
    out.write_all(b"\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<(Vec<PolygonFeature>, Vec<String>), ParseError> {
        crate::polygon_feature::with_warnings(read, s)
    }

    #[test]
    fn reads_collections_features_and_geometries() {
        let (f, w) = parse(
            r#"{"type": "FeatureCollection", "features": [
                {"type": "Feature", "properties": {"name": "lot 1"}, "geometry":
                    {"type": "Polygon", "coordinates": [[[0,0],[4,0],[4,2],[0,2],[0,0]], [[1,1],[2,1],[2,1.5],[1,1]]]}},
                {"type": "Feature", "id": 7, "properties": null, "geometry":
                    {"type": "MultiPolygon", "coordinates": [[[[0,0,9],[1,0,9],[1,1,9],[0,0,9]]], [[[5,5],[6,5],[6,6]]]]}},
                {"type": "Feature", "properties": {}, "geometry": {"type": "Point", "coordinates": [1, 2]}},
                {"type": "Feature", "properties": {}, "geometry": null}
            ]}"#,
        )
        .unwrap();
        assert_eq!(f.len(), 4);
        assert_eq!(f[0].name.as_deref(), Some("lot 1"));
        assert_eq!(f[0].polygons[0].exterior.len(), 4);
        assert_eq!(f[0].polygons[0].holes[0], vec![[1.0, 1.0], [2.0, 1.0], [2.0, 1.5]]);
        assert_eq!((f[1].name.as_deref(), f[1].polygons.len()), (Some("7"), 2));
        assert!(f[2].polygons.is_empty() && f[3].polygons.is_empty());
        assert_eq!(w.len(), 2);
        assert!(w[0].contains("features[1].geometry.coordinates[1][0]"), "{w:?}");
        assert!(w[1].contains("2 geometries without area"), "{w:?}");

        let (f, _) =
            parse(r#"{"type": "Polygon", "coordinates": [[[0,0],[1,0],[0,1],[0,0]]]}"#).unwrap();
        assert_eq!(f[0].polygons[0].exterior.len(), 3);
        let (f, _) = parse(r#"{"type": "GeometryCollection", "geometries": [{"type": "Polygon", "coordinates": []}]}"#).unwrap();
        assert!(f[0].polygons.is_empty());
    }

    #[test]
    fn errors_name_the_json_item() {
        let e = parse(r#"{"type": "FeatureCollection", "features": [{"type": "Feature", "geometry": null},
            {"type": "Feature", "geometry": {"type": "Polygon", "coordinates": [[[0,0],[1,"x"],[0,1]]]}}]}"#)
        .unwrap_err();
        assert_eq!(
            e.location,
            Some(Location::Json("features[1].geometry.coordinates[0][1]".into()))
        );
        assert!(e.message.contains("expected a position"));
        let e = parse("{\"type\": \"Polygon\",\n \"coordinates\": [[[0,0],]]}").unwrap_err();
        assert_eq!(e.location, Some(Location::Line(2)));
        assert!(e.message.starts_with("column"), "{}", e.message);
        let e = parse(r#"{"type": "Polygone", "coordinates": []}"#).unwrap_err();
        assert!(e.message.contains("'Polygone'"));
        let e = parse(r#"[1, 2]"#).unwrap_err();
        assert!(e.message.contains("not a GeoJSON object"));
    }

    #[test]
    fn writes_what_it_reads() {
        let polygons = vec![Polygon::new(
            vec![[0.1, 0.2], [1e7 + 0.3, 0.0], [1.0, 1.0 / 3.0]],
            vec![vec![[0.5, 0.5], [0.6, 0.5], [0.6, 0.6]]],
        )];
        let mut out = Vec::new();
        write_feature(&mut out, &polygons, Default::default()).unwrap();
        let (f, w) = parse(std::str::from_utf8(&out).unwrap()).unwrap();
        assert_eq!((f[0].polygons.clone(), w.len()), (polygons, 0));
    }
}
