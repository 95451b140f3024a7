// The grid kernels' polygons: crates/meshvol/src/grid/clip.rs (`Polygon`) and the
// rounding helpers of layout.rs (`floor`, `cover`), operation for operation, so that
// every piece is the CPU's bits. No contraction: Rust never fuses a multiply and an
// add, and the CPU code uses no `mul_add`, so neither does any file of these kernels.
// Each program is this file, sweeps.cl, then one kernel's file (volumes.cl, or
// integrals.cl and moments.cl): run.rs and moments.rs put them together.
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
