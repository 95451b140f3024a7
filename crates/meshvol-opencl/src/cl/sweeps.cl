// The column–clamp kernel's sweeps: crates/meshvol/src/grid/cells.rs (`sweep_layers`,
// `sweep_axis`, `for_each_piece`), operation for operation, so that every column gets
// the CPU's pieces, in the CPU's order. What a part adds to is the kernel's: each
// kernel's file (after this one) completes `struct Sink` and defines `sink_slab` (the
// part of a piece in a layer) and `sink_above` (the part above the grid's top), as the
// CPU's `LayerSink` does.

typedef struct Sink Sink;
static void sink_slab(const Sink *s, ulong column, ulong layer, const Poly *part);
static void sink_above(const Sink *s, ulong column, const Poly *part);

// The tile kernels' integer arguments after their buffers, in the order the host's
// `run::scalars` gives them: tiles, columns per tile, columns; the grid's counts; the
// block's first x and y cell, its width; its depth, its first layer, the area sums a
// column.
#define TILE_SCALARS \
    ulong tiles, ulong per_tile, ulong columns, \
    ulong nx, ulong ny, ulong nz, \
    ulong x0, ulong y0, ulong width, \
    ulong depth, ulong first, ulong areas

// sweep_layers: the piece cut at the layer planes, each part to the sink.
static void sweep_layers(const Poly *piece, double z0, double z1, ulong nz, const Sink *s, ulong column) {
    if (z1 < 0.0 || (z1 == 0.0 && z0 < 0.0)) {
        return;
    }
    double top = (double)nz;
    if (z0 >= top) {
        sink_above(s, column, piece);
        return;
    }
    double lo = max_rs(floor_rs(z0), 0.0);
    if (z0 >= lo && z1 <= lo + 1.0) {
        sink_slab(s, column, (ulong)lo, piece);
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
            sink_slab(s, column, k, rest);
            return;
        }
        split_axis(rest, 2, next, part, spare);
        Poly *swap = rest;
        rest = spare;
        spare = swap;
        sink_slab(s, column, k, part);
        if (k + 1 == nz) {
            sink_above(s, column, rest);
            return;
        }
        k += 1;
    }
}

// The tile's columns as the CPU's `for_each_piece` sees them.
typedef struct {
    ulong ny, nz;
    ulong x0, y0, width;
    ulong first_row, last_row;
    ulong col_start, col_end;
} Columns;

// Columns col_start..col_end of a tile, counted from (x0, y0) in layers `width` wide.
static Columns columns_of(ulong ny, ulong nz, ulong x0, ulong y0, ulong width, ulong col_start,
                          ulong col_end) {
    Columns c;
    c.ny = ny;
    c.nz = nz;
    c.x0 = x0;
    c.y0 = y0;
    c.width = width;
    c.first_row = x0 + col_start / width;
    c.last_row = x0 + (col_end - 1) / width;
    c.col_start = col_start;
    c.col_end = col_end;
    return c;
}

// Zeroes a work item's own n values.
static void zero(__global double *values, ulong n) {
    for (ulong e = 0; e < n; e++) {
        values[e] = 0.0;
    }
}

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
            sweep_layers(strip, z0, z1, c->nz, s, row + start - c->y0 - c->col_start);
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
            sweep_layers(piece, z0, z1, c->nz, s, row + j - c->y0 - c->col_start);
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

// sweep_triangle of a tile's triangle, its corners the nine coordinates at v (as the
// host lays them out).
static void sweep_corners(__global const double *v, ulong nx, const Columns *c, const Sink *s) {
    Poly t;
    t.len = 0;
    push(&t, v[0], v[1], v[2]);
    push(&t, v[3], v[4], v[5]);
    push(&t, v[6], v[7], v[8]);
    sweep_triangle(&t, nx, c, s);
}
