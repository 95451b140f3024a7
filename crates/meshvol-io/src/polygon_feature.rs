//! What a polygon reader gives: the features of a file ([`PolygonFeature`]), shared by
//! the WKT and GeoJSON readers and [`crate::polygons`], which picks one.

#[cfg(test)]
use crate::error::ParseError;
use meshvol::polygon::Polygon;

/// One feature of a file: a WKT geometry, a GeoJSON feature, or the whole file.
#[derive(Clone, Debug, PartialEq)]
pub struct PolygonFeature {
    /// A GeoJSON feature's `properties.name` or `id`.
    pub name: Option<String>,
    pub polygons: Vec<Polygon>,
}

/// A polygon reader: [`crate::wkt`]'s or [`crate::geojson`]'s.
#[cfg(test)]
type Reader = fn(&[u8], &mut Vec<String>) -> Result<Vec<PolygonFeature>, ParseError>;

/// A polygon reader's features and warnings for `text`, for the readers' unit tests.
#[cfg(test)]
pub(crate) fn with_warnings(
    read: Reader,
    text: &str,
) -> Result<(Vec<PolygonFeature>, Vec<String>), ParseError> {
    let mut warnings = Vec::new();
    read(text.as_bytes(), &mut warnings).map(|f| (f, warnings))
}
