/* nonlinear_lining_stiffness: the lining's secant stiffness varies with displacement.
 * u_6 <- u_6 * max(c + a*(x - 1) + b*(x - 1)^2, 0), x = u_6/u_ref, u_ref = 0.1 mm
 * (Day 2014, ch. 3; McKinlay et al. 2004)
 * Python: rollaway/effects/nonlinear_lining_stiffness.py */
static double nonlinear_lining_stiffness_displacement(const DrumState *s, double u6_m, double stiffness_scale,
                                                      double stiffness_slope, double stiffness_curvature)
{
    double x1 = u6_m / 1e-4 - 1.0;
    (void)s;
    return u6_m * fmax(stiffness_scale + stiffness_slope * x1 + stiffness_curvature * (x1 * x1), 0.0);
}
