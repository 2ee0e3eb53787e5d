"""Chapter 6's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "06_control"

_PAYLOAD = dict(unit="kg", fmt=".1f", text="payload the controller does not know", low=1.0, high=10.0, step=0.5)
#: the double pole the PD gains are placed at, and the largest sag a design must respect (one declaration each)
_PD_POLE = Param("omega", 30.0, "rad/s", ".0f", "double pole of the PD loops", low=20.0, high=40.0, step=5.0)
_SAG_MAX = Param("sag_max_mm", 0.5, "mm", ".1f", "largest sag of the quill allowed at rest", low=0.2, high=1.0,
                 step=0.1)

EXERCISES = (
    Exercise("ex-ctl-ij-pd", DOC,
             params=(Param("m_L", 5.0, **_PAYLOAD), _PD_POLE, _SAG_MAX),
             answers=(Answer("sag_mm", "(a) the quill's sag at rest (the other joints: none)", "mm", 0.01,
                             shown="the chapter's text computes the PD sag for these numbers, with (6.9)"),
                      Answer("omega_min", "(b) the smallest pole keeping the sag within the bound", "rad/s", 0.01)),
             note="(a) Only the quill sags, by m3 g0 / (omega^2 B_bar33): the revolute joints carry no gravity. "
                  "(b) omega >= sqrt(m3 g0 / (B_bar33 sag)), far below 1/T, so sampling allows it. (c) The sag only "
                  "falls as 1/omega^2 and grows with the load; a stiffer loop on every joint amplifies noise and "
                  "nears the sampling limit, while the integral removes any constant load."),
    Exercise("ex-ctl-ij-margin", DOC,
             params=(Param("m_L", 10.0, "kg", ".1f", "payload of the stretched arm", low=0.0, high=10.0, step=0.5),),
             answers=(Answer("ratio", "(b) joint 1's inertia in the stretched arm over B_bar11", "", 0.01),
                      Answer("c", "(b) the factor on K_I,1 that reaches the stability edge", "", 0.01)),
             note="(a) Routh-Hurwitz on B s^3 + (F + K_D) s^2 + K_P s + K_I gives B < (F + K_D) K_P / K_I, and "
                  "F + K_D = 3 omega B_bar, K_P = 3 omega^2 B_bar, K_I = omega^3 B_bar give 9 B_bar whatever F. "
                  "(b) c = 9 / (B11 / B_bar11). (c) No: a second-order loop with positive coefficients is always "
                  "stable."),
    Exercise("ex-ctl-ij-windup", DOC,
             params=(Param("bound_fig", 155.0, "N", ".0f", "the quill's force bound of the figure"),
                     Param("bound", 150.0, "N", ".0f", "the tighter bound of part (b)")),
             answers=(Answer("integral_N", "(a) the largest integral action on the quill without anti-windup, "
                                           "read from the figure", "N", 0.05),),
             note="(a) While the force is clipped the quill keeps sinking and the integral keeps accumulating, far "
                  "past the weight; the excess can only be unwound by an error of the other sign, so the quill "
                  "overshoots. (b) With anti-windup the run completes, the force longer at its bound; without it "
                  "the little room cannot unwind the integral, the swings grow and the error bound stops the run."),
    Exercise("ex-ctl-pdg-sag", DOC,
             params=(Param("m_L", 5.0, **_PAYLOAD), _PD_POLE),
             answers=(Answer("sag_mm", "(a) the quill's sag at rest", "mm", 0.01,
                             shown="the chapter's text computes it for the book's numbers, with (eq-ctl-pdg-sag)"),
                      Answer("ratio", "(b) that sag over the independent-joint PD's with the same gains", "", 0.01,
                             shown="the chapter's text compares the two sags for the book's numbers")),
             note="(a) At rest K_P e = g - g_hat: only the quill errs, by m_L g0 / K_P3 with K_P3 = omega^2 B_bar33. "
                  "(b) The independent PD carries m3 g0 with the same spring, so the ratio is m_L / (m_l3 + m_L). "
                  "(c) With an exact g_hat the rest is the set point itself, for any positive K_P (La Salle); K_P "
                  "still decides how fast the arm gets there, and how far a disturbance pushes it."),
    Exercise("ex-ctl-ct-omega", DOC,
             params=(Param("m_L", 5.0, **_PAYLOAD), _SAG_MAX),
             answers=(Answer("omega_min", "(a) the smallest omega keeping the sag within the bound", "rad/s", 0.01),),
             note="(a) The sag m_L g0 / (B_hat33 omega^2) falls as 1/omega^2: omega >= sqrt(m_L g0 / (B_hat33 "
                  "sag_max)) (the rotor coupling adds a few parts in 10^4). (b) omega T stays far below "
                  "min(4 zeta, 1/zeta) = 1. (c) The torque per unit error grows as omega^2, on every joint: joint 1 "
                  "pays B_hat11 omega^2 per radian, and noise and delays are amplified as much."),
    Exercise("ex-ctl-ct-step", DOC,
             params=(Param("omega", 60.0, "rad/s", ".0f", "natural frequency of computed torque (zeta = 1)",
                           low=40.0, high=80.0, step=5.0),
                     Param("f_max", 600.0, "N", ".0f", "the quill's force bound", low=400.0, high=800.0,
                           step=50.0)),
             answers=(Answer("delta_down_mm", "(a) the largest downward step of the quill's reference", "mm", 0.01),
                      Answer("delta_up_mm", "(b) the largest upward step of the quill's reference", "mm", 0.01)),
             note="At the step's first sample the error is the step and its rate zero, so y_3 = K_P3 Delta and the "
                  "force is B_hat33 omega^2 Delta - m3_hat g0, the largest of the whole response (critically damped, "
                  "|y| falls from there). (a) Down (d3 grows): Delta <= (f_max + m3_hat g0) / (B_hat33 omega^2). "
                  "(b) Up: |Delta| <= (f_max - m3_hat g0) / (B_hat33 omega^2): the modelled weight uses part of the "
                  "force. (c) The payload is not in the model, so it does not change the commanded force."),
    Exercise("ex-ctl-no-robust", DOC,
             params=(Param("m_L", 5.0, **_PAYLOAD),
                     Param("rho", 1e-4, "m/s²", ".0e", "the negligible robust term")),
             answers=(Answer("sag_mm", "the quill's sag at the final rest", "mm", 0.01,
                             shown="the sections on PD with gravity compensation and computed torque print the same "
                                   "sag for the book's numbers (the same quill spring, B_hat33 K_P3)"),),
             note="Without w the law is PD with a constant diagonal B_hat and gravity compensation without the "
                  "payload; at rest B_hat33 K_P3 e_z carries the weight: e_z = m_L g0 / (B_hat33 K_P3)."),
    Exercise("ex-ctl-wider-layer", DOC,
             params=(Param("epsilon", 0.2, "", ".4g", "width of the boundary layer (a width of the figure's slider)",
                           choices=(0.0623, 0.092, 0.1359, 0.2)),),
             answers=(Answer("sag_mm", "the sag at rest", "mm", 0.01,
                             shown="the slider of the chapter's boundary-layer figure prints it at this width"),
                      Answer("margin", "the margin epsilon / epsilon_min to the sampling limit", "", 0.01)),
             note="The layer's gain rho lambda / epsilon falls, so the sag m_L g0 / (B_hat33 (K_P3 + rho lambda / "
                  "epsilon)) grows; in exchange the torque is smoother (lower chattering) and the layer is further "
                  "from the sampling limit."),
    Exercise("ex-ctl-slow-adaptation", DOC,
             params=(Param("K_pi", 1.0, "", ".1f", "adaptation weight of m3", low=0.2, high=1.5, step=0.1),),
             answers=(Answer("t_pred", "time the estimate needs to come within 0.25 kg of the payload", "s", 0.02),),
             note="The loop is strongly overdamped; its slow root a dominates, so the estimate's error falls as "
                  "5 e^(-a t) kg and reaches 0.25 kg at t = ln 20 / a."),
    Exercise("ex-ctl-stiffer", DOC,
             params=(Param("m_L", 10.0, "kg", ".1f", "payload the controller does not know",
                           low=5.0, high=10.0, step=0.5),
                     Param("sag_max_mm", 0.5, "mm", ".1f", "largest sag allowed at rest", low=0.3, high=1.0,
                           step=0.1)),
             answers=(Answer("kpz_min", "the smallest K_P,z keeping the sag within the bound", "s⁻²", 0.01),),
             note="K_P,z >= m_L g0 / (B_hat33 sag) from the steady-state error, raised slightly by the rotor "
                  "coupling; the gain must grow with the payload, making the loop more sensitive to noise and "
                  "delay, while the integral removes the error for any constant load."),
    Exercise("ex-ctl-sampling-limit", DOC,
             params=(Param("rho", 40.0, "m/s²", ".0f", "the robust term's magnitude", low=40.0, high=60.0,
                           step=2.0),),
             answers=(Answer("eps_min", "(a) the thinnest boundary layer the sampling allows", "", 0.01),),
             note="(a) epsilon_min = mu_max rho T / (2 - mu_max K_D T), about proportional to rho, still below 0.05: "
                  "the book's layer works. (b) Below epsilon_min the torque switches at every sample with amplitude "
                  "up to B_hat11 rho, above joint 1's bound: the run stops with an UnstableError naming tau_max."),
    Exercise("ex-ctl-integral-limit", DOC,
             params=(Param("m_L", 5.0, "kg", ".1f", "payload the controller does not know", low=2.0, high=10.0,
                           step=0.5),
                     Param("K_P", 900.0, "s⁻²", ".0f", "the panel's starting K_P"),
                     Param("K_D", 60.0, "s⁻¹", ".0f", "the panel's starting K_D")),
             answers=(Answer("routh", "(a) the largest K_I with an exact model, K_D K_P", "s⁻³", 0.01),
                      Answer("cont", "(b) the largest K_I with the payload, beta K_D K_P", "s⁻³", 0.01)),
             note="(a) Routh-Hurwitz on s^3 + K_D s^2 + K_P s + K_I: K_D K_P > K_I. (b) Only beta = B_hat33 / B33 of "
                  "the commanded acceleration arrives, so K_I < beta K_D K_P (sampling lowers it a little more). "
                  "(c) The vertical error oscillates with growing amplitude until the quill's force passes its "
                  "bound; the package's check cannot see it, since it knows only the model."),
)
