//! `meshvol.polygon_area`: area, perimeter, centroid and second moments of plane
//! polygons with holes (what `meshvol area` reports).

use crate::convert::coordinates;
use crate::dict::Fields;
use crate::errors::{invalid, mesh_error};
use meshvol::polygon::{polygon_issues, Point2, Polygon};
use meshvol_io::PolygonFeature;
use meshvol_report::area::{area, AreaReport, InertiaReport};
use meshvol_report::quantities::Quantities;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Area, perimeter, centroid and second moments of plane polygons: the report of
/// `meshvol area --json` (area, perimeter, centroid, inertia, rings, warnings, ...),
/// whose keys are the keys of to_dict(), with the second moments also as attributes.
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
    report: AreaReport,
    fields: Fields,
    /// Problems found in the rings, as sentences.
    #[pyo3(get)]
    issues: Vec<String>,
}

impl PyAreaProperties {
    fn inertia(&self) -> InertiaReport {
        // No area: no centroid, and moments of zero.
        self.report.inertia.unwrap_or_default()
    }
}

#[pymethods]
impl PyAreaProperties {
    /// The centroid, a float64 array of 2, or None when the area is zero.
    #[getter]
    fn centroid<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.report.centroid.map(|c| PyArray1::from_slice(py, &c))
    }

    /// ∫(y - cy)² dA.
    #[getter]
    fn ix(&self) -> f64 {
        self.inertia().ix
    }

    /// ∫(x - cx)² dA.
    #[getter]
    fn iy(&self) -> f64 {
        self.inertia().iy
    }

    /// ∫(x - cx)(y - cy) dA.
    #[getter]
    fn ixy(&self) -> f64 {
        self.inertia().ixy
    }

    /// ix + iy.
    #[getter]
    fn polar(&self) -> f64 {
        self.inertia().polar
    }

    /// The principal second moments, ascending (as MassProperties.principal_moments);
    /// principal_axes[k] is the axis of principal_moments[k]. (The command's JSON lists
    /// them larger first, in inertia.principal.)
    #[getter]
    fn principal_moments<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &ascending(&self.inertia()).0)
    }

    /// The principal axes as a (2, 2) float64 array: row k is the unit axis (through the
    /// centroid) of principal_moments[k], a right-handed pair.
    #[getter]
    fn principal_axes<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        numpy::ndarray::arr2(&ascending(&self.inertia()).1).into_pyarray(py)
    }

    /// The angle of the axis of the larger principal moment (principal_axes[1]),
    /// counter-clockwise from x, in degrees.
    #[getter]
    fn principal_angle_degrees(&self) -> f64 {
        self.inertia().principal_angle_degrees
    }

    fn __repr__(&self) -> String {
        let r = &self.report;
        let centroid = match r.centroid {
            Some([x, y]) => format!("({x:?}, {y:?})"),
            None => "None".to_string(),
        };
        format!(
            "AreaProperties(area={:?}, perimeter={:?}, centroid={centroid})",
            r.area, r.perimeter
        )
    }
}

/// The principal moments ascending and their axes (rows), from the report's (larger
/// first, about the axis at principal_angle_degrees).
pub fn ascending(i: &InertiaReport) -> ([f64; 2], [[f64; 2]; 2]) {
    let (sin, cos) = i.principal_angle_degrees.to_radians().sin_cos();
    let [larger, smaller] = i.principal;
    ([smaller, larger], [[sin, -cos], [cos, sin]])
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
///
/// units as the command's --units ('m:ft': areas in ft²); density as its --density: a
/// mass per area ('62.8kg/m2' with units naming the file's length unit, or a number per
/// reported area unit), giving `mass`, that of a sheet with this outline. timings=True
/// adds `timings`: one stage, `measuring`.
#[pyfunction]
#[pyo3(signature = (exterior, holes = None, units = None, density = None, timings = false))]
pub fn polygon_area(
    py: Python<'_>,
    exterior: &Bound<'_, PyAny>,
    holes: Option<&Bound<'_, PyAny>>,
    units: Option<&str>,
    density: Option<&Bound<'_, PyAny>>,
    timings: bool,
) -> PyResult<PyAreaProperties> {
    let options = crate::units::area_options(units, density)?;
    let clock = timings.then(crate::timings::Clock::new);
    crate::timings::stage(clock.as_ref(), "measuring");
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
    let features = [PolygonFeature { name: None, polygons }];
    let (report, issues) = py.detach(|| {
        let issues: Vec<String> =
            polygon_issues(&features[0].polygons).iter().map(ToString::to_string).collect();
        (area(None, None, &features, Vec::new()), issues)
    });
    let report = report.map_err(mesh_error)?.in_units(&options, None).map_err(mesh_error)?;
    let fields = Fields::new(&report)?.with_timings(clock.map(|c| c.finish()))?;
    Ok(PyAreaProperties { fields, report, issues })
}

crate::dict::report_methods!(PyAreaProperties, "AreaProperties");
