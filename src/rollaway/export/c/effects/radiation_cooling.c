/* radiation_cooling: the drum loses heat by convection and radiation,
 *   C dT/dt = -h A (T - T_a) - eps sigma A (T_K^4 - T_aK^4)      (Incropera & DeWitt 2007, secs. 1.2.3, 12.3)
 * Separable: with s = ln(T - T_a), t(s) = G(s_0) - G(s), G(s) = integral of (T - T_a) C / q(T) ds.
 * G is tabulated once (radiation_cooling_setup) on the same log grid as the Python code
 * (2000 points over TABLE_SPAN_K, trapezoid rule) and inverted by linear interpolation, so both give the same
 * numbers.
 * Python: rollaway/effects/radiation_cooling.py */
/* @members */
#define RADIATION_GRID 2000               /* points of the table, as n_grid in Python */
#define RADIATION_SPAN_K 1500.0           /* the table's reach from the ambient, TABLE_SPAN_K in Python */
    double radiation_s[RADIATION_GRID];   /* log grid s = ln(T - T_a) */
    double radiation_g[RADIATION_GRID];   /* G(s) [s] */
    double radiation_f0;                  /* the integrand at the grid's lower end (pure convection) */
/* @end */

static const double STEFAN_BOLTZMANN_W_m2K4 = 5.670374419e-8;
static const double KELVIN = 273.15;

/* numpy.interp: linear interpolation in an increasing table, clamped at its ends */
static double radiation_interp(double x, const double *xp, const double *fp, int n)
{
    int lo = 0, hi = n - 1;
    double slope;
    if (x < xp[0]) return fp[0];
    if (x >= xp[n - 1]) return fp[n - 1];
    while (hi - lo > 1) {                 /* xp[lo] <= x < xp[hi] */
        int mid = (lo + hi) / 2;
        if (xp[mid] <= x) lo = mid; else hi = mid;
    }
    slope = (fp[lo + 1] - fp[lo]) / (xp[lo + 1] - xp[lo]);
    return slope * (x - xp[lo]) + fp[lo];
}

/* The table runs from T_0 to T_a on the side T_0 is on: side = +1 for a drum cooling down to the
 * ambient, -1 for one warming up to it (s = ln|T - T_a|), as in Python. */
static double radiation_side(const DrumState *s)
{
    return s->initial_temp_C >= s->ambient_C ? 1.0 : -1.0;
}

static int radiation_cooling_check(const DrumState *s, char *why, int size)
{
    (void)s; (void)why; (void)size;
    return 0;
}

static void radiation_cooling_setup(DrumState *s, double emissivity)
{
    double ta = s->ambient_C, heat_capacity_J_K = drum_density_kg_m3 * drum_specific_heat_J_kgK * drum_volume_m3;
    double sg = radiation_side(s);
    double span = sg > 0.0 ? RADIATION_SPAN_K : fmin(RADIATION_SPAN_K, 0.99 * (ta + KELVIN));  /* not below 0 K */
    double top = fmax(span, sg * (s->initial_temp_C - ta) * 1.01);
    double start = log(1e-4), step = (log(top) - start) / (RADIATION_GRID - 1), f_prev = 0.0;
    int i;
    for (i = 0; i < RADIATION_GRID; i++) {        /* numpy.linspace, then the trapezoid rule */
        double d, q, f;
        s->radiation_s[i] = i == RADIATION_GRID - 1 ? log(top) : i * step + start;
        d = exp(s->radiation_s[i]);
        q = heat_transfer_W_m2K * cooled_area_m2 * d + emissivity * STEFAN_BOLTZMANN_W_m2K4 * cooled_area_m2
            * sg * (pow(ta + sg * d + KELVIN, 4.0) - pow(ta + KELVIN, 4.0));
        f = heat_capacity_J_K * d / q;
        if (i == 0) {
            s->radiation_g[0] = 0.0;
            s->radiation_f0 = f;
        } else {
            s->radiation_g[i] = s->radiation_g[i - 1]
                + 0.5 * (f + f_prev) * (s->radiation_s[i] - s->radiation_s[i - 1]);
        }
        f_prev = f;
    }
}

static double radiation_cooling_drum_temperature(const DrumState *s, double temp_C, double emissivity)
{
    double ta = s->ambient_C, t0 = s->initial_temp_C, d0 = fmax(radiation_side(s) * (t0 - ta), 1e-4), s_out, sign;
    double g_target = radiation_interp(log(d0), s->radiation_s, s->radiation_g, RADIATION_GRID) - s->time_s;
    (void)temp_C; (void)emissivity;
    if (g_target >= 0.0)
        s_out = radiation_interp(g_target, s->radiation_g, s->radiation_s, RADIATION_GRID);
    else           /* below the grid the integrand is the pure-convection limit: extend exponentially */
        s_out = s->radiation_s[0] + g_target / s->radiation_f0;
    sign = t0 > ta ? 1.0 : (t0 < ta ? -1.0 : 0.0);
    return ta + sign * exp(s_out);
}
