// The cell volumes: crates/meshvol/src/grid/cells.rs (`ColumnSink`, `add_faces`,
// `finish_column`) for one tile of columns a work item, so that every cell gets the
// CPU's terms in the CPU's order and the same bits. The triangles arrive in grid units,
// those without projected area dropped, binned by tile in face order (tile_work.rs).

// What a tile adds into: its cells (`depth` a column) and area accumulators (`areas`
// a column), the block's first layer `first`.
struct Sink {
    __global double *cells;
    __global double *area;
    ulong depth;
    ulong areas;
    ulong first;
};

// ColumnSink::slab.
static void sink_slab(const Sink *s, ulong column, ulong layer, const Poly *part) {
    if (layer < s->first) {
        return;
    }
    ulong at = layer - s->first;
    __global double *area = s->area + column * s->areas;
    if (at < s->depth) {
        double a, m;
        area_and_moment(part, (double)layer, &a, &m);
        s->cells[column * s->depth + at] += m;
        area[at] += a;
    } else {
        area[at] += area_of(part);
    }
}

// ColumnSink::above.
static void sink_above(const Sink *s, ulong column, const Poly *part) {
    s->area[column * s->areas + s->areas - 1] += area_of(part);
}

// One work item a tile: zero its cells and areas, add its triangles' pieces in the
// order listed, then the compensated suffix sum down each column (`finish_column`).
__kernel void tile_volumes(
    __global const double *triangles,
    __global const ulong *offsets,
    __global const uint *entries,
    __global double *cells,
    __global double *areas_buf,
    TILE_SCALARS,
    double scale)
{
    ulong tile = get_global_id(0);
    if (tile >= tiles) {
        return;
    }
    ulong col_start = tile * per_tile;
    ulong col_end = min(col_start + per_tile, columns);
    Sink s;
    s.cells = cells + col_start * depth;
    s.area = areas_buf + col_start * areas;
    s.depth = depth;
    s.areas = areas;
    s.first = first;
    ulong n = col_end - col_start;
    zero(s.cells, n * depth);
    zero(s.area, n * areas);
    Columns c = columns_of(ny, nz, x0, y0, width, col_start, col_end);
    for (ulong e = offsets[tile]; e < offsets[tile + 1]; e++) {
        __global const double *v = triangles + 9 * (ulong)entries[e];
        sweep_corners(v, nx, &c, &s);
    }
    for (ulong col = 0; col < n; col++) {
        __global double *cell = s.cells + col * depth;
        __global const double *area = s.area + col * areas;
        double sum = 0.0, compensation = 0.0;
        for (ulong k = areas - 1; k-- > 0;) {
            // two_sum(sum, area[k + 1]) (accumulate.rs).
            double a = sum, b = area[k + 1];
            double t = a + b;
            double z = t - a;
            double err = (a - (t - z)) + (b - z);
            sum = t;
            compensation += err;
            if (k < depth) {
                cell[k] = (cell[k] + (sum + compensation)) * scale;
            }
        }
    }
}
