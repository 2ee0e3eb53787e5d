"""Chapter 2's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "02_manipulability"

EXERCISES = (
    Exercise("ex-manip-best", DOC,
             answers=(Answer("r_best", "radius of the circle where w is largest", "m", 0.01,
                             shown="the chapter's text, which the exercise asks to derive"),
                      Answer("w_max", "largest w", "m²", 0.01)),
             note="w = a1 a2 |sin θ2| is largest for c2 = 0, i.e. r² = a1² + a2²: a circle of radius √(a1² + a2²), "
                  "with w = a1 a2 and the elbow at a right angle."),
    Exercise("ex-manip-share", DOC,
             params=(Param("pct", 50.0, "%", ".0f", "threshold on w, in % of its largest value",
                           low=20.0, high=90.0, step=5.0),),
             answers=(Answer("share", "fraction of the workspace's area where w reaches the threshold", "", 0.01),),
             note="w >= k a1 a2 means |sin θ2| >= k; through r² = a1² + a2² + 2 a1 a2 cos θ2 this is a ring, whose area "
                  "over that of the workspace is √(1 - k²) (√3/2 for k = 1/2); the grid of workspace_map agrees to "
                  "about 0.01."),
    Exercise("ex-manip-push", DOC,
             params=(Param("t2", 45.0, "°", ".0f", "elbow angle θ2 (θ1 = 0, d3 = 0.5 m, θ4 = 0)",
                           low=15.0, high=110.0, step=5.0),),
             answers=(Answer("push", "largest horizontal force per unit torque norm, 1/σ2", "N", 0.01,
                             shown="the table of the four configurations, as 1/σ2"),
                      Answer("angle", "its direction from x_b, between -90° and 90°", "°", 0.5, absolute=True)),
             note="The major axis of the force ellipse is the minor axis of the velocity ellipse: the eigenvector of "
                  "the smaller eigenvalue σ2² of H Hᵀ, with force 1/σ2; it lies close to the line from the axis to "
                  "the gripper."),
    Exercise("ex-manip-turn", DOC,
             params=(Param("t2", 45.0, "°", ".0f", "elbow angle θ2 (fixed: the figure's)"),
                     Param("t1", 60.0, "°", ".0f", "θ1 the base turns to (a step of the figure)",
                           choices=(10.0, 20.0, 30.0, 40.0, 50.0, 60.0))),
             answers=(Answer("w", "w after the turn", "m²", 0.01,
                             shown="the table of the four configurations (turning the base changes nothing)"),
                      Answer("s1", "major velocity semi-axis after the turn", "m/s", 0.01,
                             shown="the table of the four configurations (turning the base changes nothing)"),
                      Answer("s2", "minor velocity semi-axis after the turn", "m/s", 0.01,
                             shown="the table of the four configurations (turning the base changes nothing)"),
                      Answer("axis_b", "direction of the major velocity axis after the turn, from x_b", "°", 0.2,
                             absolute=True)),
             note="w and the semi-axes depend on θ2 alone and stay; the ellipses turn rigidly by -θ1 seen from above "
                  "(the upside-down frame 0 turns the arm clockwise for a positive θ1)."),
    Exercise("ex-manip-unequal", DOC,
             params=(Param("a1", 0.7, "m", ".2f", "link length a1", low=0.55, high=0.9, step=0.05),
                     Param("a2", 0.3, "m", ".2f", "link length a2", low=0.1, high=0.45, step=0.05)),
             answers=(Answer("r_best", "radius of the circle where w is largest", "m", 0.01),
                      Answer("w_max", "largest w", "m²", 0.01),
                      Answer("r_min", "radius of the circle of folded singularities", "m", 0.01)),
             note="w = a1 a2 |sin θ2| is largest, a1 a2, on the circle r = √(a1² + a2²); the workspace has a hole of "
                  "radius |a1 - a2|, whose rim is the folded singularity."),
    Exercise("ex-manip-stretched", DOC,
             params=(Param("t2", 10.0, "°", ".0f", "elbow angle θ2 to predict at (θ1 = 0; a step of the figure)",
                           choices=(30.0, 20.0, 10.0, 5.0)),),
             answers=(Answer("s1", "major velocity semi-axis σ1", "m/s", 0.01,
                             shown="the slider of the stretched-arm figure, to check the prediction on"),
                      Answer("s2", "minor velocity semi-axis σ2", "m/s", 0.01),
                      Answer("f2", "largest force semi-axis 1/σ2", "N", 0.01)),
             note="σ1 σ2 = w = a1 a2 sin θ2 and σ1² + σ2² = trace(H Hᵀ) = a1² + 2 a2² + 2 a1 a2 cos θ2 give both "
                  "semi-axes; 1/σ2 is the force semi-axis. The ellipse becomes thin along the line from the axis to "
                  "the gripper (radially)."),
)
