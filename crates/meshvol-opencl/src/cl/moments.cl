// The cut cells' per-column stage: crates/meshvol/src/grid/cut_cells/kernel.rs
// (`MomentSink`, `add_surface`, `finish_column`, without the extra sums) for one tile
// of columns a work item, so that every cell gets the CPU's terms in the CPU's order
// and the same bits. The triangles arrive in grid units, every one (walls too), binned
// by tile in face order, each with its face's normal where the face is a polygon
// (cut_cells/device.rs). What sums across columns (the x and y apertures, the surface
// centroids) is left to the CPU.

// What a tile adds into, per column: its cells' volume terms, first moments and
// surface sums (`depth` cells a column), the area and its x and y moments handed down
// (`areas` layers a column, three values each), and the area of parts lying on the
// grid's top face; and the triangle being swept: its face's normal, if any.
struct Sink {
    __global double *volume;
    __global double *centroid;
    __global double *area;
    __global double *vector;
    __global double *weighted;
    __global double *handed;
    __global double *on_top;
    ulong depth, areas, first;
    ulong x0, y0, width, col_start;
    double scale[3];
    double normal[3];
    int has_normal;
};

// The grid column (i, j) of the tile's column `column`.
static void column_of(const Sink *s, ulong column, double *i, double *j) {
    ulong c = s->col_start + column;
    *i = (double)(s->x0 + c / s->width);
    *j = (double)(s->y0 + c % s->width);
}

// `add_surface` through `MomentSink::surface`: a part's world area (signed along the
// face's normal for a polygon face, else its vector's length), area vector, and area ×
// local centroid, added to cell `n`.
static void surface(const Sink *s, ulong n, const Poly *part, double i, double j, double k) {
    double vector[3], centre[3];
    if (!surface_part(part, i, j, k, vector, centre)) {
        return;
    }
    double world[3] = {vector[0] * s->scale[0], vector[1] * s->scale[1], vector[2] * s->scale[2]};
    double size;
    if (s->has_normal) {
        size = world[0] * s->normal[0] + world[1] * s->normal[1] + world[2] * s->normal[2];
    } else {
        size = sqrt(world[0] * world[0] + world[1] * world[1] + world[2] * world[2]);
    }
    s->area[n] += size;
    for (int d = 0; d < 3; d++) {
        s->vector[3 * n + d] += world[d];
        s->weighted[3 * n + d] += size * centre[d];
    }
}

// MomentSink::slab.
static void sink_slab(const Sink *s, ulong column, ulong layer, const Poly *part) {
    if (layer < s->first) {
        return;
    }
    ulong at = layer - s->first;
    double i, j;
    column_of(s, column, &i, &j);
    __global double *h = s->handed + 3 * (column * s->areas + at);
    if (at >= s->depth) {
        double d[3];
        handed_down(part, i, j, d);
        for (int a = 0; a < 3; a++) {
            h[a] += d[a];
        }
        return;
    }
    Projected p = projected(part, i, j, (double)layer);
    h[0] += p.area;
    h[1] += p.area_x;
    h[2] += p.area_y;
    ulong n = column * s->depth + at;
    s->volume[n] += p.z;
    s->centroid[3 * n] += p.xz;
    s->centroid[3 * n + 1] += p.yz;
    s->centroid[3 * n + 2] += p.zz_half;
    surface(s, n, part, i, j, (double)layer);
}

// MomentSink::above: handed down from above the grid; a part lying on the grid's top
// face is also the top layer's surface (the grid's far faces are closed).
static void sink_above(const Sink *s, ulong column, const Poly *part) {
    ulong top = s->areas - 1;
    double i, j;
    column_of(s, column, &i, &j);
    double d[3];
    handed_down(part, i, j, d);
    __global double *h = s->handed + 3 * (column * s->areas + top);
    for (int a = 0; a < 3; a++) {
        h[a] += d[a];
    }
    double z0, z1;
    range(part, 2, &z0, &z1);
    ulong layer = s->first + top - 1;
    if (z0 == z1 && z0 == (double)(layer + 1) && top - 1 < s->depth) {
        s->on_top[column] += d[0];
        surface(s, column * s->depth + top - 1, part, i, j, (double)layer);
    }
}

// CompensatedSum::add (accumulate.rs): TwoSum, its error accumulated.
static void add(double sum[2], double x) {
    double t = sum[0] + x;
    double z = t - sum[0];
    double err = (sum[0] - (t - z)) + (x - z);
    sum[0] = t;
    sum[1] += err;
}

// `within` of a cell neither empty nor full: a ratio as a position in the cell, clamped
// as f64::clamp does (NaN kept).
static double within(double m, double v) {
    double r = m / v;
    if (r < 0.0) {
        r = 0.0;
    }
    if (r > 1.0) {
        r = 1.0;
    }
    return r;
}

// What the columns' finish needs of the grid: its origin and cell, dx·dy·dz, and the
// occupancy tolerance.
typedef struct {
    double origin[3];
    double cell[3];
    double volume;
    double tolerance;
} Frame;

// kernel.rs `finish_column` without the extra sums: the handed-down terms summed from
// the grid's top down (compensated; a layer handing down zeros skipped, as there), the
// volumes, the centroids (world), the z apertures at the column's planes.
static void finish(const Sink *s, ulong column, __global double *aperture_z, const Frame *g) {
    double i, j;
    column_of(s, column, &i, &j);
    __global const double *handed = s->handed + 3 * column * s->areas;
    __global double *apertures = aperture_z + column * (s->depth + 1);
    double area[2] = {0.0, 0.0}, area_x[2] = {0.0, 0.0}, area_y[2] = {0.0, 0.0};
    double middle[2] = {g->origin[0] + (i + 0.5) * g->cell[0], g->origin[1] + (j + 0.5) * g->cell[1]};
    for (ulong k = s->areas - 1; k-- > 0;) {
        __global const double *above = handed + 3 * (k + 1);
        if (above[0] != 0.0 || above[1] != 0.0 || above[2] != 0.0) {
            add(area, above[0]);
            add(area_x, above[1]);
            add(area_y, above[2]);
        }
        if (k < s->depth) {
            ulong n = column * s->depth + k;
            double layer = (double)(s->first + k);
            double a = area[0] + area[1];
            double v = s->volume[n] + a;
            s->volume[n] = v * g->volume;
            __global double *c = s->centroid + 3 * n;
            double moment[3] = {c[0] + (area_x[0] + area_x[1]), c[1] + (area_y[0] + area_y[1]),
                                c[2] + 0.5 * a};
            double magnitude = fabs(v);
            int trivial = magnitude <= g->tolerance || fabs(magnitude - 1.0) <= g->tolerance;
            if (trivial) {
                c[0] = middle[0];
                c[1] = middle[1];
                c[2] = g->origin[2] + (layer + 0.5) * g->cell[2];
            } else {
                double at[3] = {i, j, layer};
                for (int d = 0; d < 3; d++) {
                    c[d] = g->origin[d] + (at[d] + within(moment[d], v)) * g->cell[d];
                }
            }
            // The plane at the bottom of layer first + k + 1: everything above it (on
            // the grid's top face, but the parts lying on it).
            double beyond = k + 2 == s->areas ? s->on_top[column] : 0.0;
            apertures[k + 1] = a - beyond;
        }
    }
    double bottom[2] = {area[0], area[1]};
    add(bottom, handed[0]);
    apertures[0] = bottom[0] + bottom[1];
}

// One work item a tile: zero its sums, add its triangles' parts in the order listed,
// then finish each column.
__kernel void tile_moments(
    __global const double *triangles,
    __global const double *normals,
    __global const ulong *offsets,
    __global const uint *entries,
    __global double *volume,
    __global double *centroid,
    __global double *boundary_area,
    __global double *boundary_vector,
    __global double *boundary_centroid,
    __global double *aperture_z,
    __global double *handed,
    __global double *on_top,
    TILE_SCALARS,
    double ox, double oy, double oz,
    double dx, double dy, double dz,
    double cell_volume, double tolerance,
    double sx, double sy, double sz)
{
    ulong tile = get_global_id(0);
    if (tile >= tiles) {
        return;
    }
    ulong col_start = tile * per_tile;
    ulong col_end = min(col_start + per_tile, columns);
    ulong n = col_end - col_start;
    Sink s;
    s.volume = volume + col_start * depth;
    s.centroid = centroid + 3 * col_start * depth;
    s.area = boundary_area + col_start * depth;
    s.vector = boundary_vector + 3 * col_start * depth;
    s.weighted = boundary_centroid + 3 * col_start * depth;
    s.handed = handed + 3 * col_start * areas;
    s.on_top = on_top + col_start;
    s.depth = depth;
    s.areas = areas;
    s.first = first;
    s.x0 = x0;
    s.y0 = y0;
    s.width = width;
    s.col_start = col_start;
    s.scale[0] = sx;
    s.scale[1] = sy;
    s.scale[2] = sz;
    zero(s.volume, n * depth);
    zero(s.area, n * depth);
    zero(s.centroid, 3 * n * depth);
    zero(s.vector, 3 * n * depth);
    zero(s.weighted, 3 * n * depth);
    zero(s.handed, 3 * n * areas);
    zero(s.on_top, n);
    Columns c = columns_of(ny, nz, x0, y0, width, col_start, col_end);
    for (ulong e = offsets[tile]; e < offsets[tile + 1]; e++) {
        ulong triangle = (ulong)entries[e];
        __global const double *v = triangles + 9 * triangle;
        __global const double *normal = normals + 4 * triangle;
        s.normal[0] = normal[0];
        s.normal[1] = normal[1];
        s.normal[2] = normal[2];
        s.has_normal = normal[3] != 0.0;
        sweep_corners(v, nx, &c, &s);
    }
    Frame g;
    g.origin[0] = ox;
    g.origin[1] = oy;
    g.origin[2] = oz;
    g.cell[0] = dx;
    g.cell[1] = dy;
    g.cell[2] = dz;
    g.volume = cell_volume;
    g.tolerance = tolerance;
    for (ulong col = 0; col < n; col++) {
        finish(&s, col, aperture_z + col_start * (depth + 1), &g);
    }
}
