/* friction_temperature: mu changes with the lining temperature.
 * mu(T_l) = mu_d * (1 + k_mu*(T_l - 100 degC)), kept in [1e-3, 0.95*l_f/l_fr] (never self-locking)
 * (Limpert 1999, sec. 3; Day 2014, ch. 3)
 * Python: rollaway/effects/friction_temperature.py */
static double friction_temperature_friction(const DrumState *s, double mu, double mu_slope_per_K)
{
    double mu_max = 0.95 * shoe_arm_normal_m / fmax(shoe_arm_friction_m, 1e-12);
    double out = mu * (1.0 + mu_slope_per_K * (s->lining_temp_C - 100.0));
    return fmin(fmax(out, 1e-3), mu_max);
}
