"""Chapter 7's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "07_interaction"

EXERCISES = (
    Exercise("ex-int-series", DOC,
             params=(Param("K_P", 5000.0, "N/m", ".0f", "compliance stiffness K_P,z along z",
                           low=1000.0, high=20000.0, step=1000.0),
                     Param("depth_mm", 2.0, "mm", ".1f", "how far below the undeformed surface z_d is set",
                           low=0.5, high=5.0, step=0.5)),
             answers=(Answer("force_N", "normal force at rest, k_e K_P,z / (K_P,z + k_e) (z_s - z_d)", "N", 0.01),
                      Answer("penetration_mm", "penetration at rest, K_P,z / (K_P,z + k_e) (z_s - z_d)", "mm",
                             0.01)),
             note="At rest the law's spring K_P,z and the surface's k_e are in series between z_d and z_s: the "
                  "force is the series stiffness times z_s - z_d, the penetration that force over k_e."),
    Exercise("ex-int-bias", DOC,
             params=(Param("f_d", 10.0, "N", ".0f", "force asked for, pressing down", low=8.0, high=30.0,
                           step=1.0),
                     Param("bias", 0.5, "N", ".1f", "the sensor's bias on f_z", low=0.1, high=2.0, step=0.1)),
             answers=(Answer("force_N", "the true normal force at rest, f_d + b", "N", 0.01),
                      Answer("penetration_mm", "the penetration at rest, (f_d + b) / k_e", "mm", 0.01)),
             note="The integral stops only when the measured force equals f_d; the sensor reads b more than the "
                  "true force upward, so the tool presses f_d + b, and the surface's spring sets the penetration."),
    Exercise("ex-int-force-loop", DOC,
             params=(Param("K_I", 2e-3, "m/(N s)", ".4f", "integral gain of the force loop",
                           low=1e-3, high=4e-3, step=5e-4),),
             answers=(Answer("tau_ms", "time constant of the force error, (1 + K_F k_e) / (K_I k_e)", "ms", 0.01),
                      Answer("routh", "largest K_I of the continuous-time loop (Routh)", "m/(N s)", 0.01),
                      Answer("sampled", "largest K_I of the loop sampled at 1 ms", "m/(N s)", 0.01)),
             note="With the inner loop at rest the force obeys (1 + K_F k_e) dh/dt = K_I k_e (f_d - h); the cubic "
                  "of the whole loop is stable while a2 a1 > a0 (Routh); sampling lowers that bound."),
    Exercise("ex-int-peg", DOC,
             params=(Param("clearance_mm", 0.5, "mm", ".1f", "radial clearance between peg and hole",
                           low=0.2, high=1.0, step=0.1),),
             answers=(Answer("offset_mm", "largest start offset from the hole's axis that drops straight in",
                             "mm", 0.01),),
             note="Above the hole the surface bears the peg only while its axis is more than the clearance off the "
                  "hole's axis; within it the force loop lowers the peg into the hole with no landing. Runs just "
                  "within and just beyond the clearance confirm it."),
)
