/* drum_radial_contraction: the cooling drum's radius shrinks onto the shoes.
 * F_l0 += c_r * k_s * alpha_d * r_d * (-dT_d), k_s the series stiffness of drum and lining
 * (Timoshenko & Goodier 1951, thin rings; Day 2014, ch. 5)
 * Python: rollaway/effects/drum_radial_contraction.py */
static double drum_radial_contraction_clamp_force(const DrumState *s, double force_N, double radial_fraction)
{
    return force_N + radial_fraction * s->series_stiffness_N_per_m * drum_expansion_per_K * drum_radius_m
        * (-(s->drum_temp_C - s->initial_temp_C));
}
