/* shoe_thermal_lag: the lining follows the drum through a first-order lag tau_l,
 * dT_l/dt = (T_d - T_l)/tau_l, T_l(0) = T_0, solved in closed form for the convective drum (eq. 10):
 * T_l = T_amb + A*(tau*e^{-t/tau} - tau_l*e^{-t/tau_l})/(tau - tau_l), limit A*(1 + t/tau)*e^{-t/tau} at tau_l = tau
 * (Incropera & DeWitt 2007, sec. 5.2)
 * Python: rollaway/effects/shoe_thermal_lag.py */
static double shoe_thermal_lag_lining_temperature(const DrumState *s, double temp_C, double lag_time_s)
{
    double t = s->time_s, tau = s->cooling_time_constant_s, amp = s->initial_temp_C - s->ambient_C;
    (void)temp_C;
    if (lag_time_s <= 0.0) return s->ambient_C + amp * exp(-t / tau);
    if (fabs(tau - lag_time_s) < 1e-6 * tau) return s->ambient_C + amp * (1.0 + t / tau) * exp(-t / tau);
    return s->ambient_C + amp * (tau * exp(-t / tau) - lag_time_s * exp(-t / lag_time_s)) / (tau - lag_time_s);
}
