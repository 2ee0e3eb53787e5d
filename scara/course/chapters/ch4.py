"""Chapter 4's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "04_clik"

EXERCISES = (
    Exercise("ex-clik-deadbeat", DOC,
             params=(Param("T_ms", 1.0, "ms", ".1f", "sampling period T of the Euler-discretised loop",
                           low=0.5, high=5.0, step=0.5),),
             answers=(Answer("K_deadbeat", "gain that removes an initial error in one step (1/T)", "s⁻¹", 0.01),
                      Answer("K_limit", "gain past which the loop is unstable (2/T)", "s⁻¹", 0.01)),
             note="Each component is multiplied by 1 - T K per step: K = 1/T cancels it in one step (deadbeat). "
                  "Between 1/T and 2/T the factor is negative, so the error changes sign every step while it "
                  "shrinks (ringing); at 2/T it no longer shrinks."),
    Exercise("ex-clik-fragile", DOC,
             answers=(Answer("kappa_max", "largest uniform transpose gain κ on the reference", "s⁻¹", 0.01),
                      Answer("t_worst", "time on the reference where the limit is set", "s", 0.5, absolute=True)),
             note="With K = κI the eigenvalues of J J^T K are κ σ_i², so κ < 2/(T σ_max²) and the limit is set "
                  "where σ_max (the norm of J_A) peaks, the arm at its farthest (p_7). Just below, a valid run; "
                  "just above, clik refuses (nothing drawn)."),
    Exercise("ex-clik-relax", DOC,
             answers=(Answer("w_y", "mean manipulability with y relaxed", "m²", 0.01,
                             shown="the menu of the relaxed-component figure, to check the prediction on"),
                      Answer("w_z", "mean manipulability with z relaxed", "m²", 0.01),
                      Answer("drift_z", "largest drift of z with z relaxed", "m", 0.02)),
             note="Relaxing y raises w as relaxing x does (y drifts); relaxing z frees only d_3, along which "
                  "∇w has no component, so w stays the inverse's and the quill never moves: z drifts by the "
                  "full height range of the path."),
    Exercise("ex-clik-lag", DOC,
             params=(Param("A", 1.0, "m/s²", ".1f", "constant acceleration of the reference along z",
                           low=0.5, high=3.0, step=0.1),
                     Param("K", 400.0, "s⁻¹", ".0f", "second-order CLIK gain K (K_P = K², K_D = 2K)",
                           low=200.0, high=900.0, step=50.0),
                     Param("duration", 0.3, "s", ".1f", "length of the run")),
             answers=(Answer("lag_um", "steady error along z at the end of the run", "µm", 0.02),),
             note="The steady lag of the second-order CLIK is e = T A K_D / (2 K_P) = T A / K with the default "
                  "gains; along z the kinematics are linear, so a run agrees to all digits."),
    Exercise("ex-clik-damping", DOC,
             params=(Param("offset_mm", 2.0, "mm", ".1f", "distance of the straight line from the joint-1 axis",
                           low=1.0, high=5.0, step=0.5),),
             answers=(Answer("rate_10", "peak joint-1 rate at λ = 0.01 m", "rad/s", 0.02),
                      Answer("rate_100", "peak joint-1 rate at λ = 0.1 m", "rad/s", 0.02),
                      Answer("err_50", "largest position error at λ = 0.05 m", "mm", 0.02),
                      Answer("away_100", "largest position error beyond 5 cm of the axis at λ = 0.1 m", "µm",
                             0.02)),
             note="The peak rate falls fast with λ while the largest error (near the axis) hardly changes; away "
                  "from the axis the error grows with λ. Choose the smallest λ whose peak rate the motors can "
                  "deliver (or damp only near the axis)."),
    Exercise("ex-clik-second-limit", DOC,
             answers=(Answer("k_limit", "largest stable gain K of the second-order CLIK (2/T)", "s⁻¹", 0.01),
                      Answer("ep_1000_nm", "largest position error with K_z = 1000 s⁻¹", "nm", 0.02),
                      Answer("ep_ok_nm", "largest position error with K_z = 1990 s⁻¹", "nm", 0.02)),
             note="The double root 1 - KT stays in the unit circle for K < 2/T. As K_z rises the largest error "
                  "first hardly moves (x and y, still at 400 s⁻¹, set it), past KT = 1 the z error rings and "
                  "grows near the limit, and past 2/T clik2 refuses the gains."),
)
