"""Chapter 1's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "01_kinematics"

EXERCISES = (
    Exercise("ex-kin-direct", DOC,
             params=(Param("t1", 30.0, "°", ".0f", "joint angle θ1", low=-45.0, high=45.0, step=5.0),
                     Param("t2", 45.0, "°", ".0f", "joint angle θ2", low=-90.0, high=90.0, step=5.0),
                     Param("d3", 0.2, "m", ".2f", "quill stroke d3", low=0.1, high=0.9, step=0.05),
                     Param("t4", -15.0, "°", ".0f", "joint angle θ4", low=-45.0, high=45.0, step=5.0)),
             answers=(Answer("px", "p_x of x_e", "m", 0.001, absolute=True),
                      Answer("py", "p_y of x_e", "m", 0.001, absolute=True),
                      Answer("pz", "p_z of x_e", "m", 0.001, absolute=True),
                      Answer("phi", "φ of x_e", "°", 0.1, absolute=True)),
             note="x_e of eq-kin-xe with a1 = a2 = 0.5 m, d0 = 1 m: p_x = a1 c1 + a2 c12, p_y = -(a1 s1 + a2 s12), "
                  "p_z = d0 - d3, φ = θ1 + θ2 + θ4; the sign of p_y is the usual slip."),
    Exercise("ex-kin-elbows", DOC,
             params=(Param("px", 0.5, "m", ".2f", "p_x of the target", low=0.2, high=0.7, step=0.05),
                     Param("py", -0.5, "m", ".2f", "p_y of the target", low=-0.7, high=-0.2, step=0.05),
                     Param("pz", 0.3, "m", ".1f", "p_z of the target", low=0.1, high=0.9, step=0.1),
                     Param("phi", 0.0, "°", ".0f", "φ of the target", low=-45.0, high=45.0, step=15.0)),
             answers=(Answer("d3", "d3 (both elbows)", "m", 0.001, absolute=True),
                      Answer("t2_up", "θ2 of elbow +1 (elbow -1 has its opposite)", "°", 0.1, absolute=True),
                      Answer("t1_up", "θ1 of elbow +1", "°", 0.1, absolute=True),
                      Answer("t1_down", "θ1 of elbow -1", "°", 0.1, absolute=True)),
             note="d3 = d0 - p_z; cos θ2 from the law of cosines (eq-kin-ik-t2), θ2 = ±acos; θ1 = atan2(-p_y, p_x) ∓ β "
                  "(eq-kin-ik-t1); θ4 = φ - θ1 - θ2 for each elbow. Both solutions are needed for full marks."),
    Exercise("ex-kin-straight", DOC,
             params=(Param("t2", 90.0, "°", ".0f", "elbow angle θ2 (θ1 = 0, d3 = 0.5 m, θ4 = 0)",
                           low=30.0, high=150.0, step=5.0),
                     Param("v", 0.1, "m/s", ".2f", "speed of the gripper along +x_b", low=0.05, high=0.3, step=0.01)),
             answers=(Answer("w1", "joint velocity of θ1", "rad/s", 0.001, absolute=True),
                      Answer("w2", "joint velocity of θ2", "rad/s", 0.001, absolute=True),
                      Answer("w4", "joint velocity of θ4", "rad/s", 0.001, absolute=True)),
             note="Solve J_A q̇ = [v, 0, 0, 0] with eq-jacobian: the horizontal 2x2 block gives θ̇1, θ̇2; the quill "
                  "stays (ḋ3 = 0) and θ̇4 = -(θ̇1 + θ̇2) keeps φ."),
    Exercise("ex-kin-singular", DOC,
             params=(Param("a1", 0.5, "m", ".2f", "link length a1", low=0.3, high=0.7, step=0.05),
                     Param("a2", 0.5, "m", ".2f", "link length a2", low=0.3, high=0.7, step=0.05)),
             answers=(Answer("null2", "θ̇2 that, with θ̇1 = 1 rad/s, keeps the gripper still", "rad/s", 0.01),),
             note="At θ2 = 0 the columns of the horizontal block are (a1 + a2) t and a2 t: θ̇2 = -(a1 + a2)/a2 θ̇1 "
                  "leaves the gripper still. The lost direction is radial (along the arm, towards or away from the "
                  "joint-1 axis); an answer without that direction is incomplete."),
    Exercise("ex-kin-unequal", DOC,
             params=(Param("a1", 0.6, "m", ".2f", "link length a1", low=0.55, high=0.8, step=0.05),
                     Param("a2", 0.4, "m", ".2f", "link length a2", low=0.2, high=0.45, step=0.05),
                     Param("px", 0.1, "m", ".2f", "p_x of the point (p_y = 0, p_z = 0.5 m)",
                           low=0.05, high=0.3, step=0.05)),
             answers=(Answer("reachable", "1 if the point is reachable, 0 if not", "", 0.1, absolute=True, fmt=".0f"),
                      Answer("rmin", "radius of the circle of folded singularities |a1 - a2|", "m", 0.01)),
             note="The workspace is the annulus |a1 - a2| <= r <= a1 + a2: the point is reachable only if its distance "
                  "to the joint-1 axis lies in it. The folded arm (θ2 = ±180°) puts the gripper on the inner rim, a "
                  "circle of singular configurations of radius |a1 - a2|."),
    Exercise("ex-kin-predict", DOC,
             params=(Param("t2", 60.0, "°", ".0f", "θ2 where the panel and the figure start (fixed: the figure)"),),
             answers=(Answer("det_start", "det J_A at the start", "m²", 0.01),
                      Answer("det_zero", "det J_A at θ2 = 0", "m²", 0.001, absolute=True),
                      Answer("det_mirror", "det J_A at θ2 = -60°", "m²", 0.01)),
             note="det J_A = a1 a2 sin θ2 (eq-kin-det): it falls to 0 at the stretched arm, changes sign, and reaches "
                  "the opposite value at the mirror elbow; θ1, d3 and θ4 leave it unchanged."),
    Exercise("ex-kin-edge", DOC,
             params=(Param("px", 0.9, "m", ".2f", "first p_x typed (p_y = 0, p_z = 0.5 m, φ = 0; a step of the figure)",
                           choices=(0.5, 0.6, 0.7, 0.8, 0.9, 0.95)),),
             answers=(Answer("t2", "θ2 of elbow +1 at the first p_x (elbow -1: its opposite)", "°", 0.1, absolute=True),
                      Answer("t2_rim", "θ2 of both elbows at p_x = 1.0 m", "°", 0.1, absolute=True)),
             note="cos θ2 = (p_x² - a1² - a2²)/(2 a1 a2) gives θ2 = ±acos; at 1.0 m cos θ2 = 1: the elbows merge into "
                  "the stretched, singular arm; at 1.01 m cos θ2 > 1: unreachable, the panel greys out and names "
                  "the annulus."),
)
