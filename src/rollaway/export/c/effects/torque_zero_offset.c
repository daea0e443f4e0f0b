/* torque_zero_offset: the torque transducer's zero offset, measured torque = T_gen (eq. 17b) + z
 * (ISO 376 practice; Doebelin 2004, sec. 4).  One value for the whole run.
 * Python: rollaway/effects/torque_zero_offset.py */
static double torque_zero_offset_torque(const DrumState *s, double torque_Nm, double offset_Nm)
{
    (void)s;
    return torque_Nm + offset_Nm;
}
