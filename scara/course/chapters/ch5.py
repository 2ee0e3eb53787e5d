"""Chapter 5's exercises as data (see :mod:`scara.course.exercises`)."""
from scara.course.exercises import Answer, Exercise, Param

DOC = "05_dynamics"

EXERCISES = (
    Exercise("ex-dyn-rotor", DOC,
             params=(Param("m_L", 5.0, "kg", ".0f", "payload on the quill", low=0.0, high=20.0, step=1.0),),
             answers=(Answer("share_pct", "share of rotor 3 (k_r3² I_m3) in B33", "%", 0.01),),
             note="B33 = m3 + k_r3² I_m3: the screw turns each m/s of the quill into k_r3 = 50 rad/s of the rotor, "
                  "and kinetic energy goes with the square of the speed, so the rotor's inertia counts 2500 times."),
    Exercise("ex-dyn-stiff", DOC,
             params=(Param("m_L", 5.0, "kg", ".0f", "payload unknown to the controller",
                           low=1.0, high=20.0, step=1.0),
                     Param("sag_mm", 2.0, "mm", ".1f", "largest sag allowed", low=0.5, high=5.0, step=0.5)),
             answers=(Answer("kp", "smallest K_P3 (m_L g0 / sag)", "N/m", 0.01),
                      Answer("sag_sim_mm", "sag after a 5 s set-point simulation with that gain", "mm", 0.01)),
             note="From the sag formula m_L g0 / K_P3 ≤ sag, K_P3 ≥ m_L g0 / sag; the simulation settles at the "
                  "allowed sag exactly."),
    Exercise("ex-dyn-fall", DOC,
             params=(Param("m_L", 5.0, "kg", ".0f", "payload (that of fig-ch5-energy)"),
                     Param("t", 0.5, "s", ".2f", "time after release", low=0.1, high=0.6, step=0.05)),
             answers=(Answer("v_inf", "terminal speed m3 g0 / F33", "m/s", 0.01),
                      Answer("tau_3", "time constant B33 / F33", "s", 0.01),
                      Answer("v_pred", "speed of the quill at the given time", "m/s", 0.01)),
             note="Joint 3 alone obeys B33 d̈3 + F33 ḋ3 = m3 g0: a first-order approach to m3 g0 / F33 with time "
                  "constant B33 / F33; the simulation differs slightly through the coupling B13 = B23."),
    Exercise("ex-dyn-weigh", DOC,
             params=(Param("m_L", 5.0, "kg", ".1f", "payload of the arm that produces the torques",
                           low=0.0, high=20.0, step=0.5),),
             answers=(Answer("mL_hat", "payload found by least squares", "kg", 0.01, absolute=True),),
             note="Stacking Y for 40 varied states gives a full column rank (13), so least squares recovers all of "
                  "π, the payload (the first entry less the quill's mass) to rounding error."),
    Exercise("ex-dyn-energy", DOC,
             params=(Param("m_L", 5.0, "kg", ".0f", "payload", low=0.0, high=20.0, step=1.0),
                     Param("w1", 1.0, "rad/s", ".1f", "initial joint-1 speed", low=0.5, high=2.0, step=0.5),
                     Param("w2", -1.0, "rad/s", ".1f", "initial joint-2 speed"),
                     Param("w4", 2.0, "rad/s", ".1f", "initial joint-4 speed", low=1.0, high=4.0, step=0.5)),
             answers=(Answer("share4_pct", "share of the friction work done at joint 4", "%", 0.1, absolute=True),
                      Answer("T1", "kinetic energy after 10 s", "J", 0.02),
                      Answer("w1_end", "joint-1 speed after 10 s", "rad/s", 0.01, absolute=True)),
             note="Joint 4's friction (F44 = 2 N m s/rad, against 5e-5 at joints 1 and 2) takes almost all the "
                  "energy; it is internal about the joint-1 axis, so the angular momentum (B q̇)_1 is conserved "
                  "and joints 1 and 2 keep turning, adjusting their rates as joint 4 slows."),
    Exercise("ex-dyn-fold", DOC,
             params=(Param("m_L", 5.0, "kg", ".0f", "payload (the slider of fig-ch5-inertia-elbow)",
                           low=0.0, high=20.0, step=1.0),),
             answers=(Answer("B11_0", "B11 stretched (ϑ2 = 0°)", "kg m²", 0.01),
                      Answer("B11_90", "B11 at a right angle (ϑ2 = -90°)", "kg m²", 0.01),
                      Answer("B11_180", "B11 folded (ϑ2 = 180°)", "kg m²", 0.01),
                      Answer("B22", "B22 (any posture)", "kg m²", 0.01)),
             note="B11 varies with cos ϑ2 by ±2 a1 (m_l2 ℓ2 + m3 a2) around its value at ±90°, B22 is constant; "
                  "ϑ1, d3 and ϑ4 appear nowhere in B (joint 1 turns the arm rigidly, d3 moves along the vertical "
                  "axis, ϑ4 turns link 4 about its own axis), so the figure needs no slider for them."),
    Exercise("ex-dyn-heavy", DOC,
             params=(Param("m_L", 20.0, "kg", ".0f", "payload, not compensated", low=10.0, high=20.0, step=1.0),
                     Param("sag_max_mm", 5.0, "mm", ".1f", "largest sag allowed", low=3.0, high=6.0, step=0.5)),
             answers=(Answer("sag_mm", "sag at rest with K_P3 = 10⁴ N/m", "mm", 0.01),
                      Answer("k_step", "smallest slider gain exponent log10 K_P3 (a multiple of 0.1) within the sag",
                             "", 0.01, absolute=True)),
             note="The sag is m_L g0 / K_P3 (the controller compensates the quill only); the gain must be at least "
                  "m_L g0 / sag_max, and the first slider value 10^(k/10) above it is the answer."),
    Exercise("ex-dyn-encoder", DOC,
             params=(Param("bits", 17.0, "", ".0f", "encoder counts per revolution, as a power of 2",
                           low=12.0, high=20.0, step=1.0),),
             answers=(Answer("step_urad", "encoder step 2π / 2^bits", "µrad", 0.005,
                             shown="the identification section states the book's encoders' resolution"),
                      Answer("rms_urad", "RMS error of a reading (uniform over ± half a step)", "µrad", 0.01),
                      Answer("speed_err", "largest error of a speed from two consecutive readings 1 ms apart",
                             "rad/s", 0.01)),
             note="A reading is off by at most half a step, uniformly, so its RMS error is step / √12; two "
                  "readings differ from the true difference by up to one step, so a speed from them errs by up "
                  "to step / T, and a second difference by up to 2 step / T²: raw readings must be filtered "
                  "before they are differentiated."),
    Exercise("ex-dyn-record", DOC,
             params=(Param("target_g", 1.0, "g", ".2f", "half-width of the 95 % interval of m3 wanted",
                           low=1.0, high=2.0, step=0.25),),
             answers=(Answer("duration_s", "record length predicted by the 1/√N law from the 40 s experiment",
                             "s", 0.02),),
             note="The interval's half-width falls like 1/√N: 40 s × (h_40 / target)² of data, h_40 the half-width "
                  "of the page's 40 s experiment; rounded up to whole periods of 10 s, the identification gives a "
                  "half-width close to the target."),
    Exercise("ex-dyn-weighing", DOC,
             params=(Param("m_L", 2.5, "kg", ".1f", "payload put on the arm of the page",
                           low=0.5, high=10.0, step=0.5),),
             answers=(Answer("payload_kg", "payload from two identifications, with and without it", "kg", 0.01,
                             absolute=True),
                      Answer("half_g", "half-width of its 95 % interval", "g", 0.02),
                      Answer("nominal_kg", "payload_from_pi of the loaded estimate (nominal quill mass)", "kg", 0.01,
                             absolute=True)),
             note="m3 = m_l3 + m_L: the difference of the two estimates of m3 is the payload; payload_from_pi "
                  "subtracts the nominal m_l3 = 10 kg, and this arm's quill differs from it."),
)
