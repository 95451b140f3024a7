//! A body prepared from the check's weld against one welded from scratch, and the
//! parallel edge table and vertex graph against a plain map of edges: independent
//! computations that must agree bit for bit, at any thread count.

use super::edges::{edge_table, vertex_graph};
use super::Body;
use crate::shapes::{cuboid, uv_sphere};
use crate::test_rng::XorShift;
use crate::topology::{check, CheckOptions, Weld};
use crate::{Mesh, Point};
use std::collections::BTreeMap;
use std::sync::Arc;

/// Runs `f` on a pool of `threads` threads.
fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap().install(f)
}

/// Every field of a body, its floats as written by `{:?}` (which tells −0 from +0).
fn bits(body: &Body) -> String {
    format!("{body:?}")
}

/// Each triangle with corners of its own (a soup, as STL stores it).
fn soup(mesh: &Mesh) -> Mesh {
    let t = mesh.triangulated();
    let crate::Faces::Triangles(triangles) = t.faces() else { unreachable!() };
    let positions: Vec<Point> =
        triangles.iter().flat_map(|f| f.map(|i| t.positions()[i as usize])).collect();
    let ids = (0..triangles.len() as u32).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect();
    Mesh::from_triangles(positions, ids).unwrap()
}

/// Meshes whose checked solid is exactly welded triangles (the check's weld is taken:
/// `true`) and, last, some whose is not (the body is welded from scratch), with the
/// weld to check them with.
fn cases() -> Vec<(&'static str, Mesh, Weld, bool)> {
    let sphere = uv_sphere(1.0, 24, 12).triangulated();
    // A soup with some zeros written as −0: one point to the weld either way.
    let mut signed = soup(&cuboid([-1.0, 0.0, -1.0], [1.0, 2.0, 0.0]));
    let mut rng = XorShift::new(7);
    let positions: Vec<Point> = signed
        .positions()
        .iter()
        .map(|p| p.map(|x| if x == 0.0 && rng.below(2) == 0 { -0.0 } else { x }))
        .collect();
    let crate::Faces::Triangles(t) = signed.faces() else { unreachable!() };
    signed = Mesh::from_triangles(positions, t.clone()).unwrap();
    // Every other triangle turned: the check reverses them back.
    let crate::Faces::Triangles(t) = sphere.faces() else { unreachable!() };
    let mut turned = t.clone();
    turned.iter_mut().step_by(2).for_each(|f| f.swap(1, 2));
    let mixed = Mesh::from_triangles(sphere.positions().to_vec(), turned).unwrap();
    // A copy of a face (dropped by the check), and a second shell inside: a cavity,
    // turned inward, its vertices numbered after the first's.
    let mut doubled = t.clone();
    doubled.insert(5, t[40]);
    let with_copy = Mesh::from_triangles(sphere.positions().to_vec(), doubled).unwrap();
    let inner = uv_sphere(0.5, 16, 8).triangulated();
    let hollow = Mesh::concatenate(&[inner, sphere.clone()]);
    let crate::Faces::Triangles(t) = sphere.faces() else { unreachable!() };
    let open = Mesh::from_triangles(sphere.positions().to_vec(), t[1..].to_vec()).unwrap();
    vec![
        ("sphere", sphere.clone(), Weld::Auto, true),
        ("soup with -0", signed, Weld::Auto, true),
        ("mixed winding", mixed, Weld::Auto, true),
        ("a copy of a face", with_copy, Weld::Auto, true),
        ("hollow", hollow, Weld::Auto, true),
        ("sphere soup", soup(&sphere), Weld::Auto, true),
        // Quads; a hole (a cap); welded within a tolerance.
        ("quads", uv_sphere(1.0, 24, 12), Weld::Auto, false),
        ("open", open, Weld::Auto, false),
        ("tolerance", sphere, Weld::Tolerance(1e-12), false),
    ]
}

#[test]
fn a_body_from_the_check_is_the_body_welded_from_its_solid_bit_for_bit() {
    for (name, mesh, weld, taken) in cases() {
        // With the check's spatial index kept, a body takes it where it holds every
        // triangle of the solid (not where a face was dropped); its order and
        // hierarchy must be those the body builds from scratch.
        for keep_spatial_index in [false, true] {
            let options = CheckOptions { weld, keep_spatial_index, ..CheckOptions::default() };
            let checked = check(&mesh, &options).unwrap();
            assert_eq!(checked.solid_triangles().is_some(), taken, "{name}");
            let index = checked.spatial_index();
            assert_eq!(index.is_some(), keep_spatial_index && weld != Weld::Tolerance(1e-12));
            let scratch = bits(&Body::new(&checked.solid(&mesh)));
            for threads in [1, 2, 5] {
                let from_check = on_threads(threads, || Body::of_solid(&checked, &mesh));
                let shared = index.is_some_and(|i| Arc::ptr_eq(&i.bvh, &from_check.bvh));
                let takes = taken && keep_spatial_index && checked.repairs().1 == 0;
                assert_eq!(shared, takes, "{name}: the check's hierarchy taken");
                assert_eq!(bits(&from_check), scratch, "{name}, {threads} threads, {options:?}");
            }
            let again = on_threads(1, || Body::new(&checked.solid(&mesh)));
            assert_eq!(bits(&again), scratch, "{name}");
        }
    }
}

/// The edge table and vertex graph by a map from (lower, upper) ends to uses, in
/// corner order: (edges, face edges, owners, closed, each vertex's (neighbour, edge)).
#[allow(clippy::type_complexity)]
fn by_map(
    triangles: &[[u32; 3]],
    flat: &[bool],
    vertices: usize,
) -> (Vec<[u32; 2]>, Vec<[u32; 3]>, Vec<u32>, bool, Vec<Vec<(u32, u32)>>) {
    let mut uses: BTreeMap<(u32, u32), Vec<(usize, usize)>> = BTreeMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        for i in 0..3 {
            let (u, v) = (tri[i], tri[(i + 1) % 3]);
            uses.entry((u.min(v), u.max(v))).or_default().push((t, i));
        }
    }
    let mut face_edges = vec![[0u32; 3]; triangles.len()];
    let (mut edges, mut owner, mut closed) = (Vec::new(), Vec::new(), true);
    let mut graph = vec![Vec::new(); vertices];
    for (id, (&(low, high), corners)) in uses.iter().enumerate() {
        edges.push([low, high]);
        let forward = corners.iter().filter(|&&(t, i)| triangles[t][i] == low).count();
        closed &= 2 * forward == corners.len();
        let first = corners.iter().find(|&&(t, _)| !flat[t]).unwrap_or(&corners[0]);
        owner.push(first.0 as u32);
        corners.iter().for_each(|&(t, i)| face_edges[t][i] = id as u32);
        graph[low as usize].push((high, id as u32));
        graph[high as usize].push((low, id as u32));
    }
    graph.iter_mut().for_each(|list| list.sort_by_key(|&(_, id)| id));
    (edges, face_edges, owner, closed, graph)
}

#[test]
fn the_edge_table_and_vertex_graph_are_those_of_a_map_of_edges_at_any_thread_count() {
    let sphere = uv_sphere(1.0, 200, 100).triangulated();
    let crate::Faces::Triangles(t) = sphere.faces() else { unreachable!() };
    let vertices = sphere.positions().len();
    let mut rng = XorShift::new(11);
    // Shuffled, so that corners of an edge lie far apart; then with one triangle gone
    // and one turned (not closed), with some triangles taken as flat.
    let mut shuffled = t.clone();
    for k in (1..shuffled.len()).rev() {
        shuffled.swap(k, rng.below(k as u64 + 1) as usize);
    }
    let mut open = shuffled.clone();
    open.pop();
    open[10].swap(0, 1);
    for (name, triangles) in [("closed", &shuffled), ("open", &open)] {
        let flat: Vec<bool> = (0..triangles.len()).map(|_| rng.below(5) == 0).collect();
        let (edges, face_edges, owner, closed, graph) = by_map(triangles, &flat, vertices);
        assert_eq!(closed, name == "closed");
        for threads in [1, 2, 5] {
            let (table, (start, adjacent)) = on_threads(threads, || {
                let table = edge_table(triangles, &flat, vertices);
                let g = vertex_graph(&table.edges, &table.first_edge);
                (table, g)
            });
            let at = format!("{name}, {threads} threads");
            assert_eq!(table.edges, edges, "{at}");
            assert_eq!(table.face_edges, face_edges, "{at}");
            assert_eq!(table.owner, owner, "{at}");
            assert_eq!(table.closed, closed, "{at}");
            for (v, list) in graph.iter().enumerate() {
                let range = start[v] as usize..start[v + 1] as usize;
                assert_eq!(&adjacent[range], &list[..], "{at}: vertex {v}");
            }
        }
    }
}
