/* lining_creep: the clamp force relaxes at fixed strain (standard linear solid).
 * F_l0 <- F_l0 * (1 - c*(1 - exp(-t/tau_c)))   (Findley, Lai & Onaran 1976, ch. 5)
 * Python: rollaway/effects/lining_creep.py */
static double lining_creep_clamp_force(const DrumState *s, double force_N, double relaxed_fraction,
                                       double relaxation_time_s)
{
    return force_N * (1.0 - relaxed_fraction * (1.0 - exp(-s->time_s / relaxation_time_s)));
}
