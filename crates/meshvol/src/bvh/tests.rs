use super::*;

/// The tree as a breadth-first queue builds it, one node at a time: the reference
/// for the level-by-level build. (begin, end, start, count) per node and the
/// leaves' node numbers in order.
fn queue_built(items: usize) -> (Vec<[u32; 4]>, Vec<usize>) {
    let (mut nodes, mut leaves, mut next) = (vec![[0, items as u32, 0, 0]], Vec::new(), 0);
    while next < nodes.len() {
        let [begin, end, ..] = nodes[next].map(|x| x as usize);
        if end - begin <= LEAF_SIZE {
            nodes[next][2] = leaves.len() as u32;
            nodes[next][3] = (end - begin) as u32;
            leaves.push(next);
        } else {
            let mid = begin + (end - begin).div_ceil(LEAF_SIZE).div_ceil(2) * LEAF_SIZE;
            nodes[next][2] = nodes.len() as u32;
            nodes.push([begin as u32, mid as u32, 0, 0]);
            nodes.push([mid as u32, end as u32, 0, 0]);
        }
        next += 1;
    }
    (nodes, leaves)
}

#[test]
fn the_level_by_level_build_numbers_nodes_as_a_queue_and_bounds_hold_their_items() {
    let item = |i: usize| {
        let c = [(i * 37 % 101) as f64, (i * 11 % 53) as f64 * 0.5, (i % 7) as f64];
        Bounds { min: c, max: [c[0] + 1.5, c[1] + 0.25, c[2] + (i % 3) as f64] }
    };
    for items in [1, 15, 16, 17, 33, 1000, 70_001] {
        let (queue, leaves) = queue_built(items);
        for threads in [1, 2, 5] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let bvh = pool.install(|| Bvh::new(items, |i| Box32::around(&item(i))));
            let got: Vec<[u32; 4]> =
                bvh.nodes.iter().map(|n| [n.begin, n.end, n.start, n.count]).collect();
            assert_eq!(got, queue, "{items} items, {threads} threads");
            assert_eq!(bvh.leaves.len(), leaves.len());
            let boxes = pool.install(|| bvh.refit(item));
            for (n, node) in bvh.nodes.iter().enumerate() {
                let mut union = Bounds::EMPTY;
                (node.begin as usize..node.end as usize).for_each(|i| union.merge(&item(i)));
                assert_eq!(boxes[n], union, "{items} items: node {n}'s refitted box");
                assert_eq!(node.bounds, Box32::around(&union), "{items} items: node {n}");
            }
        }
    }
}

#[test]
fn morton_interleaves_bits() {
    assert_eq!(morton(1, 0, 0), 1);
    assert_eq!(morton(0, 1, 0), 2);
    assert_eq!(morton(0, 0, 1), 4);
    assert_eq!(morton(3, 0, 0), 0b1001);
    assert_eq!(morton(0x1f_ffff, 0x1f_ffff, 0x1f_ffff), (1u64 << 63) - 1);
}

#[test]
fn f32_boxes_contain_their_f64_boxes_tightly() {
    let mut rng = crate::test_rng::XorShift::new(0x853c49e6748fea9bu64);
    let mut values = vec![0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300, 0.1, -0.1, 16777217.0];
    for _ in 0..100_000 {
        let x = f64::from_bits(rng.next_u64());
        if x.is_finite() {
            values.push(x);
        }
    }
    for x in values {
        let (down, up) = (f32_down(x), f32_up(x));
        assert!(f64::from(down) <= x && x <= f64::from(up), "{x}");
        // Tight: x's nearest f32 is one of the two, and they are x when x is an f32.
        let nearest = x as f32;
        assert!(nearest == down || nearest == up, "{x}");
        if f64::from(nearest) == x {
            assert!(down == nearest && up == nearest, "{x}");
        }
    }
}

#[test]
fn spatial_order_is_the_order_of_the_morton_codes() {
    // Clustered points (many share top bits, some share whole codes).
    let mut rng = crate::test_rng::XorShift::new(0x2545f4914f6cdd1du64);
    let mut next = || rng.unit();
    let points: Vec<Point> = (0..60_000)
        .map(|i| {
            let spread = if i % 3 == 0 { 1e-7 } else { 1.0 };
            [next() * spread, next() * spread, (next() * 8.0).floor()]
        })
        .collect();
    let codes = morton_codes(points.len(), |i| points[i]);
    let mut expected: Vec<u32> = (0..points.len() as u32).collect();
    expected.sort_by_key(|&i| (codes[i as usize], i));
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
        assert_eq!(pool.install(|| Bvh::spatial_order(&points)), expected);
    }
}

/// Exact overlap of f64 boxes, for the brute-force answers.
fn overlap(a: &Bounds, b: &Bounds) -> bool {
    (0..3).all(|k| a.min[k] <= b.max[k] && b.min[k] <= a.max[k])
}

#[test]
fn random_boxes_of_every_size_give_the_brute_force_pairs_and_queries() {
    // Points, slivers and boxes spanning most of the space, at f32 values (so the
    // f32 boxes are the boxes), in an item count that leaves partial leaves.
    let mut rng = crate::test_rng::XorShift::new(0x9e3779b97f4a7c15u64);
    let mut next = || rng.unit() as f32 as f64;
    let boxes: Vec<Bounds> = (0..3001)
        .map(|i| {
            let size = match i % 4 {
                0 => 0.0,
                1 => 0.01,
                2 => 0.05,
                _ => 0.5,
            };
            let min = [next(), next(), next()];
            let max = [0, 1, 2].map(|k| (min[k] + size * next()) as f32 as f64);
            Bounds { min, max }
        })
        .collect();
    let bvh = Bvh::new(boxes.len(), |i| Box32::around(&boxes[i]));
    let pairs = bvh.overlapping_pairs(None, |a| a, |&a, b| Some((a.min(b), a.max(b))));
    let brute: Vec<(usize, usize)> = (0..boxes.len())
        .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
        .filter(|&(a, b)| overlap(&boxes[a], &boxes[b]))
        .collect();
    assert!(brute.len() > 10_000);
    assert!(pairs == brute, "{} pairs found, {} overlap", pairs.len(), brute.len());
    // Tagged (runs of 100 items sharing a tag, as the triangles around a vertex of
    // high degree do, and tags shared across runs), the pairs that share no tag are
    // exactly those that share none; NO_TAG in a slot matches nothing.
    let tags: Vec<[u32; 3]> =
        (0..boxes.len() as u32).map(|i| [i / 100, 1000 + i % 3, NO_TAG]).collect();
    let apart =
        |&(a, b): &(usize, usize)| !tags[a].iter().any(|t| *t != NO_TAG && tags[b].contains(t));
    let tagged = bvh.overlapping_pairs(Some(&tags), |a| a, |&a, b| Some((a.min(b), a.max(b))));
    let kept: Vec<(usize, usize)> = brute.iter().copied().filter(apart).collect();
    assert!(kept.len() > 1000 && kept.len() < brute.len(), "{}", kept.len());
    assert_eq!(tagged, kept);
    // The first pair found with tags shares none; with one tag for all, none is found.
    let first = bvh.first_overlapping_pair(Some(&tags), |_, _| true).unwrap();
    let first = (first.0.min(first.1), first.0.max(first.1));
    assert!(kept.contains(&first), "{first:?}");
    let one_tag = vec![[NO_TAG, 7, NO_TAG]; boxes.len()];
    assert_eq!(bvh.first_overlapping_pair(Some(&one_tag), |_, _| true), None);
    let no_tags = vec![[NO_TAG; 3]; boxes.len()];
    assert_eq!(
        bvh.overlapping_pairs(Some(&no_tags), |a| a, |&a, b| Some((a.min(b), a.max(b)))),
        brute
    );
    // Queries, some reaching infinity (as rays' boxes do).
    let (inf, x) = (f64::INFINITY, 0.5);
    for q in [
        Bounds { min: [x, x, x], max: [inf, x, x] },
        Bounds { min: [-inf, x, 0.25], max: [x, x, 0.75] },
        Bounds { min: [-inf; 3], max: [inf; 3] },
        Bounds { min: [0.1, 0.2, 0.3], max: [0.4, 0.45, 0.5] },
    ] {
        let mut found = vec![];
        bvh.overlapping(&q, |i| found.push(i));
        found.sort();
        let brute: Vec<usize> = (0..boxes.len()).filter(|&i| overlap(&boxes[i], &q)).collect();
        assert_eq!(found, brute);
    }
}

#[test]
fn leaf_pairs_of_two_trees_hold_every_overlapping_pair_of_items() {
    // Two sets of random boxes, the second moved by a shift applied to its node
    // boxes (as a pose is): every pair of items whose boxes overlap, once moved,
    // lies in exactly one leaf pair found.
    let mut rng = crate::test_rng::XorShift::new(17);
    let mut make = |count: usize, size: f64| -> Vec<Bounds> {
        (0..count)
            .map(|_| {
                let min = [0; 3].map(|_| rng.unit() as f32 as f64);
                let max = min.map(|x| (x + size * rng.unit()) as f32 as f64);
                Bounds { min, max }
            })
            .collect()
    };
    let (first, second) = (make(1500, 0.1), make(999, 0.2));
    let shift = 0.25;
    let moved =
        |b: &Bounds| Bounds { min: b.min.map(|x| x + shift), max: b.max.map(|x| x + shift) };
    let tree = |boxes: &[Bounds]| Bvh::new(boxes.len(), |i| Box32::around(&boxes[i]));
    let (p, q) = (tree(&first), tree(&second));
    let leaves = p.leaf_pairs_between(&q, &p.refit(|i| first[i]), &q.refit(|i| moved(&second[i])));
    let mut found: Vec<(usize, usize)> = leaves
        .iter()
        .flat_map(|&(m, n)| {
            let items_b = q.items(n);
            p.items(m).flat_map(move |i| items_b.clone().map(move |j| (i, j)))
        })
        .filter(|&(i, j)| overlap(&first[i], &moved(&second[j])))
        .collect();
    let count = found.len();
    found.sort_unstable();
    found.dedup();
    assert_eq!(found.len(), count, "a pair of leaves found twice");
    let brute: Vec<(usize, usize)> = (0..first.len())
        .flat_map(|i| (0..second.len()).map(move |j| (i, j)))
        .filter(|&(i, j)| overlap(&first[i], &moved(&second[j])))
        .collect();
    assert!(brute.len() > 1000, "{}", brute.len());
    assert_eq!(found, brute);
}

#[test]
fn finds_exactly_the_overlapping_boxes() {
    // A 20×20 lattice of unit boxes with gaps (all values f32: the f32 boxes are
    // the boxes); compare with brute force.
    let boxes: Vec<Bounds> = (0..400)
        .map(|i| {
            let (x, y) = ((i % 20) as f64 * 1.5, (i / 20) as f64 * 1.5);
            Bounds { min: [x, y, 0.0], max: [x + 1.0, y + 1.0, 1.0] }
        })
        .collect();
    // In the given (row) order and in spatial order: the same answers.
    let centre = |b: &Bounds| [0, 1, 2].map(|k| 0.5 * (b.min[k] + b.max[k]));
    let centres: Vec<Point> = boxes.iter().map(centre).collect();
    let order = Bvh::spatial_order(&centres);
    assert_eq!(order.len(), boxes.len());
    let spatial: Vec<Bounds> = order.iter().map(|&i| boxes[i as usize]).collect();
    let tree = |boxes: &[Bounds]| Bvh::new(boxes.len(), |i| Box32::around(&boxes[i]));
    let (bvh, spatial_bvh) = (tree(&boxes), tree(&spatial));
    for q in [
        Bounds { min: [0.5, 0.5, 0.5], max: [3.2, 2.0, 0.6] },
        Bounds { min: [-5.0; 3], max: [-4.0; 3] },
        Bounds { min: [1.0, 1.0, 1.0], max: [1.5, 1.5, 2.0] }, // touches a corner
    ] {
        let mut found = vec![];
        bvh.overlapping(&q, |i| found.push(i));
        found.sort();
        let brute: Vec<usize> = (0..boxes.len()).filter(|&i| overlap(&boxes[i], &q)).collect();
        assert_eq!(found, brute);
        let mut found: Vec<usize> = vec![];
        spatial_bvh.overlapping(&q, |i| found.push(order[i] as usize));
        found.sort();
        assert_eq!(found, brute);
    }
    let mut none = 0;
    Bvh::new(0, |_| Box32::EMPTY).overlapping(&boxes[0], |_| none += 1);
    assert_eq!(none, 0);
    // Every overlapping pair exactly once.
    let pairs = bvh.overlapping_pairs(None, |a| a, |&a, b| Some((a.min(b), a.max(b))));
    let brute: Vec<(usize, usize)> = (0..boxes.len())
        .flat_map(|a| (a + 1..boxes.len()).map(move |b| (a, b)))
        .filter(|&(a, b)| overlap(&boxes[a], &boxes[b]))
        .collect();
    assert_eq!(pairs, brute);
    let mut pairs = spatial_bvh.overlapping_pairs(
        None,
        |a| a,
        |&a, b| {
            let (a, b) = (order[a] as usize, order[b] as usize);
            Some((a.min(b), a.max(b)))
        },
    );
    pairs.sort();
    assert_eq!(pairs, brute);
}
