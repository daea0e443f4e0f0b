/* modulus_temperature: the lining's Young's modulus falls as it gets hot.
 * E_l(T_l) = E_l * max(1 - k_E*(T_l - T_amb), 0.05) in eq. (16)   (Day 2014, ch. 3; Wolff 2010)
 * Python: rollaway/effects/modulus_temperature.py */
static double modulus_temperature_lining_modulus(const DrumState *s, double modulus_Pa, double modulus_slope_per_K)
{
    return modulus_Pa * fmax(1.0 - modulus_slope_per_K * (s->lining_temp_C - s->ambient_C), 0.05);
}
