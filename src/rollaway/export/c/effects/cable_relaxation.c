/* cable_relaxation: cable/lever stretch loses lining displacement with time.
 * u_6 <- u_6 - delta*(1 - exp(-t/tau_r))   (Feyrer 2007, sec. 1.3; Limpert 1999, sec. 7)
 * Python: rollaway/effects/cable_relaxation.py */
static double cable_relaxation_displacement(const DrumState *s, double u6_m, double displacement_loss_m,
                                            double relaxation_time_s)
{
    return u6_m - displacement_loss_m * (1.0 - exp(-s->time_s / relaxation_time_s));
}
