"""Chapter 3's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "03_trajectory"

EXERCISES = (
    Exercise("ex-traj-corner", DOC,
             params=(Param("L", 0.1, "m", ".2f", "length of each of the two segments", low=0.05, high=0.2, step=0.01),
                     Param("tf", 3.0, "s", ".1f", "duration of each segment (blend t_f/3)",
                           low=2.0, high=6.0, step=0.5),
                     Param("dt", 1.0, "s", ".1f", "anticipation at the corner (no longer than the blends)",
                           low=0.2, high=1.5, step=0.1)),
             answers=(Answer("a", "acceleration a = 4.5 L/t_f² of each segment", "m/s²", 0.01),
                      Answer("d_mm", "distance by which the arm misses the corner", "mm", 0.01)),
             note="Right angle and equal accelerations make the squared distance (a²/4)[(Δt-τ)⁴ + τ⁴], symmetric "
                  "about τ = Δt/2 and smallest there: a Δt²/(4√2); the plan's corner distance agrees."),
    Exercise("ex-traj-fast", DOC,
             params=(Param("v", 0.25, "m/s", ".2f", "speed limit", low=0.1, high=0.4, step=0.05),
                     Param("acc", 0.5, "m/s²", ".1f", "acceleration limit", low=0.2, high=1.0, step=0.1)),
             answers=(Answer("T", "shortest duration of p6 -> p7, rounded up to whole milliseconds", "s", 0.01),),
             note="If L >= v²/a the profile cruises at v: t_f = L/v + v/a; otherwise it is a triangle, "
                  "t_f = 2 sqrt(L/a); then rounded up to the next millisecond."),
    Exercise("ex-traj-half-circle", DOC,
             params=(Param("T_arc", 4.8, "s", ".1f", "new duration of the half circle (the reference: 9.6 s)",
                           low=2.4, high=8.0, step=0.2),),
             answers=(Answer("growth", "factor by which the peak tangential and centripetal accelerations grow",
                             "", 0.01),
                      Answer("cent_quick", "peak centripetal acceleration on the shortened half circle", "m/s²",
                             0.01),
                      Answer("quick_rest", "rest at p11 at the end of the 70 s", "s", 0.05, absolute=True)),
             note="Both accelerations scale with 1/t_f² (the cruise speed with 1/t_f), so they grow by "
                  "(9.6 s / t_f)²; the total stays 70 s and the time saved is added to the final rest."),
    Exercise("ex-traj-turn", DOC,
             params=(Param("turn", 90.0, "°", ".0f", "turn of the gripper on p0 -> p1", low=15.0, high=180.0,
                           step=15.0),),
             answers=(Answer("phidot_max_deg", "largest angular speed of the gripper", "°/s", 0.01),),
             note="The orientation rides on the segment's normalised law, so it peaks at the cruise, "
                  "1.5 Δφ/t_f with t_f = 4 s; the positions do not change at all."),
    Exercise("ex-traj-reach", DOC,
             params=(Param("x7", 0.95, "m", ".2f", "new x of p7", low=0.95, high=1.1, step=0.01),
                     Param("y7", 0.35, "m", ".2f", "new y of p7", low=0.35, high=0.5, step=0.01),
                     Param("z7", 0.3, "m", ".1f", "new z of p7")),
             answers=(Answer("r7", "distance of the new p7 from the joint-1 axis", "m", 0.002, absolute=True),
                      Answer("t_out", "time of the first sample outside the workspace (the planner's message)",
                             "s", 0.01, absolute=True)),
             note="The planner raises UnreachableError at the first sample on p6 -> p7 outside the annulus "
                  "|a1 - a2| <= r <= a1 + a2 = 1 m: what limits the reach is the distance from the joint-1 axis, "
                  "hypot(x, y) > 1 m, not the length of the arm along one coordinate; nothing is clipped."),
    Exercise("ex-traj-stop", DOC,
             answers=(Answer("end_stop", "end of the motion with p4 a stop", "s", 0.05, absolute=True),
                      Answer("p3_mm", "distance by which the arm misses p3", "mm", 0.01),
                      Answer("p8_mm", "distance by which the arm misses p8", "mm", 0.01),
                      Answer("w_stop", "smallest manipulability met", "m²", 0.01)),
             note="Every later segment starts 2 s later, so the motion ends 2 s later; the corner at p4 "
                  "disappears, those at p3 and p8 are the same parabolas, later; the arm reaches p4 itself, "
                  "closer to the axis, so the smallest manipulability goes down slightly."),
    Exercise("ex-traj-half-anticipation", DOC,
             params=(Param("antic", 1.0, "s", ".2f", "anticipation at p4 (the reference: 2 s)", low=0.25,
                           high=1.75, step=0.25),),
             answers=(Answer("d_mm", "distance by which the arm misses p4", "mm", 0.01),
                      Answer("end", "end of the motion", "s", 0.05, absolute=True)),
             note="Within the 2 s blends the corner is the pair of parabolas, every point scaling with Δt²: "
                  "the distance is (Δt / 2 s)² times the reference's; the motion ends 2 s - Δt later."),
    Exercise("ex-traj-rest-to-rest", DOC,
             answers=(Answer("cubic_peak", "peak θ̇2 on p6 -> p7, cubic", "°/s", 0.01),
                      Answer("quintic_peak", "peak θ̇2 on p6 -> p7, quintic", "°/s", 0.01,
                             shown="the chapter's comparison table of the three plans")),
             note="Cubic from rest: q̇ = (6Δq/t_f) ν(1-ν), peak 3Δq/(2t_f) at ν = 1/2, |q̈| largest (6|Δq|/t_f²) "
                  "at the ends; quintic: q̇ = (30Δq/t_f) ν²(1-ν)², peak 15Δq/(8t_f), |q̈| at most "
                  "10|Δq|/(√3 t_f²) at ν = 1/2 ∓ √3/6; then the knots' Δθ2 and t_f of p6 -> p7."),
    Exercise("ex-traj-same-path", DOC,
             note="The stop-to-stop segments (p0->p1, p1->p2, p6->p7, p9->p10, p10->p11) agree: from rest to "
                  "rest both laws move all joints as q_i + Δq h(τ) with one h, along the same joint-space line, "
                  "so the gripper follows the same curve; next to a via point the velocities bend the path "
                  "differently. The p6->p7 deviation is that of joint interpolation itself: only knots remove it."),
    Exercise("ex-traj-knots", DOC,
             params=(Param("tol_mm", 1.0, "mm", ".2f", "largest distance allowed from the path", low=0.5,
                           high=3.0, step=0.25),),
             answers=(Answer("n", "smallest number of extra knots per segment", "", 0.5, absolute=True),
                      Answer("dev_mm", "largest distance from the path with that many knots", "mm", 0.01)),
             note="path_deviation(joint_counterpart(traj, extra=n), traj).max() for n = 0, 1, ... until it is "
                  "within the tolerance; the distance does not fall with every added knot."),
)
