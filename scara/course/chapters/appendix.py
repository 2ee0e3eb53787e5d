"""The appendix's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "appendix_verification"

EXERCISES = (
    Exercise("ex-ver-bound", DOC,
             params=(Param("calls", 4, "", "d", "aba calls per step (the per-call table is a fixed measurement)"),),
             answers=(Answer("bound_s", "lower bound of the Pinocchio closed loop", "s", 0.02),
                      Answer("share_pct", "the library calls' share of the measured time", "%", 2.0,
                             absolute=True)),
             note="calls x per-call time x steps; the rest of the measured time is the Python loop's own overhead "
                  "(a dozen small numpy operations per step)."),
    Exercise("ex-ver-coupling", DOC,
             params=(Param("qdd1", 1.0, "rad/s²", ".1f", "acceleration of joint 1", low=0.5, high=3.0, step=0.5),
                     Param("qdd2", 1.0, "rad/s²", ".1f", "acceleration of joint 2", low=0.5, high=3.0, step=0.5)),
             answers=(Answer("force_N", "force the rotor coupling asks of the quill's motor", "N", 0.01),),
             note="Row 3 of Delta B is [k_r3 I_m3, k_r3 I_m3, 0, 0], so F = k_r3 I_m3 (qdd1 + qdd2); motor 3 rides on "
                  "link 2 and must be spun up with it, which a diagonal k_r^2 I_m model cannot see."),
    Exercise("ex-ver-signs", DOC,
             params=(Param("qd1", 1.0, "rad/s", ".1f", "speed of joint 1", low=0.5, high=3.0, step=0.5),),
             answers=(Answer("omega_z", "angular velocity about the base z axis the library reports", "rad/s", 0.01,
                             absolute=True),
                      Answer("phidot", "the book's yaw rate phi_dot", "rad/s", 0.01, absolute=True)),
             note="phi_dot = J_A[3] qd = qd1; the libraries report omega_z = -phi_dot because z_0 points down."),
    Exercise("ex-ver-com", DOC,
             params=(Param("m_l1", 20.0, "kg", ".0f", "mass of link 1", low=10.0, high=30.0, step=1.0),),
             answers=(Answer("dB", "error of B11", "kg m²", 0.01),),
             note="m_l1 ((a1 + l1)^2 - l1^2), the same at every q: link 1's centre of mass stays at a fixed distance "
                  "from the joint-1 axis."),
)
