// The integrals over one part of the surface in a cell:
// crates/meshvol/src/grid/cut_cells/integrals.rs (`projected`, `handed_down`,
// `surface_part`), operation for operation and in the same order of additions, so the
// same bits. Coordinates local to the part's cell, x' = x − i (and y', z'); the part a
// fan from vertex 0.

// `Projected`: the part's volume terms about its layer's floor, and its column terms.
typedef struct {
    double area, area_x, area_y, z, xz, yz, zz_half;
} Projected;

// `projected`: ∫ z' n_z dA and the projected area through `area_and_moment` (the volume
// kernel's own, so the volumes are its bits), then the fan's first and second moments.
static Projected projected(const Poly *p, double i, double j, double k) {
    Projected r;
    double area, z;
    area_and_moment(p, k, &area, &z);
    if (p->len < 3) {
        r.area = 0.0;
        r.area_x = 0.0;
        r.area_y = 0.0;
        r.z = 0.0;
        r.xz = 0.0;
        r.yz = 0.0;
        r.zz_half = 0.0;
        return r;
    }
    double o[3] = {p->v[0][0] - i, p->v[0][1] - j, p->v[0][2] - k};
    double area_x = 0.0, area_y = 0.0, xz = 0.0, yz = 0.0, zz = 0.0;
    for (int t = 1; t < p->len - 1; t++) {
        double a[3] = {p->v[t][0] - i, p->v[t][1] - j, p->v[t][2] - k};
        double b[3] = {p->v[t + 1][0] - i, p->v[t + 1][1] - j, p->v[t + 1][2] - k};
        double cross = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        double sx = o[0] + a[0] + b[0];
        double sy = o[1] + a[1] + b[1];
        double sz = o[2] + a[2] + b[2];
        area_x += cross * sx;
        area_y += cross * sy;
        xz += cross * (o[0] * o[2] + a[0] * a[2] + b[0] * b[2] + sx * sz);
        yz += cross * (o[1] * o[2] + a[1] * a[2] + b[1] * b[2] + sy * sz);
        zz += cross * (o[2] * o[2] + a[2] * a[2] + b[2] * b[2] + sz * sz);
    }
    r.area = area;
    r.area_x = area_x / 6.0;
    r.area_y = area_y / 6.0;
    r.z = z;
    r.xz = xz / 24.0;
    r.yz = yz / 24.0;
    r.zz_half = zz / 48.0;
    return r;
}

// `handed_down`: the projected area and its first moments, of a part above the cells
// computed (the same operations as `projected`'s).
static void handed_down(const Poly *p, double i, double j, double out[3]) {
    if (p->len < 3) {
        out[0] = 0.0;
        out[1] = 0.0;
        out[2] = 0.0;
        return;
    }
    double o[2] = {p->v[0][0] - i, p->v[0][1] - j};
    double area_x = 0.0, area_y = 0.0;
    for (int t = 1; t < p->len - 1; t++) {
        double a[2] = {p->v[t][0] - i, p->v[t][1] - j};
        double b[2] = {p->v[t + 1][0] - i, p->v[t + 1][1] - j};
        double cross = (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        area_x += cross * (o[0] + a[0] + b[0]);
        area_y += cross * (o[1] + a[1] + b[1]);
    }
    out[0] = area_of(p);
    out[1] = area_x / 6.0;
    out[2] = area_y / 6.0;
}

// `surface_part`: the part's area vector (half its fan's summed crosses) and its local
// centroid, the fan triangles' centres weighted by their crosses along the total;
// 0 where the part has no area (`None`).
static int surface_part(const Poly *p, double i, double j, double k, double vector[3],
                        double centroid[3]) {
    if (p->len < 3) {
        return 0;
    }
    double o[3] = {p->v[0][0] - i, p->v[0][1] - j, p->v[0][2] - k};
    double crosses[MAXV][3];
    double centres[MAXV][3];
    double total[3] = {0.0, 0.0, 0.0};
    for (int t = 0; t < p->len - 2; t++) {
        double a[3] = {p->v[t + 1][0] - i, p->v[t + 1][1] - j, p->v[t + 1][2] - k};
        double b[3] = {p->v[t + 2][0] - i, p->v[t + 2][1] - j, p->v[t + 2][2] - k};
        double e[3] = {a[0] - o[0], a[1] - o[1], a[2] - o[2]};
        double f[3] = {b[0] - o[0], b[1] - o[1], b[2] - o[2]};
        crosses[t][0] = e[1] * f[2] - e[2] * f[1];
        crosses[t][1] = e[2] * f[0] - e[0] * f[2];
        crosses[t][2] = e[0] * f[1] - e[1] * f[0];
        for (int d = 0; d < 3; d++) {
            centres[t][d] = (o[d] + a[d] + b[d]) / 3.0;
            total[d] += crosses[t][d];
        }
    }
    double norm2 = total[0] * total[0] + total[1] * total[1] + total[2] * total[2];
    if (norm2 == 0.0) {
        return 0;
    }
    for (int d = 0; d < 3; d++) {
        centroid[d] = 0.0;
    }
    for (int t = 0; t < p->len - 2; t++) {
        double weight =
            (crosses[t][0] * total[0] + crosses[t][1] * total[1] + crosses[t][2] * total[2]) / norm2;
        for (int d = 0; d < 3; d++) {
            centroid[d] += weight * centres[t][d];
        }
    }
    for (int d = 0; d < 3; d++) {
        vector[d] = 0.5 * total[d];
    }
    return 1;
}
