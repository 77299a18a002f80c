/* pn_math.c - the little host-side math the core needs beyond sqrt, written out so the
 * core links against no libm function on bare metal. */
#include "pn_internal.h"

int pn_finite(float v)
{
    /* NaN != NaN; inf - inf is NaN. Valid without -ffast-math, which the core never uses. */
    return v == v && (v - v) == 0.0f;
}

/* tan(fov/2) for fov in (0, 180) degrees, via sin/cos Taylor series in double on
 * [0, pi/2] (terms to x^25: error below 1e-17), rounded once to float. Deterministic on
 * any IEEE double implementation, and the same value on every port. */
float pn_tan_half_deg(float fov_deg)
{
    const double pi = 3.14159265358979323846;
    double x = (double)fov_deg * 0.5 * pi / 180.0;
    double x2 = x * x, term = x, s = x, c = 1.0, tc = 1.0;
    int i;
    for (i = 1; i <= 12; i++) {
        term *= -x2 / (double)((2 * i) * (2 * i + 1));
        s += term;
        tc *= -x2 / (double)((2 * i - 1) * (2 * i));
        c += tc;
    }
    return (float)(s / c);
}
