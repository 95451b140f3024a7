// The column–clamp kernel's sweeps and sums for one tile of columns a work item:
// crates/meshvol/src/grid/cells.rs (`add_faces`, `for_each_piece`, `sweep_axis`,
// `sweep_layers`, `ColumnSink`, `finish_column`) and clip.rs (`Polygon`), operation for
// operation, so that every cell gets the CPU's terms in the CPU's order and the same
// bits. No contraction: Rust never fuses a multiply and an add, and the CPU code uses
// no `mul_add`, so neither does this file. The triangles arrive in grid units, those
// without projected area dropped, binned by tile in face order (tile_work.rs).
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

// Polygon<9>: a triangle cut by at most six planes.
#define MAXV 9

typedef struct {
    int len;
    double v[MAXV][3];
} Poly;

// Polygon::push: a full polygon ignores the vertex.
static void push(Poly *p, double x, double y, double z) {
    if (p->len < MAXV) {
        p->v[p->len][0] = x;
        p->v[p->len][1] = y;
        p->v[p->len][2] = z;
        p->len += 1;
    }
}

// Polygon::range: explicit comparisons, as the Rust has them.
static void range(const Poly *p, int axis, double *lo, double *hi) {
    double l = INFINITY, h = -INFINITY;
    for (int k = 0; k < p->len; k++) {
        double c = p->v[k][axis];
        l = c < l ? c : l;
        h = c > h ? c : h;
    }
    *lo = l;
    *hi = h;
}

// Polygon::split_axis_into: `below` where v[axis] <= c, `above` where >= c; a new
// vertex from the end on the negative side, its coordinate on `axis` set to c.
static void split_axis(const Poly *p, int axis, double c, Poly *below, Poly *above) {
    below->len = 0;
    above->len = 0;
    int n = p->len;
    if (n == 0) {
        return;
    }
    int ui = n - 1;
    double du = p->v[ui][axis] - c;
    for (int k = 0; k < n; k++) {
        double dv = p->v[k][axis] - c;
        if ((du < 0.0 && dv > 0.0) || (du > 0.0 && dv < 0.0)) {
            int pi = du < 0.0 ? ui : k;
            int qi = du < 0.0 ? k : ui;
            double dp = du < 0.0 ? du : dv;
            double dq = du < 0.0 ? dv : du;
            double t = dp / (dp - dq);
            double x[3];
            for (int a = 0; a < 3; a++) {
                x[a] = p->v[pi][a] + t * (p->v[qi][a] - p->v[pi][a]);
            }
            x[axis] = c;
            push(below, x[0], x[1], x[2]);
            push(above, x[0], x[1], x[2]);
        }
        if (dv <= 0.0) {
            push(below, p->v[k][0], p->v[k][1], p->v[k][2]);
        }
        if (dv >= 0.0) {
            push(above, p->v[k][0], p->v[k][1], p->v[k][2]);
        }
        ui = k;
        du = dv;
    }
}

// Polygon::area_and_moment: the fan from vertex 0.
static void area_and_moment(const Poly *p, double t, double *area, double *moment) {
    if (p->len < 3) {
        *area = 0.0;
        *moment = 0.0;
        return;
    }
    double ox = p->v[0][0], oy = p->v[0][1];
    double zo = p->v[0][2] - t;
    double double_area = 0.0, six_moment = 0.0;
    for (int k = 1; k < p->len - 1; k++) {
        double cross = (p->v[k][0] - ox) * (p->v[k + 1][1] - oy)
                     - (p->v[k][1] - oy) * (p->v[k + 1][0] - ox);
        double_area += cross;
        six_moment += cross * (zo + (p->v[k][2] - t) + (p->v[k + 1][2] - t));
    }
    *area = 0.5 * double_area;
    *moment = six_moment / 6.0;
}

static double area_of(const Poly *p) {
    double a, m;
    area_and_moment(p, 0.0, &a, &m);
    return a;
}

// cells.rs `floor`: `x as i64 as f64`, whose cast saturates (NaN gives 0), then a
// step down where it truncated upward. A C cast out of range is undefined: saturate
// first, as Rust does.
static double floor_rs(double x) {
    double t;
    if (isnan(x)) {
        t = 0.0;
    } else if (x >= 0x1p63) {
        t = 0x1p63;
    } else if (x < -0x1p63) {
        t = -0x1p63;
    } else {
        t = (double)(long)x;
    }
    return t > x ? t - 1.0 : t;
}

static double ceil_rs(double x) {
    return -floor_rs(-x);
}

// f64::max and f64::min: the other operand where one is NaN.
static double max_rs(double a, double b) {
    return isnan(a) ? b : (isnan(b) ? a : (a > b ? a : b));
}

static double min_rs(double a, double b) {
    return isnan(a) ? b : (isnan(b) ? a : (a < b ? a : b));
}

// cells.rs `cover` with closed = false: the cells [start, end) along an axis of n
// cells that [lo, hi] overlaps with positive length.
static void cover(double lo, double hi, ulong n, ulong *start, ulong *end) {
    double limit = (double)n + 2.0;
    lo = min_rs(max_rs(lo, -2.0), limit);
    hi = min_rs(max_rs(hi, -2.0), limit);
    double s = floor_rs(lo);
    double e = max_rs(ceil_rs(hi), s + 1.0);
    *start = (ulong)min_rs(max_rs(s, 0.0), (double)n);
    *end = (ulong)min_rs(max_rs(e, 0.0), (double)n);
}

// What a tile adds into: its cells (`depth` a column) and area accumulators (`areas`
// a column), the block's first layer `first`.
typedef struct {
    __global double *cells;
    __global double *area;
    ulong depth;
    ulong areas;
    ulong first;
    ulong nz;
} Sink;

// ColumnSink::slab.
static void slab(const Sink *s, ulong column, ulong layer, const Poly *part) {
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
static void above(const Sink *s, ulong column, const Poly *part) {
    s->area[column * s->areas + s->areas - 1] += area_of(part);
}

// sweep_layers: the piece cut at the layer planes, each part to the sink.
static void sweep_layers(const Poly *piece, double z0, double z1, const Sink *s, ulong column) {
    if (z1 < 0.0 || (z1 == 0.0 && z0 < 0.0)) {
        return;
    }
    double top = (double)s->nz;
    if (z0 >= top) {
        above(s, column, piece);
        return;
    }
    double lo = max_rs(floor_rs(z0), 0.0);
    if (z0 >= lo && z1 <= lo + 1.0) {
        slab(s, column, (ulong)lo, piece);
        return;
    }
    Poly bufs[3];
    Poly *part = &bufs[0], *rest = &bufs[1], *spare = &bufs[2];
    if (z0 < lo) {
        split_axis(piece, 2, lo, part, rest);
    } else {
        *rest = *piece;
    }
    ulong k = (ulong)lo;
    for (;;) {
        double next = (double)(k + 1);
        if (z1 <= next) {
            slab(s, column, k, rest);
            return;
        }
        split_axis(rest, 2, next, part, spare);
        Poly *swap = rest;
        rest = spare;
        spare = swap;
        slab(s, column, k, part);
        if (k + 1 == s->nz) {
            above(s, column, rest);
            return;
        }
        k += 1;
    }
}

// The tile's columns as the CPU's `for_each_piece` sees them.
typedef struct {
    ulong ny;
    ulong x0, y0, width;
    ulong first_row, last_row;
    ulong col_start, col_end;
} Columns;

// The y sweep of one strip (row i): sweep_axis(strip, 1, ...) with `for_each_piece`'s
// column callback, each piece swept through the layers.
static void sweep_row(const Poly *strip, ulong i, const Columns *c, const Sink *s) {
    ulong j_lo = c->y0 + (i == c->first_row ? c->col_start % c->width : 0);
    ulong j_hi = c->y0 + (i == c->last_row ? (c->col_end - 1) % c->width + 1 : c->width);
    ulong row = (i - c->x0) * c->width;
    double lo, hi;
    range(strip, 1, &lo, &hi);
    ulong start, end;
    cover(lo, hi, c->ny, &start, &end);
    if (start >= end) {
        return;
    }
    double z0, z1;
    if (lo >= (double)start && hi <= (double)(start + 1)) {
        if (start >= j_lo && start < j_hi) {
            range(strip, 2, &z0, &z1);
            sweep_layers(strip, z0, z1, s, row + start - c->y0 - c->col_start);
        }
        return;
    }
    Poly bufs[3];
    Poly *part = &bufs[0], *rest = &bufs[1], *spare = &bufs[2];
    if (lo < (double)start) {
        split_axis(strip, 1, (double)start, part, rest);
    } else {
        *rest = *strip;
    }
    for (ulong j = start; j < end; j++) {
        const Poly *piece;
        int last = hi <= (double)(j + 1);
        if (last) {
            piece = rest;
        } else {
            split_axis(rest, 1, (double)(j + 1), part, spare);
            Poly *swap = rest;
            rest = spare;
            spare = swap;
            piece = part;
        }
        if (j >= j_hi) {
            return;
        }
        if (j >= j_lo) {
            range(piece, 2, &z0, &z1);
            sweep_layers(piece, z0, z1, s, row + j - c->y0 - c->col_start);
        }
        if (last) {
            return;
        }
    }
}

// The x sweep of one triangle: sweep_axis(triangle, 0, ...) with `for_each_piece`'s
// row callback.
static void sweep_triangle(const Poly *t, ulong nx, const Columns *c, const Sink *s) {
    double lo, hi;
    range(t, 0, &lo, &hi);
    ulong start, end;
    cover(lo, hi, nx, &start, &end);
    if (start >= end) {
        return;
    }
    if (lo >= (double)start && hi <= (double)(start + 1)) {
        if (start >= c->first_row && start <= c->last_row) {
            sweep_row(t, start, c, s);
        }
        return;
    }
    Poly bufs[3];
    Poly *part = &bufs[0], *rest = &bufs[1], *spare = &bufs[2];
    if (lo < (double)start) {
        split_axis(t, 0, (double)start, part, rest);
    } else {
        *rest = *t;
    }
    for (ulong i = start; i < end; i++) {
        const Poly *strip;
        int last = hi <= (double)(i + 1);
        if (last) {
            strip = rest;
        } else {
            split_axis(rest, 0, (double)(i + 1), part, spare);
            Poly *swap = rest;
            rest = spare;
            spare = swap;
            strip = part;
        }
        if (i > c->last_row) {
            return;
        }
        if (i >= c->first_row) {
            sweep_row(strip, i, c, s);
        }
        if (last) {
            return;
        }
    }
}

// One work item a tile: zero its cells and areas, add its triangles' pieces in the
// order listed, then the compensated suffix sum down each column (`finish_column`).
__kernel void tile_volumes(
    __global const double *triangles,
    __global const ulong *offsets,
    __global const uint *entries,
    __global double *cells,
    __global double *areas_buf,
    ulong tiles, ulong per_tile, ulong columns,
    ulong nx, ulong ny, ulong nz,
    ulong x0, ulong y0, ulong width,
    ulong depth, ulong first, ulong areas,
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
    s.nz = nz;
    ulong n = col_end - col_start;
    for (ulong e = 0; e < n * depth; e++) {
        s.cells[e] = 0.0;
    }
    for (ulong e = 0; e < n * areas; e++) {
        s.area[e] = 0.0;
    }
    Columns c;
    c.ny = ny;
    c.x0 = x0;
    c.y0 = y0;
    c.width = width;
    c.first_row = x0 + col_start / width;
    c.last_row = x0 + (col_end - 1) / width;
    c.col_start = col_start;
    c.col_end = col_end;
    for (ulong e = offsets[tile]; e < offsets[tile + 1]; e++) {
        __global const double *v = triangles + 9 * (ulong)entries[e];
        Poly t;
        t.len = 0;
        push(&t, v[0], v[1], v[2]);
        push(&t, v[3], v[4], v[5]);
        push(&t, v[6], v[7], v[8]);
        sweep_triangle(&t, nx, &c, &s);
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
