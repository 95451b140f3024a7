//! Small 3-vector helpers over plain arrays, which keep hot loops free of wrapper types.

use crate::Point;

#[inline(always)]
pub fn add(a: Point, b: Point) -> Point {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub fn sub(a: Point, b: Point) -> Point {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub fn scale(a: Point, s: f64) -> Point {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline(always)]
pub fn dot(a: Point, b: Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub fn cross(a: Point, b: Point) -> Point {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

#[inline(always)]
pub fn norm(a: Point) -> f64 {
    dot(a, a).sqrt()
}

/// The exact sign-bearing orientation of c against the line a→b in the plane: positive
/// when a, b, c turn counter-clockwise (Shewchuk's adaptive test, `robust` crate).
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let coord = |p: [f64; 2]| robust::Coord { x: p[0], y: p[1] };
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// The exact orientation of d against the plane through a, b, c: positive when d lies
/// below it, seen with a, b, c counter-clockwise (Shewchuk's adaptive test).
pub fn orient3d(a: Point, b: Point, c: Point, d: Point) -> f64 {
    let coord = |p: Point| robust::Coord3D { x: p[0], y: p[1], z: p[2] };
    robust::orient3d(coord(a), coord(b), coord(c), coord(d))
}

/// −1, 0 or +1. (Not `f64::signum`, which gives ±1 for ±0: the exact zeros that
/// predicates return are what tells touching from crossing.)
pub fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}
