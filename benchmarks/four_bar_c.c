/* Plain C closed form of the four-bar of the bundled example (crank O2A = a, coupler AB = b,
 * rocker O4B = c, frame O2O4 = d along x) at uniform crank speed w, for n crank angles: the
 * baseline the benchmarks compare linkwork against. */
#include <math.h>

typedef struct {
    double ax, ay, vax, vay, aax, aay; /* joint A */
    double bx, by, r1x, r1y, r2x, r2y; /* joint B, and B - A, B - O4 */
    double w2, w3, e2, e3;             /* angular velocities and accelerations of coupler and rocker */
} solution;

static inline solution solve(double phi, double a, double b, double c, double d, double w, double sigma) {
    solution s;
    double cp = cos(phi), sp = sin(phi);
    s.ax = a * cp, s.ay = a * sp;
    s.vax = -w * s.ay, s.vay = w * s.ax, s.aax = -w * w * s.ax, s.aay = -w * w * s.ay;
    double dx = d - s.ax, dy = -s.ay;
    double dist2 = dx * dx + dy * dy, inv = 1.0 / sqrt(dist2);
    double t = (b * b - c * c + dist2) * 0.5 * inv;
    double h = sigma * sqrt(b * b - t * t);
    double ex = dx * inv, ey = dy * inv;
    s.bx = s.ax + t * ex - h * ey, s.by = s.ay + t * ey + h * ex;
    /* v_B = v_A + w2 perp(B - A) = w3 perp(B - O4) */
    s.r1x = s.bx - s.ax, s.r1y = s.by - s.ay, s.r2x = s.bx - d, s.r2y = s.by;
    double c1x = -s.r1y, c1y = s.r1x, c2x = s.r2y, c2y = -s.r2x; /* -perp(r2) */
    double det = c1x * c2y - c1y * c2x;
    double rx = -s.vax, ry = -s.vay;
    s.w2 = (rx * c2y - ry * c2x) / det, s.w3 = (c1x * ry - c1y * rx) / det;
    double rax = -s.aax + s.w2 * s.w2 * s.r1x - s.w3 * s.w3 * s.r2x;
    double ray = -s.aay + s.w2 * s.w2 * s.r1y - s.w3 * s.w3 * s.r2y;
    s.e2 = (rax * c2y - ray * c2x) / det, s.e3 = (c1x * ray - c1y * rax) / det;
    return s;
}

/* Positions, velocities and accelerations of B and the angular velocities and accelerations of
 * coupler and rocker: n x 10 (bx by vbx vby abx aby w2 w3 e2 e3). */
void four_bar(int n, const double *phi, double a, double b, double c, double d, double w, double sigma,
              double *out) {
    for (int i = 0; i < n; i++) {
        solution s = solve(phi[i], a, b, c, d, w, sigma);
        double *o = out + 10 * i;
        o[0] = s.bx; o[1] = s.by;
        o[2] = -s.w3 * s.r2y; o[3] = s.w3 * s.r2x;
        o[4] = -s.e3 * s.r2y - s.w3 * s.w3 * s.r2x; o[5] = s.e3 * s.r2x - s.w3 * s.w3 * s.r2y;
        o[6] = s.w2; o[7] = s.w3; o[8] = s.e2; o[9] = s.e3;
    }
}

/* The outputs linkwork gives: the state of every moving link (crank, coupler, rocker), each as its
 * local frame's x, y, angle, their velocities and accelerations (the origin of a link is its first
 * end: O2, A, O4), n x 27, one row a sample. */
void four_bar_full(int n, const double *phi, double a, double b, double c, double d, double w, double sigma,
                   double *out) {
    for (int i = 0; i < n; i++) {
        solution s = solve(phi[i], a, b, c, d, w, sigma);
        double *o = out + 27 * i;
        o[0] = 0.0; o[1] = 0.0; o[2] = phi[i]; o[3] = 0.0; o[4] = 0.0; o[5] = w; o[6] = 0.0; o[7] = 0.0; o[8] = 0.0;
        o[9] = s.ax; o[10] = s.ay; o[11] = atan2(s.r1y, s.r1x);
        o[12] = s.vax; o[13] = s.vay; o[14] = s.w2; o[15] = s.aax; o[16] = s.aay; o[17] = s.e2;
        o[18] = d; o[19] = 0.0; o[20] = atan2(s.r2y, s.r2x);
        o[21] = 0.0; o[22] = 0.0; o[23] = s.w3; o[24] = 0.0; o[25] = 0.0; o[26] = s.e3;
    }
}
