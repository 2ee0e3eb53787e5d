"""Chapter 4's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "04_clik"

EXERCISES = (
    Exercise("ex-clik-lag", DOC,
             params=(Param("A", 1.0, "m/s²", ".1f", "constant acceleration of the reference along z",
                           low=0.5, high=3.0, step=0.1),
                     Param("K", 400.0, "s⁻¹", ".0f", "second-order CLIK gain K (K_P = K², K_D = 2K)",
                           low=200.0, high=900.0, step=50.0),
                     Param("duration", 0.3, "s", ".1f", "length of the run")),
             answers=(Answer("lag_um", "steady error along z at the end of the run", "µm", 0.02),),
             note="The steady lag of the second-order CLIK is e = T A K_D / (2 K_P) = T A / K with the default "
                  "gains; along z the kinematics are linear, so a run agrees to all digits."),
)
