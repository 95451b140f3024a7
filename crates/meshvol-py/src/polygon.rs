//! `meshvol.polygon_area`: area, perimeter, centroid and second moments of plane
//! polygons with holes (what `meshvol area` reports).

use crate::convert::coordinates;
use crate::errors::invalid;
use meshvol::polygon::{area_properties, polygon_issues, Point2, Polygon};
use numpy::PyArray1;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Area, perimeter, centroid and second moments of plane polygons, with the names of
/// the keys of `meshvol area --json` (its inertia keys flattened).
///
/// Holes subtract whatever their winding. ix = ∫(y - cy)² dA and iy = ∫(x - cx)² dA are
/// about axes through the centroid parallel to x and y, ixy = ∫(x - cx)(y - cy) dA, polar
/// = ix + iy; principal_moments holds the larger first, about the axis at
/// principal_angle_degrees counter-clockwise from x. With zero area the centroid is None
/// and the moments are zero. issues lists what makes the numbers mean other than they
/// seem (self-intersecting rings, holes outside, overlapping polygons), as the command
/// warns.
#[pyclass(module = "meshvol", name = "AreaProperties", frozen)]
pub struct PyAreaProperties {
    /// Exteriors minus holes.
    #[pyo3(get)]
    area: f64,
    /// The length of every ring, holes included.
    #[pyo3(get)]
    perimeter: f64,
    centroid: Option<Point2>,
    /// ∫(y - cy)² dA.
    #[pyo3(get)]
    ix: f64,
    /// ∫(x - cx)² dA.
    #[pyo3(get)]
    iy: f64,
    /// ∫(x - cx)(y - cy) dA.
    #[pyo3(get)]
    ixy: f64,
    /// ix + iy.
    #[pyo3(get)]
    polar: f64,
    principal_moments: [f64; 2],
    /// The angle of the first principal axis, counter-clockwise from x, in degrees.
    #[pyo3(get)]
    principal_angle_degrees: f64,
    /// Problems found in the rings, as sentences.
    #[pyo3(get)]
    issues: Vec<String>,
}

#[pymethods]
impl PyAreaProperties {
    /// The centroid, a float64 array of 2, or None when the area is zero.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// The principal second moments, larger first.
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.principal_moments)
    }

    fn __repr__(&self) -> String {
        let centroid = match self.centroid {
            Some([x, y]) => format!("({x:?}, {y:?})"),
            None => "None".to_string(),
        };
        format!(
            "AreaProperties(area={:?}, perimeter={:?}, centroid={centroid})",
            self.area, self.perimeter
        )
    }
}

/// A ring's points, checked finite, without a closing copy of the first point.
fn checked_ring(mut points: Vec<Point2>, what: &str) -> PyResult<Vec<Point2>> {
    for (i, p) in points.iter().enumerate() {
        if let Some(x) = p.iter().find(|x| !x.is_finite()) {
            return Err(invalid(format!("{what}: point {i} has a non-finite coordinate ({x})")));
        }
    }
    if points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
    Ok(points)
}

/// A ring given as an (n, 2) array.
fn ring_of_array(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Point2>> {
    checked_ring(coordinates::<2>(obj, what)?, what)
}

/// A GeoJSON ring: positions of two or more numbers (a third, z, is ignored).
fn ring_of_geojson(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Vec<Point2>> {
    let positions: Vec<Vec<f64>> =
        obj.extract().map_err(|e| invalid(format!("{what} must be a list of positions: {e}")))?;
    let mut points = Vec::with_capacity(positions.len());
    for (i, p) in positions.iter().enumerate() {
        match p.as_slice() {
            [x, y, ..] => points.push([*x, *y]),
            _ => return Err(invalid(format!("{what}: position {i} has fewer than 2 numbers"))),
        }
    }
    checked_ring(points, what)
}

/// A GeoJSON polygon's coordinates: the exterior ring, then the holes.
fn polygon_of_geojson(rings: &Bound<'_, PyAny>, what: &str) -> PyResult<Polygon> {
    let mut rings: Vec<Vec<Point2>> = rings
        .try_iter()?
        .enumerate()
        .map(|(r, ring)| ring_of_geojson(&ring?, &format!("{what}ring {r}")))
        .collect::<PyResult<_>>()?;
    if rings.is_empty() {
        return Err(invalid(format!("{what}polygon has no rings")));
    }
    let exterior = rings.remove(0);
    Ok(Polygon::new(exterior, rings))
}

/// Polygons from a GeoJSON geometry (a dict, or an object's `__geo_interface__`).
fn polygons_of_geojson(geometry: &Bound<'_, PyAny>) -> PyResult<Vec<Polygon>> {
    let kind: String = geometry.get_item("type")?.extract()?;
    let coordinates = geometry.get_item("coordinates")?;
    match kind.as_str() {
        "Polygon" => Ok(vec![polygon_of_geojson(&coordinates, "")?]),
        "MultiPolygon" => coordinates
            .try_iter()?
            .enumerate()
            .map(|(p, polygon)| polygon_of_geojson(&polygon?, &format!("polygon {p} ")))
            .collect(),
        other => Err(invalid(format!(
            "a {other} geometry has no area: give a Polygon or a MultiPolygon"
        ))),
    }
}

/// Area, perimeter, centroid and second moments of a polygon with holes (what
/// `meshvol area` reports).
///
/// exterior is an (n, 2) array of the outline's points (a closing copy of the first
/// point is dropped), holes a list of such arrays. Instead of arrays, a GeoJSON
/// Polygon or MultiPolygon geometry can be given: a dict, or any object with
/// `__geo_interface__` (shapely and geopandas geometries).
#[pyfunction]
#[pyo3(signature = (exterior, holes = None))]
pub fn polygon_area(
    py: Python<'_>,
    exterior: &Bound<'_, PyAny>,
    holes: Option<&Bound<'_, PyAny>>,
) -> PyResult<PyAreaProperties> {
    let geometry = if exterior.hasattr("__geo_interface__")? {
        Some(exterior.getattr("__geo_interface__")?)
    } else if exterior.cast::<PyDict>().is_ok() {
        Some(exterior.clone())
    } else {
        None
    };
    let polygons = match geometry {
        Some(geometry) => {
            if holes.is_some() {
                return Err(PyTypeError::new_err(
                    "holes are given inside a GeoJSON geometry, not as an argument",
                ));
            }
            polygons_of_geojson(&geometry)?
        }
        None => {
            let outline = ring_of_array(exterior, "exterior")?;
            let holes = match holes {
                None => Vec::new(),
                Some(holes) => holes
                    .try_iter()?
                    .enumerate()
                    .map(|(h, hole)| ring_of_array(&hole?, &format!("hole {}", h + 1)))
                    .collect::<PyResult<_>>()?,
            };
            vec![Polygon::new(outline, holes)]
        }
    };
    let (measured, issues) = py.detach(|| (area_properties(&polygons), polygon_issues(&polygons)));
    let (principal_moments, angle) =
        if measured.centroid.is_some() { measured.inertia.principal() } else { ([0.0; 2], 0.0) };
    Ok(PyAreaProperties {
        area: measured.area,
        perimeter: measured.perimeter,
        centroid: measured.centroid,
        ix: measured.inertia.ix,
        iy: measured.inertia.iy,
        ixy: measured.inertia.ixy,
        polar: measured.inertia.polar,
        principal_moments,
        principal_angle_degrees: angle.to_degrees(),
        issues: issues.iter().map(ToString::to_string).collect(),
    })
}
