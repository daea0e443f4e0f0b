/* installation_gap: eq. (16b), every lining thickness l_ol becomes l_ol + l_g
 * (Ishak et al. 2018, eq. 16b and Table 1)
 * Python: rollaway/effects/installation_gap.py */
static double installation_gap_gap(const DrumState *s, double gap, double gap_m)
{
    (void)s;
    return gap + gap_m;
}
