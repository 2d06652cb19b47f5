/* Plain C closed form of the four-bar of the bundled example (crank O2A = a, coupler AB = b,
 * rocker O4B = c, frame O2O4 = d along x): positions, velocities and accelerations of B
 * and the angular velocities and accelerations of coupler and rocker, for n crank angles
 * at uniform crank speed w.  The baseline the benchmarks compare linkwork against. */
#include <math.h>

void four_bar(int n, const double *phi, double a, double b, double c, double d, double w, double sigma,
              double *out /* n x 10: bx by vbx vby abx aby w2 w3 e2 e3 */) {
    for (int i = 0; i < n; i++) {
        double cp = cos(phi[i]), sp = sin(phi[i]);
        double ax = a * cp, ay = a * sp;
        double vax = -w * ay, vay = w * ax, aax = -w * w * ax, aay = -w * w * ay;
        double dx = d - ax, dy = -ay;
        double dist2 = dx * dx + dy * dy, inv = 1.0 / sqrt(dist2);
        double t = (b * b - c * c + dist2) * 0.5 * inv;
        double h = sigma * sqrt(b * b - t * t);
        double ex = dx * inv, ey = dy * inv;
        double bx = ax + t * ex - h * ey, by = ay + t * ey + h * ex;
        /* v_B = v_A + w2 perp(B - A) = w3 perp(B - O4) */
        double r1x = bx - ax, r1y = by - ay, r2x = bx - d, r2y = by;
        double c1x = -r1y, c1y = r1x, c2x = r2y, c2y = -r2x; /* -perp(r2) */
        double det = c1x * c2y - c1y * c2x;
        double rx = -vax, ry = -vay;
        double w2 = (rx * c2y - ry * c2x) / det, w3 = (c1x * ry - c1y * rx) / det;
        double rax = -aax + w2 * w2 * r1x - w3 * w3 * r2x, ray = -aay + w2 * w2 * r1y - w3 * w3 * r2y;
        double e2 = (rax * c2y - ray * c2x) / det, e3 = (c1x * ray - c1y * rax) / det;
        double *o = out + 10 * i;
        o[0] = bx; o[1] = by;
        o[2] = -w3 * r2y; o[3] = w3 * r2x;
        o[4] = -e3 * r2y - w3 * w3 * r2x; o[5] = e3 * r2x - w3 * w3 * r2y;
        o[6] = w2; o[7] = w3; o[8] = e2; o[9] = e3;
    }
}

/* The same closed form with the outputs linkwork gives: the state of every moving link (crank,
 * coupler, rocker), each as its local frame's x, y, angle, their velocities and accelerations
 * (the origin of a link is its first end: O2, A, O4), n x 27, one row a sample. */
void four_bar_full(int n, const double *phi, double a, double b, double c, double d, double w, double sigma,
                   double *out) {
    for (int i = 0; i < n; i++) {
        double cp = cos(phi[i]), sp = sin(phi[i]);
        double ax = a * cp, ay = a * sp;
        double vax = -w * ay, vay = w * ax, aax = -w * w * ax, aay = -w * w * ay;
        double dx = d - ax, dy = -ay;
        double dist2 = dx * dx + dy * dy, inv = 1.0 / sqrt(dist2);
        double t = (b * b - c * c + dist2) * 0.5 * inv;
        double h = sigma * sqrt(b * b - t * t);
        double ex = dx * inv, ey = dy * inv;
        double bx = ax + t * ex - h * ey, by = ay + t * ey + h * ex;
        double r1x = bx - ax, r1y = by - ay, r2x = bx - d, r2y = by;
        double c1x = -r1y, c1y = r1x, c2x = r2y, c2y = -r2x;
        double det = c1x * c2y - c1y * c2x;
        double rx = -vax, ry = -vay;
        double w2 = (rx * c2y - ry * c2x) / det, w3 = (c1x * ry - c1y * rx) / det;
        double rax = -aax + w2 * w2 * r1x - w3 * w3 * r2x, ray = -aay + w2 * w2 * r1y - w3 * w3 * r2y;
        double e2 = (rax * c2y - ray * c2x) / det, e3 = (c1x * ray - c1y * rax) / det;
        double *o = out + 27 * i;
        /* crank about O2 */
        o[0] = 0.0; o[1] = 0.0; o[2] = phi[i]; o[3] = 0.0; o[4] = 0.0; o[5] = w; o[6] = 0.0; o[7] = 0.0; o[8] = 0.0;
        /* coupler from A */
        o[9] = ax; o[10] = ay; o[11] = atan2(r1y, r1x);
        o[12] = vax; o[13] = vay; o[14] = w2; o[15] = aax; o[16] = aay; o[17] = e2;
        /* rocker about O4 */
        o[18] = d; o[19] = 0.0; o[20] = atan2(r2y, r2x);
        o[21] = 0.0; o[22] = 0.0; o[23] = w3; o[24] = 0.0; o[25] = 0.0; o[26] = e3;
    }
}
